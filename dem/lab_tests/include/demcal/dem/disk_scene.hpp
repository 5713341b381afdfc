#pragma once
// What a 2D test reads from a scene: the disk engine's contact models (as the
// scene layer's catalog, and bound into a World), the packed specimen of the
// "specimen" section and a concrete's "aggregates"; and PackedTest, the base
// of every test of a packed specimen (uniaxial, Brazilian, biaxial, wave
// strip), which declares those sections, the specimen's roles and what a
// batch packs.
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "demcal/dem/aggregates.hpp"
#include "demcal/dem/genesis.hpp"
#include "demcal/dem/lab_test.hpp"
#include "demcal/dem/scene.hpp"

namespace demcal::dem {

class World;

// The disk engine's contact models (ContactModelRegistry) as the scene layer sees them.
const ContactModelCatalog& disk_contact_models();

// Creates a model for each of the scene's contact roles (in the order of
// contact_roles(), bound to `parameters`) and assigns it to the role's groups.
void bind_contact_models(World& world, const Scene& scene, const std::map<std::string, double>& parameters);

// The scene's "specimen" section at `parameters`: a prism (width_m,
// height_m) or a disc (diameter_m, cut from a square packing), radii,
// porosity, density, stresses.
SpecimenSpec specimen_spec(const Scene& scene, const std::map<std::string, double>& parameters, std::uint64_t seed);
// The scene's "aggregates" section (sizes in mm as engineers give them);
// empty for a one-phase specimen. Throws an Error naming the file and field.
std::optional<AggregateSpec> scene_aggregates(const Scene& scene);

// A 2D test of a packed specimen: reads "specimen" (required), "aggregates"
// and "loading", plus the sections extra_sections() names.
class PackedTest : public LabTest {
 public:
  int dimension() const override { return 2; }
  const ContactModelCatalog& contact_models() const override { return disk_contact_models(); }
  std::vector<SceneSection> sections() const final;
  // The sections beyond the packed specimen's (a wave strip's "boundaries", "pulse").
  virtual std::vector<SceneSection> extra_sections() const { return {}; }
  std::vector<ContactRole> specimen_roles(const Scene& scene) const override;
  // Checks the specimen and the aggregates, then check_extra_sections.
  void check_scene(const Scene& scene) const final;
  virtual void check_extra_sections(const Scene& scene) const { (void)scene; }
  std::vector<SpecimenToPack> specimens_to_pack(const Scene& scene, const std::map<std::string, double>& parameters,
                                                std::uint64_t seed) const override;
};

}  // namespace demcal::dem
