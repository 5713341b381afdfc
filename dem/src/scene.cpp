#include "demcal/dem/scene.hpp"

#include <cstdint>
#include <cstdio>

#include <cmath>
#include <fstream>
#include <sstream>

#include "demcal/core/error.hpp"
#include "demcal/core/json_fields.hpp"
#include "demcal/core/number_format.hpp"

namespace demcal::dem {
namespace {

using json = nlohmann::json;

double number_field(const json& object, const char* key, double fallback, const std::string& where) {
  if (!object.contains(key)) return fallback;
  const json& v = object.at(key);
  if (!v.is_number() || !std::isfinite(v.get<double>())) throw Error(where + ": \"" + key + "\" must be a finite number");
  return v.get<double>();
}

// The aggregates object: sizes in mm as engineers give them.
AggregateSpec aggregate_spec(const json& a, const std::string& where) {
  require_known_fields(a, {"size_range_mm", "bins", "coarse_fraction", "sides", "min_gap_m", "density_kg_m3", "max_attempts",
                           "note"},
                       where);
  AggregateSpec spec;
  if (a.contains("size_range_mm")) {
    const json& r = a.at("size_range_mm");
    if (!r.is_array() || r.size() != 2 || !r[0].is_number() || !r[1].is_number())
      throw Error(where + ": size_range_mm must be [d_min, d_max]");
    spec.d_min_m = r[0].get<double>() / 1000;
    spec.d_max_m = r[1].get<double>() / 1000;
  }
  if (a.contains("sides")) {
    const json& r = a.at("sides");
    if (!r.is_array() || r.size() != 2 || !r[0].is_number_integer() || !r[1].is_number_integer())
      throw Error(where + ": sides must be [min, max] integers");
    spec.sides_min = r[0].get<int>();
    spec.sides_max = r[1].get<int>();
  }
  spec.bins = static_cast<int>(number_field(a, "bins", spec.bins, where));
  spec.coarse_fraction = number_field(a, "coarse_fraction", spec.coarse_fraction, where);
  spec.min_gap_m = number_field(a, "min_gap_m", spec.min_gap_m, where);
  spec.density_kg_m3 = number_field(a, "density_kg_m3", spec.density_kg_m3, where);
  spec.max_attempts = static_cast<int>(number_field(a, "max_attempts", spec.max_attempts, where));
  spec.validate(where);
  return spec;
}

}  // namespace

Scene Scene::load(const std::string& path) { return from_json(read_json_file(path, "scene file"), path); }

namespace {

// Raise when a change of the engine changes results (2: a burst past the peak
// ends the test instead of failing it).
constexpr int kResultsVersion = 2;

// FNV-1a over the canonical dump (keys sorted): the same scene content gives
// the same fingerprint, whatever the file's layout.
std::string scene_fingerprint(const json& root) {
  const std::string text = root.dump() + "|results-v" + std::to_string(kResultsVersion);
  std::uint64_t hash = 1469598103934665603ull;
  for (unsigned char c : text) {
    hash ^= c;
    hash *= 1099511628211ull;
  }
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%016llx-v%d", static_cast<unsigned long long>(hash), kResultsVersion);
  return buffer;
}

}  // namespace

Scene Scene::from_json(const json& root, const std::string& origin) {
  require_known_fields(root, {"name", "test", "description", "specimen", "aggregates", "parameters", "contacts", "loading"},
                       origin);
  Scene scene;
  scene.origin_ = origin;
  scene.fingerprint_ = scene_fingerprint(root);
  scene.name_ = root.value("name", std::string("scene"));
  scene.test_ = root.value("test", std::string(""));
  if (scene.test_ != "ucs" && scene.test_ != "brazilian")
    throw Error(origin + ": \"test\" must be \"ucs\" or \"brazilian\" (got \"" + scene.test_ + "\")");

  if (!root.contains("specimen")) throw Error(origin + ": missing \"specimen\"");
  scene.specimen_ = root.at("specimen");
  require_known_fields(scene.specimen_, {"width_m", "height_m", "diameter_m", "thickness_m", "porosity", "radius_min_m",
                              "radius_max_m", "density_kg_m3", "isotropic_stress_pa"},
            origin + ": specimen");

  if (root.contains("parameters")) {
    const json& params = root.at("parameters");
    if (!params.is_object()) throw Error(origin + ": \"parameters\" must be an object of name: {value, low, high}");
    for (auto it = params.begin(); it != params.end(); ++it) {
      const std::string where = origin + ": parameters." + it.key();
      require_known_fields(it.value(), {"value", "low", "high", "unit", "note"}, where);
      SceneParameter p;
      if (!it.value().contains("value")) throw Error(where + ": missing \"value\" (the default)");
      p.value = number_field(it.value(), "value", 0, where);
      p.low = number_field(it.value(), "low", p.low, where);
      p.high = number_field(it.value(), "high", p.high, where);
      if (!(p.low <= p.value && p.value <= p.high))
        throw Error(where + ": value " + format_double(p.value) + " lies outside [low, high]");
      scene.parameters_[it.key()] = p;
    }
  }

  if (root.contains("aggregates")) scene.aggregates_ = aggregate_spec(root.at("aggregates"), origin + ": aggregates");
  if (!root.contains("contacts")) throw Error(origin + ": missing \"contacts\"");
  const std::vector<const char*> pairs =
      scene.aggregates_ ? std::vector<const char*>{"mortar-mortar", "mortar-aggregate", "aggregate-aggregate", "disk-platen"}
                        : std::vector<const char*>{"disk-disk", "disk-platen"};
  if (scene.aggregates_)
    require_known_fields(root.at("contacts"), {"mortar-mortar", "mortar-aggregate", "aggregate-aggregate", "disk-platen"},
                         origin + ": contacts (a scene with aggregates)");
  else
    require_known_fields(root.at("contacts"), {"disk-disk", "disk-platen"}, origin + ": contacts");
  for (const char* pair : pairs) {
    const std::string where = origin + ": contacts." + pair;
    if (!root.at("contacts").contains(pair)) throw Error(where + ": missing");
    const json& c = root.at("contacts").at(pair);
    require_known_fields(c, {"model", "parameters"}, where);
    ContactSpec spec;
    spec.model = c.value("model", std::string(""));
    spec.parameters = c.value("parameters", json::object());
    scene.contacts_[pair] = spec;
  }

  if (root.contains("loading")) {
    const json& l = root.at("loading");
    const std::string where = origin + ": loading";
    require_known_fields(l, {"platen_velocity_m_s", "stop_fraction_of_peak", "strain_limit", "record_strain", "max_wall_s",
                  "bond_gap_tolerance_m", "density_scaling_dt_s"},
              where);
    LoadingSpec& s = scene.loading_;
    s.platen_velocity_m_s = number_field(l, "platen_velocity_m_s", s.platen_velocity_m_s, where);
    s.stop_fraction_of_peak = number_field(l, "stop_fraction_of_peak", s.stop_fraction_of_peak, where);
    s.strain_limit = number_field(l, "strain_limit", s.strain_limit, where);
    s.record_strain = number_field(l, "record_strain", s.record_strain, where);
    s.max_wall_s = number_field(l, "max_wall_s", s.max_wall_s, where);
    s.bond_gap_tolerance_m = number_field(l, "bond_gap_tolerance_m", s.bond_gap_tolerance_m, where);
    s.density_scaling_dt_s = number_field(l, "density_scaling_dt_s", s.density_scaling_dt_s, where);
    if (s.density_scaling_dt_s < 0) throw Error(where + ": density_scaling_dt_s must be >= 0");
    if (!(s.platen_velocity_m_s > 0)) throw Error(where + ": platen_velocity_m_s must be positive");
    if (!(s.stop_fraction_of_peak > 0 && s.stop_fraction_of_peak < 1))
      throw Error(where + ": stop_fraction_of_peak must lie in (0, 1)");
    if (!(s.strain_limit > 0 && s.strain_limit < 0.5)) throw Error(where + ": strain_limit must lie in (0, 0.5)");
    if (!(s.record_strain > 0)) throw Error(where + ": record_strain must be positive");
  }
  // Evaluate everything once with the defaults, so a bad expression fails at load.
  std::map<std::string, double> defaults = scene.resolve({});
  scene.specimen(defaults, 1).validate();
  for (const auto& [pair, contact] : scene.contacts_) scene.bind(contact, defaults, origin + ": contacts." + pair);
  return scene;
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

SpecimenSpec Scene::specimen(const std::map<std::string, double>& parameters, std::uint64_t seed) const {
  SpecimenSpec spec;
  auto field = [&](const char* key, double& target) {
    if (specimen_.contains(key)) target = evaluate(specimen_.at(key), parameters, origin_ + ": specimen." + key);
  };
  field("width_m", spec.width_m);
  field("height_m", spec.height_m);
  if (specimen_.contains("diameter_m")) {  // a Brazilian disc is cut from a square packing
    field("diameter_m", spec.width_m);
    spec.height_m = spec.width_m;
  }
  field("thickness_m", spec.thickness_m);
  field("porosity", spec.porosity);
  field("radius_min_m", spec.radius_min_m);
  field("radius_max_m", spec.radius_max_m);
  field("density_kg_m3", spec.density_kg_m3);
  field("isotropic_stress_pa", spec.isotropic_stress_pa);
  spec.seed = seed;
  return spec;
}

}  // namespace demcal::dem
