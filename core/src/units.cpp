#include "demcal/core/units.hpp"

#include <utility>

#include "demcal/core/error.hpp"

namespace demcal {
namespace {

// Stiffness in N/m: with PFC's unit thickness a 2D contact stiffness scales
// like a stress, so it belongs with the stress-like parameters.
const std::vector<std::pair<std::string, Quantity>>& table() {
  static const std::vector<std::pair<std::string, Quantity>> units = {
      {"Pa", Quantity::Stress},     {"kPa", Quantity::Stress},       {"MPa", Quantity::Stress},
      {"GPa", Quantity::Stress},    {"N/m", Quantity::Stiffness},    {"m", Quantity::Length},
      {"mm", Quantity::Length},     {"1", Quantity::Dimensionless},  {"kg/m3", Quantity::Density},
      {"m/s", Quantity::Velocity},  {"s", Quantity::Time},           {"deg", Quantity::Angle},
      {"J", Quantity::Energy},  // per the model's thickness, as every 2D energy here
      {"MN/m", Quantity::Stiffness},
      // A force in 2D is per the model's thickness (PFC's unit thickness): a stress times a length, so it scales
      // like a stress (a contact bond's strength given as a force, as PFC 4 users give it).
      {"N", Quantity::Force},       {"kN", Quantity::Force},
  };
  return units;
}

}  // namespace

Quantity quantity_of_unit(const std::string& unit, const std::string& where) {
  for (const auto& [name, q] : table())
    if (name == unit) return q;
  std::string list;
  for (const std::string& u : known_units()) list += (list.empty() ? "" : ", ") + u;
  throw Error(where + ": unknown unit \"" + unit + "\" (known: " + list + "; \"1\" for dimensionless)");
}

const char* quantity_name(Quantity q) {
  switch (q) {
    case Quantity::Stress: return "stress";
    case Quantity::Stiffness: return "stiffness";
    case Quantity::Length: return "length";
    case Quantity::Dimensionless: return "dimensionless";
    case Quantity::Density: return "density";
    case Quantity::Velocity: return "velocity";
    case Quantity::Time: return "time";
    case Quantity::Angle: return "angle";
    case Quantity::Energy: return "energy";
    case Quantity::Force: return "force";
  }
  return "unknown";
}

double si_factor_of_unit(const std::string& unit, const std::string& where) {
  quantity_of_unit(unit, where);  // an unknown unit is an error here too
  if (unit == "kPa" || unit == "kN") return 1e3;
  if (unit == "MPa" || unit == "MN/m") return 1e6;
  if (unit == "GPa") return 1e9;
  if (unit == "mm") return 1e-3;
  return 1.0;
}

bool is_stress_like(Quantity q) {
  return q == Quantity::Stress || q == Quantity::Stiffness || q == Quantity::Force;
}

std::vector<std::string> known_units() {
  std::vector<std::string> out;
  for (const auto& entry : table()) out.push_back(entry.first);
  return out;
}

}  // namespace demcal
