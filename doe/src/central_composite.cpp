#include <cmath>
#include <cstdlib>

#include "demcal/core/error.hpp"
#include "demcal/core/number_format.hpp"
#include "demcal/doe/response_surface.hpp"

namespace demcal::doe {

int ccd_default_center(int factors) {
  static const int table[] = {5, 6, 7, 10, 15, 21, 28};
  if (factors < 2 || factors > 8) throw Error("ccd: default centre points are known for 2..8 factors; give --center");
  return table[factors - 2];
}

double ccd_alpha(const std::string& choice, int factors, int center) {
  double cube = std::pow(2.0, factors);
  if (choice == "rotatable") return std::pow(cube, 0.25);
  if (choice == "face") return 1.0;
  if (choice == "orthogonal") {
    double root = std::sqrt(cube + 2.0 * factors + center) - std::sqrt(cube);
    return std::pow(root * root * cube / 4.0, 0.25);
  }
  double value = 0;
  if (!parse_double(choice, value) || !std::isfinite(value))
    throw Error("ccd: --alpha \"" + choice + "\": expected rotatable, orthogonal, face or a positive number");
  if (value <= 0) throw Error("ccd: --alpha must be positive (got " + choice + ")");
  return value;
}

Design central_composite(const CcdOptions& options) {
  int k = options.factors;
  if (k < 2) throw Error("ccd: needs at least 2 factors (got " + std::to_string(k) + ")");
  if (k > 10) throw Error("ccd: at most 10 factors with a full factorial cube (got " + std::to_string(k) + ")");
  if (options.type != "circumscribed" && options.type != "inscribed" && options.type != "faced")
    throw Error("ccd: --type \"" + options.type + "\": expected circumscribed, inscribed or faced");
  int center = options.center;
  if (center < 0) center = ccd_default_center(k);
  double alpha = options.type == "faced" ? 1.0 : ccd_alpha(options.alpha, k, center);
  if (options.type == "faced" && options.alpha != "rotatable" && options.alpha != "face" &&
      std::abs(ccd_alpha(options.alpha, k, center) - 1.0) > 1e-12)
    throw Error("ccd: a face-centred design has alpha = 1; drop --alpha or use --type circumscribed");

  int cube = 1 << k;
  int runs = cube + 2 * k + center;
  Eigen::MatrixXd coded = Eigen::MatrixXd::Zero(runs, k);
  for (int r = 0; r < cube; ++r)
    for (int j = 0; j < k; ++j) coded(r, j) = (r >> j) & 1 ? 1.0 : -1.0;
  for (int j = 0; j < k; ++j) {
    coded(cube + 2 * j, j) = -alpha;
    coded(cube + 2 * j + 1, j) = alpha;
  }
  if (options.type == "inscribed") coded /= alpha;

  Design design = make_design("ccd", std::move(coded), 0);
  design.description = "central composite (" + options.type + "), " + std::to_string(k) + " factors, alpha = " +
                       format_double(std::round(alpha * 1e4) / 1e4) + ", " + std::to_string(center) +
                       " centre points, " + std::to_string(runs) + " runs";
  design.settings["type"] = options.type;
  design.settings["alpha"] = format_double(alpha);
  design.settings["alpha_choice"] = options.type == "faced" ? "face" : options.alpha;
  design.settings["center_points"] = std::to_string(center);
  design.settings["cube_points"] = std::to_string(cube);
  design.settings["axial_points"] = std::to_string(2 * k);
  return design;
}

}  // namespace demcal::doe
