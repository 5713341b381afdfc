#include "demcal/dem/hertz_material.hpp"

#include <nlohmann/json.hpp>

#include "demcal/core/error.hpp"
#include "demcal/core/number_format.hpp"
#include "demcal/dem/model_parameters.hpp"

namespace demcal::dem {
namespace {

double poisson_of(const nlohmann::json& p, const std::string& key, const std::string& where) {
  const double nu = number(p, key, where);
  if (!(nu > -1.0 && nu < 0.5))
    throw Error(where + ": " + key + " must lie in (-1, 0.5) (got " + format_double(nu) + ")");
  return nu;
}

}  // namespace

HertzMaterial HertzMaterial::read(const nlohmann::json& p, const std::string& where) {
  HertzMaterial m;
  const double g1 = positive(p, "shear_modulus_pa", where);
  const double nu1 = poisson_of(p, "poisson", where);
  const double g2 = p.contains("shear_modulus_2_pa") ? positive(p, "shear_modulus_2_pa", where) : g1;
  const double nu2 = p.contains("poisson_2") ? poisson_of(p, "poisson_2", where) : nu1;
  const double e1 = 2 * g1 * (1 + nu1), e2 = 2 * g2 * (1 + nu2);
  m.e_eff_pa = 1.0 / ((1 - nu1 * nu1) / e1 + (1 - nu2 * nu2) / e2);
  m.g_eff_pa = 1.0 / ((2 - nu1) / g1 + (2 - nu2) / g2);
  m.restitution = positive(p, "restitution", where);
  if (m.restitution > 1)
    throw Error(where + ": restitution must lie in (0, 1] (got " + format_double(m.restitution) + ")");
  m.friction = non_negative(p, "friction", where);
  m.overlap_ratio = p.contains("time_step_overlap_ratio") ? positive(p, "time_step_overlap_ratio", where) : 0.01;
  m.rolling = RollingResistance::read(p, where);
  return m;
}

std::vector<std::string> hertz_parameter_keys(std::initializer_list<const char*> extra) {
  std::vector<std::string> keys = {"shear_modulus_pa", "poisson",  "shear_modulus_2_pa",     "poisson_2",
                                   "restitution",      "friction", "time_step_overlap_ratio"};
  for (const char* key : RollingResistance::kParameters) keys.push_back(key);
  for (const char* key : extra) keys.push_back(key);
  return keys;
}

}  // namespace demcal::dem
