#include "demcal/dem/describe.hpp"

#include <cmath>

#include "demcal/dem/lab_test.hpp"

namespace demcal::dem {

namespace {

bool listed(const std::vector<std::string>& names, const std::string& name) {
  for (const std::string& n : names)
    if (n == name) return true;
  return false;
}

// 2 or 3; null for an external test (its own program decides).
nlohmann::json dimension_json(const LabTest& test) {
  return test.dimension() > 0 ? nlohmann::json(test.dimension()) : nlohmann::json(nullptr);
}

nlohmann::json axes_json(const LabTest& test) {
  const auto [x, y] = test.curve_axes();
  return x.empty() ? nlohmann::json(nullptr) : nlohmann::json({{"x", x}, {"y", y}});
}

// A confined series' sigma_3 values (MPa), in the order its curve holds their
// pieces; null for a test that is not confined.
nlohmann::json confinements_json(const Scene& scene) {
  if (!scene.lab_test().confined()) return nullptr;
  nlohmann::json out = nlohmann::json::array();
  for (double s : scene.loading().confining_stresses_pa) out.push_back(s / 1e6);
  return out;
}

// An output with the flags its test gives it: a headline value, a modulus.
nlohmann::json flagged_output_json(const OutputSpec& o, const Scene& scene);

nlohmann::json output_json(const OutputSpec& o) {
  const Quantity q = quantity_of_unit(o.unit, "output " + o.name);
  nlohmann::json item = {{"unit", o.unit}, {"description", o.description}, {"quantity", quantity_name(q)},
                         {"stress_like", is_stress_like(q)}, {"si_factor", si_factor_of_unit(o.unit, o.name)}};
  if (!o.always) item["optional"] = true;
  // The values a target may take: [low, high], null for an open end.
  const auto end = [](double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); };
  item["range"] = nlohmann::json::array({end(o.range.low), end(o.range.high)});
  return item;
}

nlohmann::json flagged_output_json(const OutputSpec& o, const Scene& scene) {
  nlohmann::json item = output_json(o);
  if (listed(scene.lab_test().headline_outputs(scene), o.name)) item["headline"] = true;
  // A modulus carries its rank in the test's list (1: the preferred scale target).
  const std::vector<std::string> moduli = scene.lab_test().modulus_outputs(scene);
  for (std::size_t k = 0; k < moduli.size(); ++k)
    if (moduli[k] == o.name) item["modulus"] = static_cast<int>(k + 1);
  return item;
}

}  // namespace

nlohmann::json describe_scene(const Scene& scene) {
  using json = nlohmann::json;
  json out;
  out["scene"] = scene.origin();
  out["name"] = scene.name();
  out["test"] = scene.test();
  out["test_description"] = scene.lab_test().description();
  out["dimension"] = dimension_json(scene.lab_test());
  out["fingerprint"] = scene.fingerprint();
  out["exact_scaling"] = scene.lab_test().exact_scaling() && (!scene.is_external() || scene.external().exact_scaling);
  out["parameters"] = json::object();
  for (const auto& [name, p] : scene.parameters()) {
    json item = {{"unit", p.unit}, {"quantity", quantity_name(p.quantity)}, {"stress_like", is_stress_like(p.quantity)},
                 {"value", p.value}, {"low", p.low}, {"high", p.high}, {"shapes_specimen", scene.shapes_specimen(name)},
                 {"si_factor", si_factor_of_unit(p.unit, name)}};
    if (!p.note.empty()) item["note"] = p.note;
    out["parameters"][name] = item;
  }
  out["outputs"] = json::object();
  for (const OutputSpec& o : scene.lab_test().outputs(scene)) out["outputs"][o.name] = flagged_output_json(o, scene);
  out["curve_axes"] = axes_json(scene.lab_test());
  out["curve_confinements_MPa"] = confinements_json(scene);
  out["contacts"] = json::object();
  for (const ContactRole& role : scene.contact_roles())
    out["contacts"][role.name] = {{"model", scene.contacts().at(role.name).model}, {"description", role.description},
                                  {"parameters", scene.contacts().at(role.name).parameters}};
  return out;
}


