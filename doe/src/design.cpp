#include "demcal/doe/design.hpp"

#include "demcal/core/error.hpp"

namespace demcal::doe {

std::size_t Design::factors() const {
  std::size_t count = 0;
  for (std::size_t j = 0; j < width(); ++j)
    if (j >= blank.size() || !blank[j]) ++count;
  return count;
}

double coded_level(int index, int levels) {
  if (levels < 2) throw Error("a design column needs at least two levels");
  return -1.0 + 2.0 * static_cast<double>(index) / static_cast<double>(levels - 1);
}

Design make_design(std::string kind, Eigen::MatrixXd coded, int levels, Coding coding) {
  Design design;
  std::size_t width = static_cast<std::size_t>(coded.cols());
  design.kind = std::move(kind);
  design.coded = std::move(coded);
  design.coding = coding;
  design.columns = default_names(width);
  design.levels.assign(width, levels);
  design.blank.assign(width, false);
  return design;
}

Design design_from_levels(const LevelMatrix& level_indices, const std::vector<int>& levels_per_column,
                          std::string kind, std::string description) {
  Design design;
  design.kind = std::move(kind);
  design.description = std::move(description);
  design.coded.resize(level_indices.rows(), level_indices.cols());
  for (Eigen::Index j = 0; j < level_indices.cols(); ++j)
    for (Eigen::Index i = 0; i < level_indices.rows(); ++i)
      design.coded(i, j) = coded_level(level_indices(i, j), levels_per_column[static_cast<std::size_t>(j)]);
  design.levels = levels_per_column;
  design.blank.assign(levels_per_column.size(), false);
  design.columns = default_names(levels_per_column.size());
  return design;
}

std::vector<std::string> default_names(std::size_t count) {
  std::vector<std::string> names;
  for (std::size_t i = 0; i < count; ++i) names.push_back("x" + std::to_string(i + 1));
  return names;
}

}  // namespace demcal::doe
