#include "demcal/dem/describe.hpp"

#include "demcal/dem/contact_model.hpp"
#include "demcal/dem/lab_test.hpp"

namespace demcal::dem {

nlohmann::json describe_scene(const Scene& scene) {
  using json = nlohmann::json;
  json out;
  out["scene"] = scene.origin();
  out["name"] = scene.name();
  out["test"] = scene.test();
  out["test_description"] = scene.lab_test().description();
  out["fingerprint"] = scene.fingerprint();
  out["parameters"] = json::object();
  for (const auto& [name, p] : scene.parameters()) {
    json item = {{"unit", p.unit}, {"quantity", quantity_name(p.quantity)}, {"stress_like", is_stress_like(p.quantity)},
                 {"value", p.value}, {"low", p.low}, {"high", p.high}, {"shapes_specimen", scene.shapes_specimen(name)},
                 {"si_factor", si_factor_of_unit(p.unit, name)}};
    if (!p.note.empty()) item["note"] = p.note;
    out["parameters"][name] = item;
  }
  out["outputs"] = json::object();
  for (const OutputSpec& o : scene.lab_test().outputs(scene)) {
    const Quantity q = quantity_of_unit(o.unit, "output " + o.name);
    json item = {{"unit", o.unit}, {"description", o.description}, {"quantity", quantity_name(q)},
                 {"stress_like", is_stress_like(q)}, {"si_factor", si_factor_of_unit(o.unit, o.name)}};
    if (!o.always) item["optional"] = true;
    out["outputs"][o.name] = item;
  }
  out["contacts"] = json::object();
  for (const ContactRole& role : scene.contact_roles())
    out["contacts"][role.name] = {{"model", scene.contacts().at(role.name).model}, {"description", role.description}};
  return out;
}

nlohmann::json describe_registries() {
  return {{"tests", LabTestRegistry::instance().names()}, {"contact_models", ContactModelRegistry::instance().names()}};
}

}  // namespace demcal::dem
