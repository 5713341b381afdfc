#include "demcal/dem/disk_scene.hpp"

#include <cmath>

#include <nlohmann/json.hpp>

#include "demcal/core/error.hpp"
#include "demcal/core/json_fields.hpp"
#include "demcal/dem/contact_model.hpp"
#include "demcal/dem/specimen_roles.hpp"
#include "demcal/dem/world.hpp"

namespace demcal::dem {
namespace {

using json = nlohmann::json;

// The aggregates object: sizes in mm as engineers give them.
AggregateSpec aggregate_spec(const json& a, const std::string& where) {
  require_known_fields(a, {"size_range_mm", "bins", "coarse_fraction", "sides", "min_gap_m", "density_kg_m3", "max_attempts",
                           "fill", "note"},
                       where);
  AggregateSpec spec;
  // area: Walraven's area per bin; count: its circle-equivalent count.
  spec.fill = choice_field(a, "fill", {"area", "count"}, 0, where) == 0 ? AggregateFill::area : AggregateFill::count;
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

const ContactModelCatalog& disk_contact_models() {
  static const RegistryCatalog<ContactModelRegistry> models("2d");
  return models;
}

void bind_contact_models(World& world, const Scene& scene, const std::map<std::string, double>& parameters) {
  for (const ContactRole& role : scene.contact_roles()) {
    const ContactSpec& c = scene.contacts().at(role.name);
    const std::string where = scene.origin() + ": contacts." + role.name;
    const std::uint8_t model =
        world.add_model(ContactModelRegistry::instance().create(c.model, scene.bind(c, parameters, where), where));
    for (const auto& [a, b] : role.groups) world.assign(a, b, model);
  }
}

SpecimenSpec specimen_spec(const Scene& scene, const std::map<std::string, double>& parameters, std::uint64_t seed) {
  const json& specimen = scene.section("specimen");
  SpecimenSpec spec;
  auto field = [&](const char* key, double& target) {
    if (specimen.contains(key)) target = scene.evaluate(specimen.at(key), parameters, scene.origin() + ": specimen." + key);
  };
  field("width_m", spec.width_m);
  field("height_m", spec.height_m);
  if (specimen.contains("diameter_m")) {  // a Brazilian disc is cut from a square packing
    field("diameter_m", spec.width_m);
    spec.height_m = spec.width_m;
  }
  field("thickness_m", spec.thickness_m);
  field("porosity", spec.porosity);
  field("radius_min_m", spec.radius_min_m);
  field("radius_max_m", spec.radius_max_m);
  field("density_kg_m3", spec.density_kg_m3);
  field("isotropic_stress_pa", spec.isotropic_stress_pa);
  field("locked_in_stress_pa", spec.locked_in_stress_pa);
  spec.seed = seed;
  return spec;
}

std::optional<AggregateSpec> scene_aggregates(const Scene& scene) {
  if (!scene.has_section("aggregates")) return std::nullopt;
  return aggregate_spec(scene.section("aggregates"), scene.origin() + ": aggregates");
}

std::vector<SceneSection> PackedTest::sections() const {
  std::vector<SceneSection> out = {
      {"specimen", "the packed specimen: its size, radii, porosity, density and stresses", true, true,
       {"locked_in_stress_pa"}},  // applied when bonding, after (and apart from) the packing
      {"aggregates", "a concrete's aggregates (Walraven gradation, polygons) placed in the specimen", true, false, {}},
      {"loading", "how the test loads the specimen", false, false, {}}};
  for (const SceneSection& section : extra_sections()) out.push_back(section);
  return out;
}

std::vector<ContactRole> PackedTest::specimen_roles(const Scene& scene) const {
  return specimen_contact_roles(scene.has_section("aggregates"));
}

void PackedTest::check_scene(const Scene& scene) const {
  require_known_fields(scene.section("specimen"),
                       {"width_m", "height_m", "diameter_m", "thickness_m", "porosity", "radius_min_m", "radius_max_m",
                        "density_kg_m3", "isotropic_stress_pa", "locked_in_stress_pa"},
                       scene.origin() + ": specimen");
  scene_aggregates(scene);
  try {
    specimen_spec(scene, scene.resolve({}), 1).validate();
  } catch (const Error& e) {
    throw Error(scene.origin() + ": " + e.what());
  }
  check_extra_sections(scene);
}

std::vector<SpecimenToPack> PackedTest::specimens_to_pack(const Scene& scene,
                                                          const std::map<std::string, double>& parameters,
                                                          std::uint64_t seed) const {
  const SpecimenSpec spec = specimen_spec(scene, parameters, seed);
  return {{spec.cache_key(), [spec](const std::string& cache_dir) { cached_specimen(spec, cache_dir); }}};
}

}  // namespace demcal::dem
