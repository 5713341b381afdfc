#pragma once
// What a parameter's unit says about it. A scene declares every parameter
// with its unit; the unit alone decides whether the parameter is stress-like
// (moduli, strengths, stiffnesses: scaled together by the exact scaling of
// quasi-static bonded DEM), a length, or dimensionless.
#include <string>
#include <vector>

namespace demcal {

enum class Quantity { Stress, Stiffness, Length, Dimensionless, Density, Velocity, Time, Angle, Energy, Force };

// The quantity of a unit ("MPa" -> Stress, "1" -> Dimensionless); throws an
// Error "<where>: unknown unit "X" (known: ...)" otherwise.
Quantity quantity_of_unit(const std::string& unit, const std::string& where);
// "stress", "stiffness", "length", "dimensionless", ...
const char* quantity_name(Quantity q);
// True for quantities that scale with stress (stress, stiffness and, per the
// model's thickness, force).
bool is_stress_like(Quantity q);
// What one of the unit is in SI ("MPa" -> 1e6, "mm" -> 1e-3, "1" -> 1).
double si_factor_of_unit(const std::string& unit, const std::string& where);
// The units quantity_of_unit accepts, in a stable order.
std::vector<std::string> known_units();

}  // namespace demcal
