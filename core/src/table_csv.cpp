// CSV reading and writing of a Table.
#include <cmath>
#include <limits>
#include <fstream>
#include <sstream>

#include "demcal/core/atomic_file.hpp"
#include "demcal/core/error.hpp"
#include "demcal/core/number_format.hpp"
#include "demcal/core/table.hpp"

namespace demcal {
namespace {

std::vector<std::string> split_fields(const std::string& line, char delimiter) {
  std::vector<std::string> fields;
  std::string field;
  bool quoted = false;
  for (char c : line) {
    if (c == '"') {
      quoted = !quoted;
    } else if (c == delimiter && !quoted) {
      fields.push_back(field);
      field.clear();
    } else if (c != '\r') {
      field += c;
    }
  }
  fields.push_back(field);
  for (auto& f : fields) {
    while (!f.empty() && (f.front() == ' ' || f.front() == '\t')) f.erase(f.begin());
    while (!f.empty() && (f.back() == ' ' || f.back() == '\t')) f.pop_back();
  }
  return fields;
}

// Spreadsheets save CSV in ways a plain reader trips on (a byte-order mark
// before the first name, or ';' between fields and ',' as the decimal mark
// where the locale wants it): read those, and refuse UTF-16 naming the cause.
void strip_utf8_bom(std::string& line, const std::string& path) {
  if (line.size() >= 2 && ((line[0] == '\xFF' && line[1] == '\xFE') || (line[0] == '\xFE' && line[1] == '\xFF')))
    throw Error(path + ": saved as UTF-16 (a spreadsheet's \"Unicode text\"); save it as \"CSV UTF-8\" or plain CSV");
  if (line.compare(0, 3, "\xEF\xBB\xBF") == 0) line.erase(0, 3);
}

// ';' when the header has semicolons and no commas (a spreadsheet in a
// locale with decimal commas), else ','.
char delimiter_of(const std::string& header) {
  return header.find(';') != std::string::npos && header.find(',') == std::string::npos ? ';' : ',';
}

// With ';' between fields, one ',' in a number is its decimal mark.
bool parse_number(std::string text, char delimiter, double& value) {
  if (delimiter == ';') {
    const std::size_t comma = text.find(',');
    if (comma != std::string::npos && text.find(',', comma + 1) == std::string::npos) text[comma] = '.';
  }
  return parse_double(text, value);
}

}  // namespace

Table Table::read_csv(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw Error(path + ": cannot open CSV file");
  std::string line;
  std::size_t line_number = 0;
  std::vector<std::string> header;
  char delimiter = ',';
  while (header.empty() && std::getline(in, line)) {
    ++line_number;
    if (line_number == 1) strip_utf8_bom(line, path);
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    delimiter = delimiter_of(line);
    header = split_fields(line, delimiter);
  }
  if (header.empty()) throw Error(path + ": empty CSV file (no header)");
  bool has_run = header.front() == "run";
  std::size_t first = has_run ? 1 : 0;
  for (std::size_t i = 0; i < header.size(); ++i) {
    if (header[i].empty()) throw Error(path + ": header column " + std::to_string(i + 1) + " has no name");
    for (std::size_t j = 0; j < i; ++j)
      if (header[i] == header[j]) throw Error(path + ": header names column \"" + header[i] + "\" twice");
  }

  std::vector<int> runs;
  std::vector<std::vector<double>> columns(header.size() - first);
  std::vector<std::string> statuses;
  const std::size_t none = header.size();
  std::size_t status_column = none;
  for (std::size_t i = first; i < header.size(); ++i)
    if (header[i] == "status") status_column = i;
  while (std::getline(in, line)) {
    ++line_number;
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    std::vector<std::string> fields = split_fields(line, delimiter);
    if (fields.size() != header.size())
      throw Error(path + ":" + std::to_string(line_number) + ": " + std::to_string(fields.size()) +
                  " fields, the header has " + std::to_string(header.size()) + " (fields separated by '" +
                  std::string(1, delimiter) + "', as in the header)");
    if (has_run) {
      double run = 0;
      if (!parse_number(fields[0], delimiter, run) || !std::isfinite(run) || run != std::floor(run))
        throw Error(path + ":" + std::to_string(line_number) + ": run id \"" + fields[0] + "\" is not an integer");
      if (run < 0 || run > std::numeric_limits<int>::max())
        throw Error(path + ":" + std::to_string(line_number) + ": run id \"" + fields[0] + "\" is out of range");
      runs.push_back(static_cast<int>(run));
    } else {
      runs.push_back(static_cast<int>(runs.size()) + 1);
    }
    for (std::size_t i = first; i < fields.size(); ++i) {
      if (i == status_column) {
        statuses.push_back(fields[i]);
        continue;
      }
      double value = 0;
      if (!parse_number(fields[i], delimiter, value))
        throw Error(path + ":" + std::to_string(line_number) + ": column \"" + header[i] + "\": \"" + fields[i] +
                    "\" is not a number");
      columns[i - first].push_back(value);
    }
  }
  Table table(runs);
  for (std::size_t i = first; i < header.size(); ++i)
    if (i != status_column) table.add_column(header[i], std::move(columns[i - first]));
  if (status_column != none) table.set_statuses(std::move(statuses));
  return table;
}

void Table::write_csv(const std::string& path) const {
  std::ostringstream out;
  out << "run";
  if (!statuses_.empty()) out << ",status";
  for (const auto& name : names_) out << ',' << name;
  out << '\n';
  for (std::size_t r = 0; r < rows(); ++r) {
    out << run_ids_[r];
    if (!statuses_.empty()) out << ',' << statuses_[r];
    for (const auto& column : columns_) out << ',' << format_double(column[r]);
    out << '\n';
  }
  write_file_atomically(path, out.str());
}

}  // namespace demcal
