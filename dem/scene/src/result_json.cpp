#include "demcal/dem/result_json.hpp"

#include <algorithm>

namespace demcal::dem {

nlohmann::json result_json(const TestResult& r, const std::map<std::string, double>& parameters, std::uint64_t seed) {
  nlohmann::json out;
  out["status"] = r.ok ? "ok" : "failed";
  out["reason"] = r.reason;
  if (!r.ended_by.empty()) out["ended_by"] = r.ended_by;
  out["macro"] = nlohmann::json::object();
  for (const auto& [name, value] : r.macro) out["macro"][name] = value;
  if (!r.extra_outputs.empty()) out["extra_outputs"] = r.extra_outputs;
  out["parameters"] = parameters;
  out["seed"] = seed;
  out["particles"] = r.particles;
  out["porosity"] = r.porosity;
  if (!r.specimen_info.empty()) out["specimen"] = r.specimen_info;
  out["steps"] = r.steps;
  out["dt_s"] = r.dt_s;
  if (r.density_scaling_dt_s > 0) out["density_scaling_dt_s"] = r.density_scaling_dt_s;
  out["wall_s"] = r.wall_s;
  out["test_wall_s"] = r.test_wall_s;
  out["threads"] = r.threads;
  if (!r.thread_cuts.empty()) out["thread_cuts"] = r.thread_cuts;
  out["particle_steps_per_s"] =
      r.test_wall_s > 0 ? static_cast<double>(r.particles) * static_cast<double>(r.steps) / r.test_wall_s : 0.0;
  return out;
}

nlohmann::json curve_json(const TestResult& r) {
  if (!r.series.empty()) {
    nlohmann::json columns = nlohmann::json::object();
    for (const auto& [name, values] : r.series) columns[name] = values;
    return columns;
  }
  nlohmann::json curve = {{"axial_strain", nlohmann::json::array()}, {"stress_MPa", nlohmann::json::array()},
                          {"lateral_strain", nlohmann::json::array()}, {"cracks", nlohmann::json::array()}};
  for (const CurvePoint& c : r.curve) {
    curve["axial_strain"].push_back(c.axial_strain);
    curve["stress_MPa"].push_back(c.stress_pa / 1e6);
    curve["lateral_strain"].push_back(c.lateral_strain);
    curve["cracks"].push_back(c.cracks);
  }
  // Only a confined test's curve has the column (its stress is then sigma_1 - sigma_3).
  const bool confined = std::any_of(r.curve.begin(), r.curve.end(),
                                    [](const CurvePoint& c) { return c.confining_stress_pa != 0; });
  if (confined) {
    curve["confining_stress_MPa"] = nlohmann::json::array();
    for (const CurvePoint& c : r.curve) curve["confining_stress_MPa"].push_back(c.confining_stress_pa / 1e6);
  }
  return curve;
}

}  // namespace demcal::dem
