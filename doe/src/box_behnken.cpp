#include <vector>

#include "demcal/core/error.hpp"
#include "demcal/doe/response_surface.hpp"

namespace demcal::doe {
namespace {

// Blocks of factors (0-based) whose 2^b factorials make up the design.
std::vector<std::vector<int>> blocks_for(int factors) {
  std::vector<std::vector<int>> blocks;
  if (factors <= 5) {
    for (int i = 0; i < factors; ++i)
      for (int j = i + 1; j < factors; ++j) blocks.push_back({i, j});
  } else if (factors == 6) {
    blocks = {{0, 1, 3}, {1, 2, 4}, {2, 3, 5}, {0, 3, 4}, {1, 4, 5}, {0, 2, 5}};
  } else {
    blocks = {{0, 1, 3}, {1, 2, 4}, {2, 3, 5}, {3, 4, 6}, {0, 4, 5}, {1, 5, 6}, {0, 2, 6}};
  }
  return blocks;
}

}  // namespace

int bbd_default_center(int factors) {
  static const int table[] = {3, 3, 6, 6, 6};
  if (factors < 3 || factors > 7) throw Error("bbd: Box-Behnken designs need 3..7 factors (got " + std::to_string(factors) + ")");
  return table[factors - 3];
}

Design box_behnken(int factors, int center) {
  int default_center = bbd_default_center(factors);
  if (center < 0) center = default_center;
  std::vector<std::vector<int>> blocks = blocks_for(factors);
  int per_block = 1 << static_cast<int>(blocks.front().size());
  int runs = static_cast<int>(blocks.size()) * per_block + center;
  Eigen::MatrixXd coded = Eigen::MatrixXd::Zero(runs, factors);
  int r = 0;
  for (const auto& block : blocks)
    for (int corner = 0; corner < per_block; ++corner, ++r)
      for (std::size_t b = 0; b < block.size(); ++b) coded(r, block[b]) = (corner >> b) & 1 ? 1.0 : -1.0;

  Design design = make_design("bbd", std::move(coded), 3);
  design.description = "Box-Behnken, " + std::to_string(factors) + " factors, " + std::to_string(blocks.size()) +
                       " blocks of " + std::to_string(blocks.front().size()) + ", " + std::to_string(center) +
                       " centre points, " + std::to_string(runs) + " runs";
  design.settings["center_points"] = std::to_string(center);
  design.settings["blocks"] = std::to_string(blocks.size());
  return design;
}

}  // namespace demcal::doe
