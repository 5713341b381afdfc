#pragma once
// Shortest text that reads back to the same double (round trip), so CSV files
// written by one stage give the next stage bit-identical numbers.
#include <string>
#include <string_view>
#include <utility>

namespace demcal {

std::string format_double(double value);

// Parses a whole field as a double ("nan", "inf" and an empty field are
// accepted; an empty field reads as NaN). Returns false on anything else.
bool parse_double(std::string_view text, double& value);

// "NAME=VALUE" of a command-line option; throws "<option> "text": expected
// NAME=VALUE with a number" when the name or the number is missing.
std::pair<std::string, double> parse_name_value(const std::string& text, const std::string& option);

}  // namespace demcal
