#pragma once
// A scene file: the test (ucs, ...), the sections the test reads (a packed
// specimen's "specimen" and "loading", a heap's "funnel" ...), the named
// parameters a design varies, and the contact models whose parameters are
// bound to them.
//
//   {"name": "ucs_rock_pb", "test": "ucs",
//    "specimen": {"width_m": 0.05, "height_m": 0.1, "porosity": 0.16,
//                 "radius_min_m": 5e-4, "radius_max_m": "R_min_m*1.5", "density_kg_m3": 2650},
//    "parameters": {"Ec_GPa": {"value": 16, "low": 1, "high": 200, "unit": "GPa"}, ...},
//    "contacts": {"particle-particle": {"model": "parallel_bond", "parameters": {"modulus_pa": "Ec_GPa*1e9", ...}},
//                 "particle-platen":   {"model": "linear", "parameters": {...}}},
//    "loading": {"platen_velocity_m_s": 0.02, "stop_fraction_of_peak": 0.7, "strain_limit": 0.02}}
//
// A bound value is a number or a product of parameter names and numbers
// ("Ec_GPa*1e9", "R_min_m*R_max_over_R_min").
//
// The scene is the one place a parameter is declared: its default (`value`),
// its physical bounds (`low`, `high`) and its `unit` (core/units.hpp: the unit
// says whether it is stress-like, a length or dimensionless, "1"). Parameter
// spaces only narrow it (check_space), studies fix it.
//
// Variants: {"extends": "ucs_concrete.json", ...} starts from that scene
// (path relative to this file; chains allowed) and applies this file as a
// JSON Merge Patch (RFC 7386): objects merge, anything else replaces, null
// deletes.
//
// The contacts object binds a model to every contact role of the scene: the
// specimen's own ("particle-particle", or a concrete's "mortar-mortar",
// "mortar-aggregate", "aggregate-aggregate") and the test's boundaries
// ("particle-platen"); the roles' older names ("disk-disk" ...) still read.
//
// Nothing here depends on the dimension: the scene keeps each section as
// JSON, and the test's engine reads it (a 2D specimen: packed_test.hpp) and
// checks the contact models against its own registry (LabTest::contact_models).
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "demcal/core/units.hpp"
#include "demcal/dem/contact_role.hpp"
#include "demcal/dem/external_test.hpp"

namespace demcal {
class ParameterSpace;
}

namespace demcal::dem {

struct SceneParameter {
  double value = 0;                 // default (reference) value
  double low = -1e300, high = 1e300;  // physical bounds, checked on --set
  std::string unit;                 // "GPa", "m", "1" ...
  Quantity quantity = Quantity::Dimensionless;  // what the unit says
  std::string note;
};

class LabTest;

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
  double local_damping = 0.7;          // alpha of the local non-viscous damping (PFC's default for quasi-static tests)
  double safety_factor = 0.8;          // the time step's share of the critical one (dashpots counted)
  // UCS only: the platens start at elastic_speedup x platen_velocity_m_s
  // and slow in proportion as the most loaded bond takes up its strength,
  // reaching platen_velocity_m_s when it carries speedup_until_utilisation
  // of it or a bond breaks: fewer steps while the specimen is elastic, and
  // the constant speed well before the window E and nu are taken over
  // (scripts/speedup_check.py, docs/benchmarks.md).
  double elastic_speedup = 1;          // 1: one speed throughout
  double speedup_until_utilisation = 0.5;
  // Where the platens of a packed prism start: at the faces of the vessel it
  // was packed in, touching every disk that touched the vessel, force-free as
  // they lie (PFC: the vessel's walls become the platens); or at the
  // outermost disks, which makes the first strain close the ends' roughness.
  // A Brazilian disc (cut from the packing) and a specimen relaxed out of its
  // vessel (a locked-in stress) have no vessel faces: they start at their
  // outermost disks either way.
  enum class PlatenStart { vessel_faces, outermost_disks };
  PlatenStart platen_start = PlatenStart::vessel_faces;
  // A confined test only (LabTest::confined): one specimen per confining stress (same seed), in
  // this order; its outputs are numbered 1, 2, ... in it.
  std::vector<double> confining_stresses_pa;
};

