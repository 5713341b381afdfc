#pragma once
// Designs for quadratic response surfaces: central composite and Box-Behnken.
#include <string>

#include "demcal/doe/design.hpp"

namespace demcal::doe {

struct CcdOptions {
  int factors = 2;
  std::string type = "circumscribed";  // circumscribed | inscribed | faced
  std::string alpha = "rotatable";     // rotatable | orthogonal | face | a positive number
  int center = -1;                     // -1: Minitab's default for an unblocked design
};

// Cube points (full 2^k, Yates order), then axial points (-alpha, +alpha per
// factor), then centre points. Coded: cube at +-1 and axial at +-alpha
// (inscribed: scaled so the axial points sit at +-1).
Design central_composite(const CcdOptions& options);

// Minitab's default centre points for an unblocked CCD with a full cube:
// 2..8 factors -> 5, 6, 7, 10, 15, 21, 28.
int ccd_default_center(int factors);

// alpha for a named choice: rotatable (2^k)^(1/4); orthogonal
// [(sqrt(F + 2k + n0) - sqrt(F))^2 F / 4]^(1/4) with F = 2^k cube points
// (orthogonal quadratic terms); face 1; or the number given.
double ccd_alpha(const std::string& choice, int factors, int center);

// Box-Behnken for 3..7 factors: blocks of factors (all pairs for 3-5
// factors; the balanced incomplete blocks {124,235,346,145,256,136} and the
// Fano plane {124,235,346,457,156,267,137} for 6 and 7) crossed with a 2^2 or
// 2^3 factorial, then centre points (default 3, 3, 6, 6, 6 as Minitab).
Design box_behnken(int factors, int center = -1);
int bbd_default_center(int factors);

}  // namespace demcal::doe
