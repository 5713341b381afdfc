#include "demcal/surrogate/data_columns.hpp"

#include <algorithm>
#include <cmath>
#include <set>
#include <sstream>

#include "demcal/core/error.hpp"
#include "demcal/core/number_format.hpp"

namespace demcal::surrogate {

std::vector<std::string> split_names(const std::string& text, const std::string& option) {
  std::vector<std::string> names;
  std::set<std::string> seen;
  std::stringstream stream(text);
  for (std::string part; std::getline(stream, part, ',');) {
    if (part.empty()) continue;
    if (!seen.insert(part).second) throw Error(option + ": \"" + part + "\" is listed twice");
    names.push_back(part);
  }
  return names;
}

Eigen::MatrixXd select_columns(const Table& table, const std::vector<std::string>& names, const std::string& origin) {
  Eigen::MatrixXd values(static_cast<Eigen::Index>(table.rows()), static_cast<Eigen::Index>(names.size()));
  for (std::size_t j = 0; j < names.size(); ++j) {
    if (!table.has_column(names[j])) {
      std::string list;
      for (const std::string& n : table.names()) list += (list.empty() ? "" : ", ") + n;
      throw Error(origin + ": no column \"" + names[j] + "\" (columns: " + list + ")");
    }
    const std::vector<double>& column = table.column(names[j]);
    for (std::size_t i = 0; i < column.size(); ++i) {
      if (!std::isfinite(column[i]))
        throw Error(origin + ": column " + names[j] + ", run " + std::to_string(table.run_ids()[i]) +
                    ": not a number (a failed DEM point? drop or rerun it)");
      values(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) = column[i];
    }
  }
  return values;
}

void require_varying(const Eigen::MatrixXd& columns, const std::vector<std::string>& names,
                     const std::string& origin, const std::string& why) {
  for (Eigen::Index j = 0; j < columns.cols(); ++j) {
    if (columns.rows() == 0) continue;
    if (columns.col(j).maxCoeff() == columns.col(j).minCoeff())
      throw Error(origin + ": column " + names[static_cast<std::size_t>(j)] + " is constant (every run has " +
                  format_double(columns(0, j)) + "); " + why);
  }
}

std::vector<double> distinct_values(const Eigen::VectorXd& column) {
  std::vector<double> values(column.data(), column.data() + column.size());
  std::sort(values.begin(), values.end());
  values.erase(std::unique(values.begin(), values.end()), values.end());
  return values;
}

}  // namespace demcal::surrogate
