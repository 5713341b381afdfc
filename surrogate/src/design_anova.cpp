#include "demcal/surrogate/design_anova.hpp"

#include <algorithm>
#include <map>

#include "demcal/core/error.hpp"
#include "demcal/surrogate/data_columns.hpp"
#include "demcal/surrogate/least_squares.hpp"

namespace demcal::surrogate {

namespace {

// Sum-to-zero (effect) coding: a factor with L levels gives L-1 columns; the
// last level is -1 in all of them.
Eigen::MatrixXd effect_columns(const Eigen::VectorXd& column, const std::string& name) {
  std::vector<double> levels = distinct_values(column);
  if (levels.size() < 2) throw Error("anova: factor " + name + " has a single level; it cannot be a term");
  if (2 * levels.size() > static_cast<std::size_t>(column.size()))
    throw Error("anova: factor " + name + " has " + std::to_string(levels.size()) + " distinct values in " +
                std::to_string(column.size()) + " runs; it is not a categorical design column");
  Eigen::MatrixXd coded = Eigen::MatrixXd::Zero(column.size(), static_cast<Eigen::Index>(levels.size()) - 1);
  for (Eigen::Index i = 0; i < column.size(); ++i) {
    auto at = std::lower_bound(levels.begin(), levels.end(), column(i)) - levels.begin();
    if (at + 1 == static_cast<long>(levels.size()))
      coded.row(i).setConstant(-1.0);
    else
      coded(i, at) = 1.0;
  }
  return coded;
}

struct TermBlock {
  std::string name;
  Eigen::MatrixXd columns;
};

Eigen::MatrixXd model_matrix(const std::vector<TermBlock>& blocks, Eigen::Index rows, int skip) {
  Eigen::Index width = 1;
  for (int b = 0; b < static_cast<int>(blocks.size()); ++b)
    if (b != skip) width += blocks[b].columns.cols();
  Eigen::MatrixXd X(rows, width);
  X.col(0).setOnes();
  Eigen::Index at = 1;
  for (int b = 0; b < static_cast<int>(blocks.size()); ++b) {
    if (b == skip) continue;
    X.middleCols(at, blocks[b].columns.cols()) = blocks[b].columns;
    at += blocks[b].columns.cols();
  }
  return X;
}

}  // namespace

DesignAnova design_anova(const std::vector<std::string>& names, const Eigen::MatrixXd& columns,
                         const Eigen::VectorXd& y, const std::vector<std::string>& terms,
                         const std::string& response, const DesignAnovaOptions& options) {
  auto index_of = [&](const std::string& name) {
    auto it = std::find(names.begin(), names.end(), name);
    if (it == names.end()) throw Error("anova: no column \"" + name + "\"");
    return static_cast<Eigen::Index>(it - names.begin());
  };
  const Eigen::Index n = y.size();
  std::vector<TermBlock> blocks;
  for (const std::string& term : terms) {
    if (term == options.error_column) continue;
    blocks.push_back({term, effect_columns(columns.col(index_of(term)), term)});
  }
  if (blocks.empty()) throw Error("anova: no terms left (the error column cannot be the only factor)");
  int error_block = -1;
  if (!options.error_column.empty()) {
    error_block = static_cast<int>(blocks.size());
    blocks.push_back({options.error_column, effect_columns(columns.col(index_of(options.error_column)), options.error_column)});
  }

  Eigen::MatrixXd X = model_matrix(blocks, n, -1);
  if (X.cols() > n)
    throw Error("anova: " + std::to_string(X.cols()) + " model coefficients but only " + std::to_string(n) +
                " runs; use fewer terms");
  LeastSquaresFit full = least_squares(X, y);
  if (full.rank < X.cols()) {
    // Name the first term whose columns depend on earlier terms.
    std::vector<int> dependent = dependent_columns(X);
    Eigen::Index at = 1;
    for (const TermBlock& b : blocks) {
      bool hit = false;
      for (int d : dependent) hit = hit || (d >= at && d < at + b.columns.cols());
      if (hit) throw Error("anova: term " + b.name + " is aliased with earlier terms in this design; drop it or one of them");
      at += b.columns.cols();
    }
    throw Error("anova: the model matrix is rank deficient");
  }

  DesignAnova result;
  result.response = response;
  double mean = y.mean();
  result.total.source = "Total";
  result.total.ss = (y.array() - mean).square().sum();
  result.total.df = static_cast<int>(n) - 1;
  result.r2 = result.total.ss > 0 ? 1.0 - full.sse / result.total.ss : 0.0;

  std::vector<AnovaRow> rows;
  for (int b = 0; b < static_cast<int>(blocks.size()); ++b) {
    AnovaRow row;
    row.source = blocks[b].name;
    row.ss = std::max(0.0, residual_sum_of_squares(model_matrix(blocks, n, b), y) - full.sse);
    row.df = static_cast<int>(blocks[b].columns.cols());
    rows.push_back(row);
  }

  AnovaRow error;
  error.source = "Error";
  if (error_block >= 0) {
    error.ss = rows[error_block].ss;
    error.df = rows[error_block].df;
    result.error_description = "SS of column " + options.error_column;
    rows.pop_back();
    result.unassigned = AnovaRow{"Residual (not in the error)", full.sse, full.residual_df};
  } else {
    error.ss = full.sse;
    error.df = full.residual_df;
    result.error_description = "residual";
  }

  for (const std::string& name : options.pool) {
    auto it = std::find_if(rows.begin(), rows.end(), [&](const AnovaRow& r) { return r.source == name; });
    if (it == rows.end()) throw Error("anova: --pool names \"" + name + "\", which is not a term");
    it->pooled = true;
    error.ss += it->ss;
    error.df += it->df;
  }
  auto unpooled = [&]() { return std::count_if(rows.begin(), rows.end(), [](const AnovaRow& r) { return !r.pooled; }); };
  if (options.pool_below_f > 0) {
    while (unpooled() > 1) {
      error.ms = error.df > 0 ? error.ss / error.df : 0.0;
      AnovaRow* weakest = nullptr;
      double weakest_f = options.pool_below_f;
      for (AnovaRow& r : rows) {
        if (r.pooled || error.df <= 0 || error.ms <= 0) continue;
        double f = (r.ss / r.df) / error.ms;
        if (f < weakest_f) {
          weakest_f = f;
          weakest = &r;
        }
      }
      if (!weakest) break;
      weakest->pooled = true;
      error.ss += weakest->ss;
      error.df += weakest->df;
    }
  }
  bool any_pooled = unpooled() < static_cast<long>(rows.size());
  if (any_pooled) result.error_description += " + pooled terms";
  if (error.df <= 0)
    throw Error("anova: the error has no degrees of freedom (saturated design); name a blank column with "
                "--error column:NAME or pool small terms");
  error.ms = error.ss / error.df;
  for (AnovaRow& r : rows) {
    if (r.pooled)
      r.ms = r.ss / r.df;
    else
      complete_row(r, error);
  }
  result.terms = rows;
  result.error = error;
  return result;
}

}  // namespace demcal::surrogate