class Scene {
 public:
  // Reads the file, follows "extends" and validates.
  static Scene load(const std::string& path);
  // `json` is a whole scene ("extends" already applied).
  static Scene from_json(const nlohmann::json& json, const std::string& origin);
  // The scene's JSON with every "extends" applied (what from_json takes).
  static nlohmann::json resolved_json(const std::string& path);
  // A whole scene's JSON with the particles' radii (radius_min_m and
  // radius_max_m of the section that shapes the specimen) divided by `factor`
  // (> 1: finer; aggregates keep their sizes), to check a calibration made on
  // a coarse specimen at a finer resolution.
  static nlohmann::json with_finer_disks(nlohmann::json scene, double factor, const std::string& origin);

  const std::string& name() const { return name_; }
  const std::string& test() const { return test_; }
  const LabTest& lab_test() const { return *lab_test_; }
  // Every contact role the scene binds: the specimen's, then the test's
  // boundaries', under their canonical names (contacts() uses them too).
  const std::vector<ContactRole>& contact_roles() const { return roles_; }
  const std::map<std::string, SceneParameter>& parameters() const { return parameters_; }
  const std::map<std::string, ContactSpec>& contacts() const { return contacts_; }
  const LoadingSpec& loading() const { return loading_; }
  // An external test's command, inputs and outputs (external_test.hpp):
  // such a scene has no specimen, contacts or loading. Throws for any other.
  bool is_external() const { return external_.has_value(); }
  const ExternalSpec& external() const;
  // A section the scene's test reads (LabTest::sections), e.g. "specimen"
  // or a heap's "particles", as written; an empty object when the file has none.
  const nlohmann::json& section(const std::string& name) const;
  bool has_section(const std::string& name) const { return sections_.contains(name); }
  const std::string& origin() const { return origin_; }
  // Identifies what a stored result was made with: what changes results
  // (test, specimen, aggregates, contacts, loading, parameter defaults) and
  // the version of the results (raised when the engine's physics change), so
  // a batch never reuses a result of an edited scene or an older engine.
  // Names, descriptions, notes, units and bounds do not count.
  const std::string& fingerprint() const { return fingerprint_; }

  // A parameter space narrows the scene: each parameter it varies, fixes or
  // ties must be a scene parameter, its unit (when given) the scene's, and
  // its range inside the scene's bounds. Throws a one-line Error naming both files.
  void check_space(const ParameterSpace& space, const std::string& space_path) const;

  // Defaults with `overrides` applied; unknown names, non-finite values and
  // values outside [low, high] are errors naming the parameter.
  std::map<std::string, double> resolve(const std::map<std::string, double>& overrides) const;
  // Evaluates a bound value (number or product expression).
  double evaluate(const nlohmann::json& value, const std::map<std::string, double>& parameters,
                  const std::string& where) const;
  // The contact model parameters with every expression evaluated.
  nlohmann::json bind(const ContactSpec& contact, const std::map<std::string, double>& parameters,
                      const std::string& where) const;
  // Whether the parameter enters the specimen (a section the test marks
  // shapes_specimen: its size, radii, porosity, density): each value is then
  // another packing, not the same specimen with other contacts. A
  // calibration keeps such parameters fixed unless its space varies them.
  bool shapes_specimen(const std::string& parameter) const;

 private:
  std::string origin_, name_, test_, fingerprint_;
  const LabTest* lab_test_ = nullptr;
  std::vector<ContactRole> roles_;
  std::map<std::string, SceneParameter> parameters_;
  std::map<std::string, ContactSpec> contacts_;
  LoadingSpec loading_;
  std::optional<ExternalSpec> external_;
  nlohmann::json sections_ = nlohmann::json::object();  // the test's sections, as written

  void read_parameters(const nlohmann::json& root);
};

// Scene::check_space against any declared parameters (a scene's, or the
// union of a test list's); `origin` names where they were declared.
void check_space_against(const std::map<std::string, SceneParameter>& parameters, const std::string& origin,
                         const ParameterSpace& space, const std::string& space_path);

// A number of one of a test's own scene sections (a value or an expression
// of the parameters) into `target` when present; an Error naming the file,
// "section.key" and what is wrong when it is missing but required, or not finite.
void read_section_number(const Scene& scene, const std::map<std::string, double>& parameters,
                         const std::string& section, const nlohmann::json& object, const char* key, double& target,
                         bool required);


}  // namespace demcal::dem
