#pragma once
// A scene file: the test (ucs, ...), the specimen, the named parameters a
// design varies, and the contact models whose parameters are bound to them.
//
//   {"name": "ucs_rock_pb", "test": "ucs",
//    "specimen": {"width_m": 0.05, "height_m": 0.1, "porosity": 0.16,
//                 "radius_min_m": 5e-4, "radius_max_m": "R_min_m*1.5", "density_kg_m3": 2650},
//    "parameters": {"Ec_GPa": {"value": 16, "low": 1, "high": 200}, ...},
//    "contacts": {"disk-disk":   {"model": "parallel_bond", "parameters": {"modulus_pa": "Ec_GPa*1e9", ...}},
//                 "disk-platen": {"model": "linear", "parameters": {...}}},
//    "loading": {"platen_velocity_m_s": 0.02, "stop_fraction_of_peak": 0.7, "strain_limit": 0.02}}
//
// A bound value is a number or a product of parameter names and numbers
// ("Ec_GPa*1e9", "R_min_m*R_max_over_R_min").
//
// Concrete: an "aggregates" object (Walraven gradation, polygon sides, gap,
// density) makes the disks inside each placed polygon one rigid clump, and
// the contacts are then "mortar-mortar", "mortar-aggregate" (the interfacial
// transition zone), "aggregate-aggregate" and "disk-platen".
#include <map>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "demcal/dem/aggregates.hpp"
#include "demcal/dem/genesis.hpp"

namespace demcal::dem {

struct SceneParameter {
  double value = 0;                 // default (reference) value
  double low = -1e300, high = 1e300;  // allowed range, checked on --set
};

struct ContactSpec {
  std::string model;
  nlohmann::json parameters;        // values or expressions
};

struct LoadingSpec {
  double platen_velocity_m_s = 0.02;   // each platen moves at this speed
  double stop_fraction_of_peak = 0.7;  // stop once past the peak and below this fraction of it
  double strain_limit = 0.05;
  double record_strain = 2e-5;         // curve resolution (axial strain between points)
  double max_wall_s = 3600;            // a run longer than this is recorded as failed (timeout)
  double bond_gap_tolerance_m = 0;     // 0: 1 % of the smallest radius
  double density_scaling_dt_s = 0;     // > 0: density scaling to this time step (stated in the result)
};

class Scene {
 public:
  static Scene load(const std::string& path);
  static Scene from_json(const nlohmann::json& json, const std::string& origin);

  const std::string& name() const { return name_; }
  const std::string& test() const { return test_; }
  const std::map<std::string, SceneParameter>& parameters() const { return parameters_; }
  const std::map<std::string, ContactSpec>& contacts() const { return contacts_; }
  const LoadingSpec& loading() const { return loading_; }
  // The aggregates of a concrete scene; empty for a one-phase specimen.
  const std::optional<AggregateSpec>& aggregates() const { return aggregates_; }
  const std::string& origin() const { return origin_; }
  // Identifies what a stored result was made with: the scene's content and
  // the version of the results (raised when the engine's physics change), so
  // a batch never reuses a result of an edited scene or an older engine.
  const std::string& fingerprint() const { return fingerprint_; }

  // Defaults with `overrides` applied; unknown names, non-finite values and
  // values outside [low, high] are errors naming the parameter.
  std::map<std::string, double> resolve(const std::map<std::string, double>& overrides) const;
  // Evaluates a bound value (number or product expression).
  double evaluate(const nlohmann::json& value, const std::map<std::string, double>& parameters,
                  const std::string& where) const;
  // The contact model parameters with every expression evaluated.
  nlohmann::json bind(const ContactSpec& contact, const std::map<std::string, double>& parameters,
                      const std::string& where) const;
  SpecimenSpec specimen(const std::map<std::string, double>& parameters, std::uint64_t seed) const;

 private:
  std::string origin_, name_, test_, fingerprint_;
  nlohmann::json specimen_;
  std::map<std::string, SceneParameter> parameters_;
  std::map<std::string, ContactSpec> contacts_;
  LoadingSpec loading_;
  std::optional<AggregateSpec> aggregates_;
};

}  // namespace demcal::dem
