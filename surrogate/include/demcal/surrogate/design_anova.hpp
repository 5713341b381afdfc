#pragma once
// ANOVA of a designed experiment as a general linear model with categorical
// factors, fitted by least squares. Each term's SS is its adjusted (Type III)
// sum of squares, the drop in fit when the term leaves the model, so collapsed
// columns with unequal level counts (32/16/16) come out as Minitab's GLM
// prints them; for a proportional-frequency design it equals the textbook
// sum_i n_i (k_i - ybar)^2.
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "demcal/surrogate/anova_table.hpp"

namespace demcal::surrogate {

struct DesignAnovaOptions {
  // Column whose SS is the error (the textbook way with a blank column);
  // empty: the residual of the model with every term (Minitab's GLM).
  std::string error_column;
  std::vector<std::string> pool;  // terms pooled into the error by name
  double pool_below_f = 0.0;      // also pool, smallest F first, while F < this (0: off)
};

struct DesignAnova {
  std::string response;
  std::vector<AnovaRow> terms;  // in the order given; pooled ones flagged
  AnovaRow error;               // source "Error" (residual, the blank column, plus pooled terms)
  AnovaRow total;
  // With a blank column as the error: the model's residual, which is then in
  // no row of the test (shown so the table adds up); df 0 otherwise.
  AnovaRow unassigned;
  std::string error_description;
  double r2 = 0.0;              // of the model with every term
};

// `columns`: runs x (terms, and the error column when it is not among them),
// named by `names`; `terms`: the names that are model terms.
DesignAnova design_anova(const std::vector<std::string>& names, const Eigen::MatrixXd& columns,
                         const Eigen::VectorXd& y, const std::vector<std::string>& terms,
                         const std::string& response, const DesignAnovaOptions& options);

}  // namespace demcal::surrogate
