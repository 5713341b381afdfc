#pragma once
// The published tables the surrogate tests run on (shipped in data/literature).
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "demcal/core/table.hpp"
#include "demcal/surrogate/data_columns.hpp"

namespace demcal::test {

inline std::string literature(const std::string& file) {
  return std::string(DEMCAL_SOURCE_DIR) + "/data/literature/" + file;
}

inline const std::vector<std::string>& l64_columns() {
  static const std::vector<std::string> columns = {
      "Ec_GPa", "kn_ks", "pb_sigma_c_MPa", "pb_tau_c_MPa", "mu", "Ec_g_GPa", "kn_ks_g", "mu_g",
      "Ec_j_GPa", "kn_ks_j", "pb_sigma_c_j_MPa", "pb_tau_c_j_MPa", "mu_j", "null_column"};
  return columns;
}

struct Fixture {
  Table table;
  Eigen::MatrixXd X;
  Eigen::VectorXd y;
};

inline Fixture load_fixture(const std::string& file, const std::vector<std::string>& x, const std::string& y) {
  Fixture f{Table::read_csv(literature(file)), {}, {}};
  f.X = surrogate::select_columns(f.table, x, file);
  f.y = surrogate::select_columns(f.table, {y}, file).col(0);
  return f;
}

}  // namespace demcal::test
