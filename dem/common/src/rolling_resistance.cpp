#include "demcal/dem/rolling_resistance.hpp"

#include <nlohmann/json.hpp>

#include "demcal/core/error.hpp"
#include "demcal/dem/model_parameters.hpp"

namespace demcal::dem {

const char* const RollingResistance::kParameters[5] = {"rolling_friction_epsd", "rolling_damping_epsd",
                                                       "rolling_friction_cdt", "rolling_friction_cdt_relative",
                                                       "rolling_threshold_cdt_rad_s"};

RollingResistance RollingResistance::read(const nlohmann::json& p, const std::string& where) {
  RollingResistance r;
  const bool epsd = p.contains("rolling_friction_epsd"), cdt = p.contains("rolling_friction_cdt"),
             relative = p.contains("rolling_friction_cdt_relative");
  if (int(epsd) + int(cdt) + int(relative) > 1)
    throw Error(where + ": give one of rolling_friction_epsd (type C), rolling_friction_cdt (type A) and "
                "rolling_friction_cdt_relative (LIGGGHTS' cdt), not both");
  if (!epsd && p.contains("rolling_damping_epsd"))
    throw Error(where + ": rolling_damping_epsd needs rolling_friction_epsd");
  if (!relative && p.contains("rolling_threshold_cdt_rad_s"))
    throw Error(where + ": rolling_threshold_cdt_rad_s needs rolling_friction_cdt_relative (type A holds a body at "
                "rest without a threshold)");
  if (epsd) {
    r.type = Type::Epsd;
    r.friction = non_negative(p, "rolling_friction_epsd", where);
    r.damping = non_negative_or(p, "rolling_damping_epsd", 0.3, where);
  } else if (cdt) {
    r.type = Type::Cdt;
    r.friction = non_negative(p, "rolling_friction_cdt", where);
  } else if (relative) {
    r.type = Type::CdtRelative;
    r.friction = non_negative(p, "rolling_friction_cdt_relative", where);
    r.threshold_rad_s = p.contains("rolling_threshold_cdt_rad_s") ? positive(p, "rolling_threshold_cdt_rad_s", where) : 0.1;
  }
  return r;
}

}  // namespace demcal::dem
