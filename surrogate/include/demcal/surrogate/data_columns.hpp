#pragma once
// Picks the named columns of a data table for analysis and fitting, with
// one-line errors that name the file, the column and what is wrong.
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "demcal/core/table.hpp"

namespace demcal::surrogate {

// "A,B,,C" -> {"A", "B", "C"}; duplicates are an error naming `option`.
std::vector<std::string> split_names(const std::string& text, const std::string& option);

// Rows x names matrix. Throws "<origin>: no column "X" (columns: ...)" for a
// missing column and "<origin>: column X, run R: not a number" for NaN/inf.
Eigen::MatrixXd select_columns(const Table& table, const std::vector<std::string>& names, const std::string& origin);

// Throws "<origin>: column X is constant (every run has V); <why>" when a
// column does not vary.
void require_varying(const Eigen::MatrixXd& columns, const std::vector<std::string>& names,
                     const std::string& origin, const std::string& why);

// Sorted distinct values of one column.
std::vector<double> distinct_values(const Eigen::VectorXd& column);

}  // namespace demcal::surrogate
