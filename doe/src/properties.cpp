#include "demcal/doe/properties.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>

#include "demcal/core/number_format.hpp"
#include "demcal/doe/space_filling.hpp"

namespace demcal::doe {
namespace {

constexpr std::size_t kMaxDiscreteLevels = 12;

// Index of each entry's level in `levels` (values equal within 1e-9).
std::vector<int> level_indices(const Eigen::VectorXd& column, const ColumnLevels& levels) {
  std::vector<int> index(static_cast<std::size_t>(column.size()));
  for (Eigen::Index i = 0; i < column.size(); ++i) {
    auto it = std::lower_bound(levels.values.begin(), levels.values.end(), column(i) - 1e-9);
    index[static_cast<std::size_t>(i)] = static_cast<int>(it - levels.values.begin());
  }
  return index;
}

ColumnLevels column_levels(const Eigen::VectorXd& column) {
  std::vector<double> values(column.data(), column.data() + column.size());
  std::sort(values.begin(), values.end());
  ColumnLevels levels;
  for (double v : values) {
    if (levels.values.empty() || v - levels.values.back() > 1e-9) {
      levels.values.push_back(v);
      levels.counts.push_back(1);
    } else {
      ++levels.counts.back();
    }
  }
  if (levels.values.size() > kMaxDiscreteLevels) levels = ColumnLevels{};
  return levels;
}

std::string fixed(double value, int digits) {
  std::ostringstream out;
  out.setf(std::ios::fixed);
  out.precision(digits);
  out << value;
  return out.str();
}

}  // namespace

DesignProperties analyse(const Design& design) {
  DesignProperties p;
  const Eigen::MatrixXd& x = design.coded;
  p.runs = design.runs();
  p.columns = design.width();
  p.discrete = true;
  for (Eigen::Index j = 0; j < x.cols(); ++j) {
    p.levels.push_back(column_levels(x.col(j)));
    if (p.levels.back().values.empty()) p.discrete = false;
  }

  if (p.discrete) {
    p.strength_two = true;
    p.proportional_frequencies = true;
    std::vector<std::vector<int>> index;
    for (Eigen::Index j = 0; j < x.cols(); ++j) index.push_back(level_indices(x.col(j), p.levels[static_cast<std::size_t>(j)]));
    for (std::size_t a = 0; a < p.columns; ++a)
      for (std::size_t b = a + 1; b < p.columns; ++b) {
        const ColumnLevels& la = p.levels[a];
        const ColumnLevels& lb = p.levels[b];
        std::vector<long> joint(la.values.size() * lb.values.size(), 0);
        for (std::size_t r = 0; r < p.runs; ++r)
          ++joint[static_cast<std::size_t>(index[a][r]) * lb.values.size() + static_cast<std::size_t>(index[b][r])];
        bool proportional = true;
        bool balanced = true;
        for (std::size_t u = 0; u < la.values.size(); ++u)
          for (std::size_t v = 0; v < lb.values.size(); ++v) {
            long n_uv = joint[u * lb.values.size() + v];
            if (n_uv * static_cast<long>(p.runs) != static_cast<long>(la.counts[u]) * lb.counts[v]) proportional = false;
            if (n_uv * static_cast<long>(la.values.size() * lb.values.size()) != static_cast<long>(p.runs)) balanced = false;
          }
        if (!proportional) {
          p.proportional_frequencies = false;
          p.non_proportional_pairs.emplace_back(static_cast<int>(a), static_cast<int>(b));
        }
        if (!balanced) p.strength_two = false;
      }
  }

  std::map<std::vector<double>, int> seen;
  for (Eigen::Index i = 0; i < x.rows(); ++i) {
    std::vector<double> row(static_cast<std::size_t>(x.cols()));
    for (Eigen::Index j = 0; j < x.cols(); ++j) row[static_cast<std::size_t>(j)] = std::round(x(i, j) * 1e9) / 1e9;
    if (seen[row]++ > 0) ++p.duplicate_runs;
  }

  Eigen::MatrixXd scaled = x;
  for (Eigen::Index j = 0; j < x.cols(); ++j) {
    double low = x.col(j).minCoeff(), high = x.col(j).maxCoeff();
    if (high > low) scaled.col(j) = (x.col(j).array() - low) / (high - low);
    else scaled.col(j).setZero();
  }
  if (p.runs >= 2) {
    p.min_distance = min_distance(scaled);
    p.phi_p = p.min_distance > 0 ? doe::phi_p(scaled, 10.0) : INFINITY;
  }

  for (Eigen::Index a = 0; a < x.cols(); ++a)
    for (Eigen::Index b = a + 1; b < x.cols(); ++b) {
      Eigen::VectorXd u = x.col(a).array() - x.col(a).mean();
      Eigen::VectorXd v = x.col(b).array() - x.col(b).mean();
      double denominator = u.norm() * v.norm();
      double r = denominator > 0 ? std::abs(u.dot(v)) / denominator : 0.0;
      if (r > p.max_abs_correlation + 1e-15 || p.max_correlation_pair.first < 0) {
        p.max_abs_correlation = r;
        p.max_correlation_pair = {static_cast<int>(a), static_cast<int>(b)};
      }
    }
  return p;
}

std::string properties_markdown(const Design& design, const DesignProperties& p) {
  std::ostringstream out;
  out << "## Design: " << design.description << "\n\n";
  out << "- runs: " << p.runs << ", columns: " << p.columns << " (" << design.factors() << " factors";
  if (design.factors() < p.columns) out << ", " << p.columns - design.factors() << " blank";
  out << ")\n";
  if (p.discrete) {
    out << "- strength 2 (every pair of columns holds all level combinations equally often): "
        << (p.strength_two ? "yes" : "no") << "\n";
    out << "- proportional frequencies in every pair of columns (main effects orthogonal): "
        << (p.proportional_frequencies ? "yes" : "no");
    if (!p.proportional_frequencies) {
      out << ", fails for";
      std::size_t shown = 0;
      for (auto [a, b] : p.non_proportional_pairs) {
        if (shown++ == 8) {
          out << " ...";
          break;
        }
        out << " (" << design.columns[static_cast<std::size_t>(a)] << ", " << design.columns[static_cast<std::size_t>(b)] << ")";
      }
    }
    out << "\n";
  }
  out << "- duplicated runs: " << p.duplicate_runs << "\n";
  out << "- max |correlation| between columns: " << fixed(p.max_abs_correlation, 4);
  if (p.max_correlation_pair.first >= 0)
    out << " (" << design.columns[static_cast<std::size_t>(p.max_correlation_pair.first)] << ", "
        << design.columns[static_cast<std::size_t>(p.max_correlation_pair.second)] << ")";
  out << "\n";
  out << "- min pairwise distance (columns scaled to [0, 1]): " << fixed(p.min_distance, 4) << ", phi_10: "
      << (std::isfinite(p.phi_p) ? fixed(p.phi_p, 4) : std::string("inf (duplicated runs)")) << "\n\n";

  out << "| column | levels (coded) | runs per level |\n|---|---|---|\n";
  for (std::size_t j = 0; j < p.columns; ++j) {
    const ColumnLevels& l = p.levels[j];
    out << "| " << design.columns[j] << (design.blank[j] ? " (blank)" : "") << " | ";
    if (l.values.empty()) {
      out << "continuous (more than 12 distinct values) | - |\n";
      continue;
    }
    for (std::size_t k = 0; k < l.values.size(); ++k) out << (k ? ", " : "") << format_double(std::round(l.values[k] * 1e6) / 1e6);
    out << " | ";
    for (std::size_t k = 0; k < l.counts.size(); ++k) out << (k ? "/" : "") << l.counts[k];
    out << " |\n";
  }
  return out.str();
}

}  // namespace demcal::doe
