#pragma once
// What the Hertz-Mindlin family of both engines reads from its parameters:
// the two bodies' materials as the effective moduli E* and G*, the
// restitution, friction, the time step's overlap ratio and the rolling
// resistance, with one-line errors that name where the parameters came from.
//   E* = 1 / ((1 - nu_1^2)/E_1 + (1 - nu_2^2)/E_2), G* = 1 / ((2 - nu_1)/G_1 + (2 - nu_2)/G_2), E = 2 G (1 + nu)
#include <initializer_list>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "demcal/dem/rolling_resistance.hpp"

namespace demcal::dem {

struct HertzMaterial {
  double e_eff_pa = 0, g_eff_pa = 0;
  double restitution = 1;  // in (0, 1]
  double friction = 0;
  double overlap_ratio = 0.01;  // time_step_overlap_ratio
  RollingResistance rolling;

  static HertzMaterial read(const nlohmann::json& p, const std::string& where);
};

// The keys of the family followed by a model's own `extra` keys.
std::vector<std::string> hertz_parameter_keys(std::initializer_list<const char*> extra);

}  // namespace demcal::dem