nlohmann::json describe_scene_set(const SceneSet& set) {
  using json = nlohmann::json;
  if (set.size() == 1) {
    json out = describe_scene(set.scenes()[0]);
    out["scene"] = set.origin();
    return out;
  }
  json out;
  out["scene"] = set.origin();
  out["name"] = set.name();
  out["test"] = "list";
  out["test_description"] = "several lab tests per point, sharing one parameter set";
  out["fingerprint"] = set.fingerprint();
  bool exact_scaling = true;
  for (const Scene& s : set.scenes()) exact_scaling = exact_scaling && s.lab_test().exact_scaling() && (!s.is_external() || s.external().exact_scaling);
  out["exact_scaling"] = exact_scaling;
  out["tests"] = json::array();
  for (std::size_t k = 0; k < set.size(); ++k) {
    const Scene& s = set.scenes()[k];
    out["tests"].push_back({{"scene", s.origin()}, {"name", s.name()}, {"test", s.test()}, {"label", set.label(k)},
                            {"dimension", dimension_json(s.lab_test())}, {"curve_axes", axes_json(s.lab_test())},
                            {"curve_confinements_MPa", confinements_json(s)}});
  }
  // The list's dimension when its tests share one (null when they differ or none is ours).
  out["dimension"] = out["tests"][0]["dimension"];
  for (const json& t : out["tests"])
    if (t["dimension"] != out["dimension"]) out["dimension"] = nullptr;
  out["parameters"] = json::object();
  for (const auto& [name, p] : set.parameters()) {
    out["parameters"][name] = {{"unit", p.unit}, {"quantity", quantity_name(p.quantity)},
                               {"stress_like", is_stress_like(p.quantity)}, {"value", p.value}, {"low", p.low},
                               {"high", p.high}, {"shapes_specimen", set.shapes_specimen(name)},
                               {"si_factor", si_factor_of_unit(p.unit, name)}};
    if (!p.note.empty()) out["parameters"][name]["note"] = p.note;
  }
  out["outputs"] = json::object();
  for (std::size_t k = 0; k < set.size(); ++k)
    for (const OutputSpec& o : set.scenes()[k].lab_test().outputs(set.scenes()[k])) {
      json item = flagged_output_json(o, set.scenes()[k]);
      item["test"] = set.label(k);
      out["outputs"][set.output_name(k, o.name)] = item;
    }
  out["contacts"] = json::object();
  for (std::size_t k = 0; k < set.size(); ++k)
    for (const ContactRole& role : set.scenes()[k].contact_roles())
      out["contacts"][set.label(k)][role.name] = {{"model", set.scenes()[k].contacts().at(role.name).model},
                                                  {"description", role.description},
                                                  {"parameters", set.scenes()[k].contacts().at(role.name).parameters}};
  return out;
}

nlohmann::json describe_registries() {
  // The contact models per engine ("2d", "3d"): each test names its engine's
  // catalog, and the same model name may exist in both with its own keys.
  nlohmann::json names = nlohmann::json::object(), keys = nlohmann::json::object(),
                 peer_names = nlohmann::json::object();
  nlohmann::json tests = nlohmann::json::object(), dimensions = nlohmann::json::object();
  for (const std::string& name : LabTestRegistry::instance().names()) {
    const LabTest& test = LabTestRegistry::instance().find(name, "registry");
    tests[name] = test.description();
    dimensions[name] = dimension_json(test);
    const ContactModelCatalog& models = test.contact_models();
    if (models.dimension().empty() || names.contains(models.dimension())) continue;
    names[models.dimension()] = models.names();
    for (const std::string& model : models.names()) {
      keys[models.dimension()][model] = models.parameter_keys(model);
      peer_names[models.dimension()][model] = models.peer_names(model);
    }
  }
  return {{"tests", LabTestRegistry::instance().names()},
          {"test_descriptions", tests},
          {"test_dimensions", dimensions},
          {"contact_models", names},
          {"contact_model_parameters", keys},
          {"contact_model_peer_names", peer_names}};
}

}  // namespace demcal::dem
