#pragma once
// Independent checks of orthogonal-array properties for the tests (they do not
// reuse doe/properties.cpp, which is itself under test).
#include <map>
#include <utility>

#include "demcal/doe/design.hpp"

namespace demcal::doe::testing {

// Every pair of columns holds every pair of levels equally often.
inline bool is_strength_two(const LevelMatrix& a) {
  const Eigen::Index n = a.rows();
  for (Eigen::Index i = 0; i < a.cols(); ++i)
    for (Eigen::Index j = i + 1; j < a.cols(); ++j) {
      std::map<std::pair<int, int>, int> count;
      int si = a.col(i).maxCoeff() + 1, sj = a.col(j).maxCoeff() + 1;
      for (Eigen::Index r = 0; r < n; ++r) ++count[{a(r, i), a(r, j)}];
      if (static_cast<int>(count.size()) != si * sj) return false;
      for (auto& [pair, c] : count)
        if (c * si * sj != n) return false;
    }
  return true;
}

// n_uv * N == n_u * n_v for every pair of columns and levels.
inline bool has_proportional_frequencies(const Eigen::MatrixXd& x) {
  const Eigen::Index n = x.rows();
  for (Eigen::Index i = 0; i < x.cols(); ++i)
    for (Eigen::Index j = i + 1; j < x.cols(); ++j) {
      std::map<double, int> ni, nj;
      std::map<std::pair<double, double>, int> nij;
      for (Eigen::Index r = 0; r < n; ++r) {
        ++ni[x(r, i)];
        ++nj[x(r, j)];
        ++nij[{x(r, i), x(r, j)}];
      }
      for (auto& [u, cu] : ni)
        for (auto& [v, cv] : nj) {
          auto it = nij.find({u, v});
          int c = it == nij.end() ? 0 : it->second;
          if (static_cast<long>(c) * n != static_cast<long>(cu) * cv) return false;
        }
    }
  return true;
}

}  // namespace demcal::doe::testing
