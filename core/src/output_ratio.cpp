#include "demcal/core/output_ratio.hpp"

#include "demcal/core/error.hpp"

namespace demcal {

std::optional<OutputRatio> parse_output_ratio(const std::string& name, const std::string& where) {
  const std::size_t slash = name.find('/');
  if (slash == std::string::npos) return std::nullopt;
  OutputRatio ratio{name.substr(0, slash), name.substr(slash + 1)};
  if (ratio.numerator.empty() || ratio.denominator.empty() || ratio.denominator.find('/') != std::string::npos)
    throw Error(where + ": \"" + name + "\" is not an output or a ratio A/B of two outputs");
  return ratio;
}

void add_ratio_columns(Table& table, const std::vector<std::string>& names, const std::string& where) {
  for (const std::string& name : names) {
    if (table.has_column(name)) continue;
    const std::optional<OutputRatio> ratio = parse_output_ratio(name, where);
    if (!ratio) continue;  // a plain name: the caller reports it missing as it always did
    for (const std::string& part : {ratio->numerator, ratio->denominator})
      if (!table.has_column(part))
        throw Error(where + ": " + name + ": no column \"" + part + "\" to form the ratio from");
    const std::vector<double>& a = table.column(ratio->numerator);
    const std::vector<double>& b = table.column(ratio->denominator);
    std::vector<double> values(table.rows());
    for (std::size_t i = 0; i < values.size(); ++i) values[i] = a[i] / b[i];
    table.add_column(name, std::move(values));
  }
}

bool output_value(const std::map<std::string, double>& values, const std::string& name, double& value) {
  auto it = values.find(name);
  if (it != values.end()) {
    value = it->second;
    return true;
  }
  const std::optional<OutputRatio> ratio = parse_output_ratio(name, name);
  if (!ratio) return false;
  auto a = values.find(ratio->numerator), b = values.find(ratio->denominator);
  if (a == values.end() || b == values.end()) return false;
  value = a->second / b->second;
  return true;
}

}  // namespace demcal
