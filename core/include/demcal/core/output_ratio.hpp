#pragma once
// An output named "A/B" is the ratio of the outputs A and B: a tensile to
// compressive strength ratio (sigma_t_MPa/sigma_u_MPa), or the dimensionless
// sigma_u_MPa/E_GPa of a calibration. It may stand wherever an output may: a
// target, a response column of an analysis or a fit, an output of the DEM in
// the loop. Its value is formed per run (per specimen), never as a ratio of
// means.
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "demcal/core/table.hpp"

namespace demcal {

struct OutputRatio {
  std::string numerator, denominator;
};

// The two parts of "A/B"; nothing when `name` holds no '/'. "A/", "/B" and
// "A/B/C" are Errors naming `where`.
std::optional<OutputRatio> parse_output_ratio(const std::string& name, const std::string& where);

// For each ratio name in `names` that `table` lacks, adds the column A / B
// row by row; an Error naming `where` when A or B is not a column.
void add_ratio_columns(Table& table, const std::vector<std::string>& names, const std::string& where);

// The value of `name` (an output, or a ratio of two) in `values`; false when
// it, or a part of it, is missing.
bool output_value(const std::map<std::string, double>& values, const std::string& name, double& value);

}  // namespace demcal
