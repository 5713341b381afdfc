#include "demcal/dem/spatial_order.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "demcal/core/error.hpp"

namespace demcal::dem {

std::uint64_t hilbert_index(std::uint32_t cx, std::uint32_t cy) {
  // The classic bit-by-bit walk (Hamilton's xy2d): at each level, the
  // quadrant gives two bits and the frame is rotated for the next level.
  constexpr std::uint32_t side = 1u << 16;
  std::uint64_t d = 0;
  for (std::uint32_t s = side / 2; s > 0; s /= 2) {
    const std::uint32_t rx = (cx & s) ? 1 : 0, ry = (cy & s) ? 1 : 0;
    d += static_cast<std::uint64_t>(s) * s * ((3 * rx) ^ ry);
    if (ry == 0) {
      if (rx == 1) {
        cx = side - 1 - cx;
        cy = side - 1 - cy;
      }
      std::swap(cx, cy);
    }
  }
  return d;
}

std::vector<std::size_t> hilbert_order(const std::vector<double>& x, const std::vector<double>& y) {
  if (x.size() != y.size()) throw Error("hilbert_order: x and y differ in length");
  std::vector<std::size_t> order(x.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  if (x.empty()) return order;
  const auto [xmin, xmax] = std::minmax_element(x.begin(), x.end());
  const auto [ymin, ymax] = std::minmax_element(y.begin(), y.end());
  // One square box, so the curve's cells are square in space.
  const double span = std::max(*xmax - *xmin, *ymax - *ymin);
  if (!std::isfinite(span)) throw Error("hilbert_order: a position is not finite");
  const double to_cell = span > 0 ? 65535.0 / span : 0.0;
  std::vector<std::uint64_t> key(x.size());
  for (std::size_t k = 0; k < x.size(); ++k)
    key[k] = hilbert_index(static_cast<std::uint32_t>((x[k] - *xmin) * to_cell),
                           static_cast<std::uint32_t>((y[k] - *ymin) * to_cell));
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return key[a] < key[b]; });
  return order;
}

}  // namespace demcal::dem
