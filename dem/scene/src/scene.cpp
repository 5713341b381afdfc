#include "demcal/dem/scene.hpp"

#include <climits>
#include <cstdint>
#include <cstdlib>
#include <algorithm>
#include <cstdio>

#include <cmath>
#include <fstream>
#include <sstream>

#include "demcal/core/error.hpp"
#include "demcal/core/file_path.hpp"
#include "demcal/core/fnv_hash.hpp"
#include "demcal/core/json_fields.hpp"
#include "demcal/core/number_format.hpp"
#include "demcal/core/parameter_space.hpp"
#include "demcal/dem/lab_test.hpp"

namespace demcal::dem {

using json = nlohmann::json;

namespace {

// The canonical path of a file, to recognise an "extends" cycle however its paths are spelled.
std::string canonical_path(const std::string& path) {
  char resolved[PATH_MAX];
  return ::realpath(path.c_str(), resolved) ? std::string(resolved) : path;
}

// Follows "extends" (relative to the extending file). `chain` holds the files
// already on the way, so a cycle is an error naming the file that closes it.
json resolve_extends(const std::string& path, std::vector<std::string>& chain) {
  const bool first = chain.empty();  // the file the user named
  json root = read_json_file(path, "scene file");
  if (!root.is_object()) throw Error(path + ": a scene must be a JSON object");
  if (!root.contains("extends")) return root;
  const json& base_name = root.at("extends");
  if (!base_name.is_string() || base_name.get<std::string>().empty())
    throw Error(path + ": \"extends\" must be the path of another scene file");
  const std::string base_path = path_beside(path, base_name.get<std::string>());
  chain.push_back(canonical_path(path));
  if (std::find(chain.begin(), chain.end(), canonical_path(base_path)) != chain.end())
    throw Error(path + ": \"extends\": " + base_name.get<std::string>() + " extends this file again (a cycle)");
  json merged;
  try {
    merged = resolve_extends(base_path, chain);
  } catch (const Error& e) {
    // Name the file the user gave first; the base's own message follows.
    if (!first) throw;
    throw Error(path + ": extends " + base_name.get<std::string>() + ": " + e.what());
  }
  json patch = root;
  patch.erase("extends");
  merged.merge_patch(patch);  // RFC 7386
  return merged;
}

}  // namespace

json Scene::resolved_json(const std::string& path) {
  std::vector<std::string> chain;
  return resolve_extends(path, chain);
}

Scene Scene::load(const std::string& path) { return from_json(resolved_json(path), path); }

json Scene::with_finer_disks(json scene, double factor, const std::string& origin) {
  if (!(factor >= 1.0) || !std::isfinite(factor)) throw Error(origin + ": a finer resolution needs a factor >= 1");
  if (scene.value("test", json()) == "external")
    throw Error(origin + ": an external test has no disks of ours to make finer (its program sets its resolution)");
  // The radii are in the section that shapes the specimen (a packed
  // specimen's "specimen", a heap's "particles").
  if (!scene.contains("test") || !scene.at("test").is_string()) throw Error(origin + ": missing \"test\" (a string)");
  std::string section_key;
  for (const SceneSection& section : LabTestRegistry::instance().find(scene.at("test").get<std::string>(), origin).sections())
    if (section_key.empty() && section.shapes_specimen && scene.contains(section.name) &&
        scene.at(section.name).is_object() && scene.at(section.name).contains("radius_min_m"))
      section_key = section.name;
  if (section_key.empty()) throw Error(origin + ": no specimen (no section with radius_min_m)");
  json& specimen = scene[section_key];
  for (const char* key : {"radius_min_m", "radius_max_m"}) {
    if (!specimen.contains(key)) throw Error(origin + ": " + section_key + "." + key + " is missing");
    json& r = specimen[key];
    if (r.is_number())
      r = r.get<double>() / factor;
    else if (r.is_string())
      r = r.get<std::string>() + "*" + format_double(1.0 / factor);  // expressions are products
    else
      throw Error(origin + ": " + section_key + "." + key + " must be a number or an expression");
  }
  if (scene.contains("name") && scene.at("name").is_string())
    scene["name"] = scene.at("name").get<std::string>() + "_finer_" + format_double(factor);
  return scene;
}

namespace {

// Raise when a change of the engine changes results (2: a burst past the peak
// ends the test instead of failing it; 3: a prism's platens start at its
// vessel's faces; 4: a burst no longer ends a platen test, which goes on to
// its own end).
constexpr int kResultsVersion = 4;

// loading.confining_stresses_MPa, in Pa: the biaxial test's list, each > 0;
// at least two different ones when there are several (the Mohr-Coulomb fit).
std::vector<double> confining_stresses(const json& loading, const LabTest& test, const std::string& where) {
  std::vector<double> out;
  if (!loading.contains("confining_stresses_MPa")) return out;
  const std::string field = where + ".confining_stresses_MPa";
  if (!test.confined())
    throw Error(field + ": only a confined test (biaxial) has a confining stress (this scene's test: " + test.name() + ")");
  const json& list = loading.at("confining_stresses_MPa");
  if (!list.is_array() || list.empty()) throw Error(field + ": must be a non-empty list of stresses in MPa, e.g. [1, 2, 4, 8]");
  for (std::size_t k = 0; k < list.size(); ++k) {
    if (!list[k].is_number()) throw Error(field + ": entry " + std::to_string(k + 1) + " is not a number");
    const double mpa = list[k].get<double>();
    if (!(std::isfinite(mpa) && mpa > 0))
      throw Error(field + ": entry " + std::to_string(k + 1) + " is " + format_double(mpa) +
                  " MPa; a confining stress must be > 0 (an unconfined test is the ucs test)");
    out.push_back(mpa * 1e6);
  }
  if (out.size() > 1 && std::all_of(out.begin(), out.end(), [&](double v) { return v == out[0]; }))
    throw Error(field + ": the Mohr-Coulomb fit of a series needs at least two different confining stresses");
  return out;
}

void drop_notes(json& value) {
  if (!value.is_object()) return;
  value.erase("note");
  for (auto& [key, child] : value.items()) drop_notes(child);
}

// FNV-1a over the canonical dump (keys sorted) of what changes results: the
// same physics gives the same fingerprint, whatever the file's layout, name,
// descriptions, notes, units or parameter bounds.
std::string scene_fingerprint(const json& root, int test_version, const std::vector<SceneSection>& sections = {}) {
  json physics = root;
  if (physics.contains("contacts") && physics.at("contacts").is_object()) {  // a role's old name is the same role
    json canonical = json::object();
    for (auto& [role, contact] : physics.at("contacts").items()) canonical[canonical_role_name(role)] = contact;
    physics["contacts"] = canonical;
  }
  for (const char* key : {"name", "description", "extends"}) physics.erase(key);
  if (physics.contains("parameters") && physics.at("parameters").is_object()) {
    json defaults = json::object();
    for (auto& [name, p] : physics.at("parameters").items()) defaults[name] = p.value("value", json());
    physics["parameters"] = defaults;
  }
  if (physics.contains("contacts")) drop_notes(physics["contacts"]);
  for (const SceneSection& section : sections)
    if (physics.contains(section.name)) drop_notes(physics[section.name]);
  std::string text = physics.dump() + "|results-v" + std::to_string(kResultsVersion);
  if (test_version > 0) text += "|test-v" + std::to_string(test_version);
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%016llx-v%d", static_cast<unsigned long long>(fnv1a_64(text)), kResultsVersion);
  return buffer;
}

}  // namespace

Scene Scene::from_json(const json& root, const std::string& origin) {
  const bool external = root.is_object() && root.value("test", json()) == "external";
  if (external)
    require_known_fields(root, {"name", "test", "description", "parameters", "command", "workdir", "timeout_s", "inputs",
                                "outputs", "exact_scaling"},
                         origin);
  else if (!root.is_object())
    throw Error(origin + ": a scene must be a JSON object");
  Scene scene;
  scene.origin_ = origin;
  if (root.contains("name") && !root.at("name").is_string()) throw Error(origin + ": \"name\" must be a string");
  if (root.contains("description") && !root.at("description").is_string())
    throw Error(origin + ": \"description\" must be a string");
  scene.name_ = root.value("name", std::string("scene"));
  if (!root.contains("test") || !root.at("test").is_string()) throw Error(origin + ": missing \"test\" (a string)");
  scene.test_ = root.at("test").get<std::string>();
  scene.lab_test_ = &LabTestRegistry::instance().find(scene.test_, origin);

  scene.read_parameters(root);
  if (external) {
    scene.external_ = parse_external_spec(root, origin, scene.parameters_);
    json physics = root;  // the driver's contents count, so an edited driver never reuses a result
    physics["inputs_content"] = scene.external_->inputs_hash;
    scene.fingerprint_ = scene_fingerprint(physics, scene.lab_test_->results_version());
    return scene;
  }
  const std::vector<SceneSection> sections = scene.lab_test_->sections();
  std::vector<std::string> known = {"name", "test", "description", "parameters", "contacts"};
  for (const SceneSection& section : sections) known.push_back(section.name);
  require_known_fields(root, known, origin);
  for (const SceneSection& section : sections) {
    if (!root.contains(section.name)) {
      if (section.required) throw Error(origin + ": missing \"" + section.name + "\"");
      continue;
    }
    if (!root.at(section.name).is_object()) throw Error(origin + ": \"" + section.name + "\" must be an object");
    scene.sections_[section.name] = root.at(section.name);
  }
  // The contact roles: the specimen's own (as its sections say), then the
  // test's boundaries, each against every group of the specimen.
  scene.roles_ = scene.lab_test_->specimen_roles(scene);
  std::vector<std::uint8_t> groups;
  for (const ContactRole& r : scene.roles_)
    for (const auto& [a, b] : r.groups)
      for (std::uint8_t g : {a, b})
        if (std::find(groups.begin(), groups.end(), g) == groups.end()) groups.push_back(g);
  for (const BoundaryRole& b : scene.lab_test_->boundary_roles()) {
    ContactRole role{b.name, {}, b.description};
    for (std::uint8_t g : groups) role.groups.emplace_back(g, b.group);
    scene.roles_.push_back(role);
  }
  std::string role_list;
  for (const ContactRole& r : scene.roles_) role_list += (role_list.empty() ? "" : ", ") + r.name;
  if (!root.contains("contacts") || !root.at("contacts").is_object())
    throw Error(origin + ": missing \"contacts\" (an object binding a model to each of: " + role_list + ")");
  std::map<std::string, std::string> spelled;  // canonical role name -> the name the file gives it
  for (auto it = root.at("contacts").begin(); it != root.at("contacts").end(); ++it) {
    const std::string& role_name = canonical_role_name(it.key());
    bool known_role = false;
    for (const ContactRole& r : scene.roles_) known_role = known_role || r.name == role_name;
    if (!known_role)
      throw Error(origin + ": contacts: unknown contact role \"" + it.key() + "\" (this scene's roles: " + role_list + ")");
    if (spelled.count(role_name))
      throw Error(origin + ": contacts: \"" + spelled[role_name] + "\" and \"" + it.key() + "\" name the same role (" +
                  role_name + "); keep one");
    spelled[role_name] = it.key();
  }
  for (const ContactRole& role : scene.roles_) {
    if (!spelled.count(role.name)) throw Error(origin + ": contacts." + role.name + ": missing");
    const std::string where = origin + ": contacts." + spelled[role.name];
    const json& c = root.at("contacts").at(spelled[role.name]);
    require_known_fields(c, {"model", "parameters"}, where);
    if (!c.contains("model") || !c.at("model").is_string()) throw Error(where + ": missing \"model\" (a string)");
    if (c.contains("parameters") && !c.at("parameters").is_object())
      throw Error(where + ": \"parameters\" must be an object of name: number or expression");
    ContactSpec spec;
    spec.model = c.at("model").get<std::string>();
    spec.parameters = c.value("parameters", json::object());
    scene.contacts_[role.name] = spec;
  }

  if (scene.has_section("loading")) {
    const json& l = root.at("loading");
    const std::string where = origin + ": loading";
    require_known_fields(l, {"platen_velocity_m_s", "stop_fraction_of_peak", "strain_limit", "record_strain", "max_wall_s",
                  "bond_gap_tolerance_m", "density_scaling_dt_s", "platen_start", "local_damping",
                  "confining_stresses_MPa", "elastic_speedup", "speedup_until_utilisation", "safety_factor"},
              where);
    LoadingSpec& s = scene.loading_;
    s.platen_start = choice_field(l, "platen_start", {"vessel_faces", "outermost_disks"}, 0, where) == 0
                         ? LoadingSpec::PlatenStart::vessel_faces
                         : LoadingSpec::PlatenStart::outermost_disks;
    s.platen_velocity_m_s = number_field(l, "platen_velocity_m_s", s.platen_velocity_m_s, where);
    s.stop_fraction_of_peak = number_field(l, "stop_fraction_of_peak", s.stop_fraction_of_peak, where);
    s.strain_limit = number_field(l, "strain_limit", s.strain_limit, where);
    s.record_strain = number_field(l, "record_strain", s.record_strain, where);
    s.max_wall_s = number_field(l, "max_wall_s", s.max_wall_s, where);
    s.bond_gap_tolerance_m = number_field(l, "bond_gap_tolerance_m", s.bond_gap_tolerance_m, where);
    s.density_scaling_dt_s = number_field(l, "density_scaling_dt_s", s.density_scaling_dt_s, where);
    s.safety_factor = number_field(l, "safety_factor", s.safety_factor, where);
    if (!(s.safety_factor > 0 && s.safety_factor <= 1)) throw Error(where + ": safety_factor must lie in (0, 1]");
    if (s.density_scaling_dt_s < 0) throw Error(where + ": density_scaling_dt_s must be >= 0");
    s.local_damping = number_field(l, "local_damping", s.local_damping, where);
    if (!(s.local_damping >= 0 && s.local_damping < 1)) throw Error(where + ": local_damping must lie in [0, 1)");
    // A quasi-static test: platens faster than 10 m/s would be an impact test.
    if (!(s.platen_velocity_m_s > 0 && s.platen_velocity_m_s <= 10))
      throw Error(where + ": platen_velocity_m_s must lie in (0, 10] m/s");
    if (!(s.max_wall_s > 0)) throw Error(where + ": max_wall_s must be positive");
    if (s.bond_gap_tolerance_m < 0) throw Error(where + ": bond_gap_tolerance_m must be >= 0");
    if (!(s.stop_fraction_of_peak > 0 && s.stop_fraction_of_peak < 1))
      throw Error(where + ": stop_fraction_of_peak must lie in (0, 1)");
    if (!(s.strain_limit > 0 && s.strain_limit < 0.5)) throw Error(where + ": strain_limit must lie in (0, 0.5)");
    if (!(s.record_strain > 0 && s.record_strain < s.strain_limit))
      throw Error(where + ": record_strain must lie in (0, strain_limit)");
    s.confining_stresses_pa = confining_stresses(l, *scene.lab_test_, where);
    s.elastic_speedup = number_field(l, "elastic_speedup", s.elastic_speedup, where);
    s.speedup_until_utilisation = number_field(l, "speedup_until_utilisation", s.speedup_until_utilisation, where);
    if (!(s.elastic_speedup >= 1 && s.elastic_speedup <= 20))
      throw Error(where + ": elastic_speedup must lie in [1, 20] (1: one platen speed throughout)");
    if (!(s.elastic_speedup * s.platen_velocity_m_s <= 10))
      throw Error(where + ": elastic_speedup x platen_velocity_m_s must be at most 10 m/s");
    if (!(s.speedup_until_utilisation > 0 && s.speedup_until_utilisation < 1))
      throw Error(where + ": speedup_until_utilisation must lie in (0, 1)");
    if (s.elastic_speedup != 1 && !scene.lab_test_->speeds_up_while_elastic())
      throw Error(where + ": elastic_speedup: only uniaxial compression uses it (this scene's test is " + scene.test_ + ")");
  }
  if (scene.lab_test_->confined() && scene.loading_.confining_stresses_pa.empty())
    throw Error(origin + ": loading.confining_stresses_MPa: missing (the " + scene.test_ +
                " test's confining stresses, MPa, e.g. [1, 2, 4, 8])");
  // Evaluate everything once with the defaults, so a bad expression fails at load.
  std::map<std::string, double> defaults = scene.resolve({});
  scene.lab_test_->check_scene(scene);
  for (const auto& [role, contact] : scene.contacts_) {
    // Building the model checks its parameters (names, signs) at load, not at
    // the first run, against the test's own engine's models.
    const std::string where = origin + ": contacts." + spelled[role];
    scene.lab_test_->contact_models().check(contact.model, scene.bind(contact, defaults, where), where);
  }
  scene.fingerprint_ = scene_fingerprint(root, scene.lab_test_->results_version(), sections);  // on the validated file
  return scene;
}

void Scene::read_parameters(const json& root) {
  if (root.contains("parameters")) {
    const json& params = root.at("parameters");
    if (!params.is_object()) throw Error(origin_ + ": \"parameters\" must be an object of name: {value, low, high}");
    for (auto it = params.begin(); it != params.end(); ++it) {
      const std::string where = origin_ + ": parameters." + it.key();
      if (!it.value().is_object()) throw Error(where + ": must be an object {value, low, high, unit}");
      require_known_fields(it.value(), {"value", "low", "high", "unit", "note"}, where);
      SceneParameter p;
      if (!it.value().contains("value")) throw Error(where + ": missing \"value\" (the default)");
      if (!it.value().contains("unit") || !it.value().at("unit").is_string())
        throw Error(where + ": missing \"unit\" (a string such as \"MPa\", \"m\", or \"1\" for dimensionless)");
      p.unit = it.value().at("unit").get<std::string>();
      p.quantity = quantity_of_unit(p.unit, where + ".unit");
      if (it.value().contains("note")) {
        if (!it.value().at("note").is_string()) throw Error(where + ": \"note\" must be a string");
        p.note = it.value().at("note").get<std::string>();
      }
      p.value = number_field(it.value(), "value", 0, where);
      p.low = number_field(it.value(), "low", p.low, where);
      p.high = number_field(it.value(), "high", p.high, where);
      if (!(p.low <= p.value && p.value <= p.high))
        throw Error(where + ": value " + format_double(p.value) + " lies outside [low, high]");
      parameters_[it.key()] = p;
    }
  }

}

const json& Scene::section(const std::string& name) const {
  static const json empty = json::object();
  return sections_.contains(name) ? sections_.at(name) : empty;
}

const ExternalSpec& Scene::external() const {
  if (!external_) throw Error(origin_ + ": not an external test (its test: " + test_ + ")");
  return *external_;
}

void Scene::check_space(const ParameterSpace& space, const std::string& space_path) const {
  check_space_against(parameters_, origin_, space, space_path);
}

void check_space_against(const std::map<std::string, SceneParameter>& parameters, const std::string& origin_,
                         const ParameterSpace& space, const std::string& space_path) {
  auto scene_parameter = [&](const std::string& name, const std::string& what) -> const SceneParameter& {
    auto it = parameters.find(name);
    if (it == parameters.end()) {
      std::string list;
      for (const auto& [known, p] : parameters) list += (list.empty() ? "" : ", ") + known;
      throw Error(space_path + ": " + what + " \"" + name + "\" is not a parameter of the scene " + origin_ +
                  " (its parameters: " + list + ")");
    }
    return it->second;
  };
  auto inside = [&](const std::string& name, const SceneParameter& p, double value, const std::string& what) {
    if (value < p.low || value > p.high)
      throw Error(space_path + ": " + name + " " + what + " " + format_double(value) + " lies outside the bounds [" +
                  format_double(p.low) + ", " + format_double(p.high) + "] the scene " + origin_ + " declares");
  };
  for (const Parameter& q : space.parameters()) {
    const SceneParameter& p = scene_parameter(q.name, "parameter");
    if (!q.unit.empty() && q.unit != p.unit)
      throw Error(space_path + ": " + q.name + " has unit \"" + q.unit + "\" but the scene " + origin_ + " declares \"" +
                  p.unit + "\"");
    inside(q.name, p, q.low, "low");
    inside(q.name, p, q.high, "high");
  }
  for (const auto& [name, value] : space.fixed()) inside(name, scene_parameter(name, "fixed parameter"), value, "fixed at");
  for (const TiedParameter& t : space.tied()) scene_parameter(t.name, "tied parameter");
}

std::map<std::string, double> Scene::resolve(const std::map<std::string, double>& overrides) const {
  std::map<std::string, double> values;
  for (const auto& [name, p] : parameters_) values[name] = p.value;
  for (const auto& [name, value] : overrides) {
    auto it = parameters_.find(name);
    if (it == parameters_.end()) {
      std::string list;
      for (const auto& [known, p] : parameters_) list += (list.empty() ? "" : ", ") + known;
      throw Error(origin_ + ": unknown parameter \"" + name + "\" (scene parameters: " + list + ")");
    }
    if (!std::isfinite(value)) throw Error("parameter " + name + " is not a finite number");
    if (value < it->second.low || value > it->second.high)
      throw Error("parameter " + name + " = " + format_double(value) + " lies outside [" + format_double(it->second.low) +
                  ", " + format_double(it->second.high) + "]");
    values[name] = value;
  }
  return values;
}

double Scene::evaluate(const json& value, const std::map<std::string, double>& parameters, const std::string& where) const {
  if (value.is_number()) return value.get<double>();
  if (!value.is_string()) throw Error(where + ": expected a number or an expression like \"Ec_GPa*1e9\"");
  const std::string text = value.get<std::string>();
  double product = 1.0;
  std::stringstream stream(text);
  std::string factor;
  while (std::getline(stream, factor, '*')) {
    double number = 0;
    if (parse_double(factor, number) && !factor.empty()) {
      product *= number;
      continue;
    }
    auto it = parameters.find(factor);
    if (it == parameters.end()) throw Error(where + ": \"" + factor + "\" in \"" + text + "\" is not a scene parameter");
    product *= it->second;
  }
  return product;
}

json Scene::bind(const ContactSpec& contact, const std::map<std::string, double>& parameters,
                 const std::string& where) const {
  json bound = json::object();
  for (auto it = contact.parameters.begin(); it != contact.parameters.end(); ++it)
    bound[it.key()] = evaluate(it.value(), parameters, where + ".parameters." + it.key());
  return bound;
}

bool Scene::shapes_specimen(const std::string& parameter) const {
  if (!lab_test_) return false;
  for (const SceneSection& section : lab_test_->sections()) {
    if (!section.shapes_specimen || !has_section(section.name)) continue;
    for (const auto& [key, value] : this->section(section.name).items()) {
      const auto& after_packing = section.keys_not_shaping;
      if (!value.is_string() || std::find(after_packing.begin(), after_packing.end(), key) != after_packing.end())
        continue;
      std::stringstream stream(value.get<std::string>());
      std::string factor;
      while (std::getline(stream, factor, '*'))
        if (factor == parameter) return true;
    }
  }
  return false;
}

void read_section_number(const Scene& scene, const std::map<std::string, double>& parameters,
                         const std::string& section, const nlohmann::json& object, const char* key, double& target,
                         bool required) {
  const std::string where = scene.origin() + ": " + section + "." + key;
  if (!object.contains(key)) {
    if (required) throw Error(where + ": missing");
    return;
  }
  target = scene.evaluate(object.at(key), parameters, where);
  if (!std::isfinite(target)) throw Error(where + ": not a finite number");
}

}  // namespace demcal::dem
