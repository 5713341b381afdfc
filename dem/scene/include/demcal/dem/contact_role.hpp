#pragma once
// A contact role of a scene: a name a scene binds a contact model to
// ("particle-particle", a concrete's "mortar-aggregate", a test's
// "particle-platen"), and the pairs of material groups it joins. The same in
// 2D and 3D: a group is a label the test's engine gives its particles and walls.
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace demcal::dem {

struct ContactRole {
  std::string name;
  std::vector<std::pair<std::uint8_t, std::uint8_t>> groups;  // the material groups it joins
  std::string description;
};

// The names the roles had when only disks existed ("disk-disk",
// "disk-platen", "disk-wall"): a scene may still use them. The canonical name
// of `name` (itself when it is no old name).
const std::string& canonical_role_name(const std::string& name);

}  // namespace demcal::dem
