// The Hilbert order genesis numbers disks by: checked against the curve's
// defining properties, not against a stored sequence.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <set>
#include <vector>

#include "demcal/core/rng.hpp"
#include "demcal/dem/genesis.hpp"
#include "demcal/dem/spatial_order.hpp"

using namespace demcal::dem;

TEST(SpatialOrder, TheFirstCellsOfTheCurveFillACornerSquareAndEachStepMovesOneCell) {
  // The first 4^k indices of a Hilbert curve visit every cell of the 2^k x
  // 2^k corner square once, and consecutive indices are edge neighbours.
  const std::uint32_t side = 64;
  std::vector<std::pair<std::uint64_t, std::pair<int, int>>> cells;
  for (std::uint32_t cx = 0; cx < side; ++cx)
    for (std::uint32_t cy = 0; cy < side; ++cy) cells.push_back({hilbert_index(cx, cy), {int(cx), int(cy)}});
  std::sort(cells.begin(), cells.end());
  for (std::size_t d = 0; d < cells.size(); ++d) ASSERT_EQ(cells[d].first, d) << "index missing or repeated";
  for (std::size_t d = 1; d < cells.size(); ++d) {
    const int step = std::abs(cells[d].second.first - cells[d - 1].second.first) +
                     std::abs(cells[d].second.second - cells[d - 1].second.second);
    ASSERT_EQ(step, 1) << "between indices " << d - 1 << " and " << d;
  }
  // The whole order-16 grid is one curve: its far corners are its ends' neighbourhood.
  EXPECT_EQ(hilbert_index(0, 0), 0u);
  EXPECT_EQ(hilbert_index(65535, 0), (std::uint64_t{1} << 32) - 1);
}

TEST(SpatialOrder, OrderIsAPermutationThatKeepsNearPointsNear) {
  demcal::Rng rng(7, 1);
  std::vector<double> x(5000), y(5000);
  for (std::size_t k = 0; k < x.size(); ++k) {
    x[k] = rng.uniform(0.0, 0.05);
    y[k] = rng.uniform(0.0, 0.1);
  }
  const std::vector<std::size_t> order = hilbert_order(x, y);
  std::set<std::size_t> seen(order.begin(), order.end());
  ASSERT_EQ(seen.size(), x.size());
  ASSERT_EQ(*seen.rbegin(), x.size() - 1);
  // Mean distance between consecutive points: in random order about a third
  // of the box; along the curve about the spacing of the points (box side /
  // sqrt(n) = 1e-3 m here).
  double along = 0, as_given = 0;
  for (std::size_t k = 1; k < x.size(); ++k) {
    along += std::hypot(x[order[k]] - x[order[k - 1]], y[order[k]] - y[order[k - 1]]);
    as_given += std::hypot(x[k] - x[k - 1], y[k] - y[k - 1]);
  }
  along /= double(x.size() - 1);
  as_given /= double(x.size() - 1);
  EXPECT_LT(along, 2e-3);
  EXPECT_GT(as_given, 2e-2);
  // Ties keep their input order.
  const std::vector<std::size_t> same = hilbert_order({1.0, 1.0, 0.0}, {2.0, 2.0, 0.0});
  EXPECT_EQ(same, (std::vector<std::size_t>{2, 0, 1}));
}

TEST(SpatialOrder, GenesisNumbersItsDisksAlongTheCurve) {
  SpecimenSpec spec;
  spec.width_m = 0.02;
  spec.height_m = 0.04;
  spec.radius_min_m = 0.4e-3;
  spec.radius_max_m = 0.6e-3;
  spec.porosity = 0.16;
  const Specimen s = pack_specimen(spec);
  const std::vector<std::size_t> order = hilbert_order(s.x, s.y);
  for (std::size_t k = 0; k < order.size(); ++k) ASSERT_EQ(order[k], k) << "disk " << k << " is out of Hilbert order";
}
