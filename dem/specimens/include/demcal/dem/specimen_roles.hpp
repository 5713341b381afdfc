#pragma once
// The contact roles of a specimen's own pairs, and the material groups of
// its disks: a one-phase specimen has "disk-disk"; a concrete has
// "mortar-mortar", "mortar-aggregate" (the interfacial transition zone) and
// "aggregate-aggregate". A lab test adds the roles of its boundaries.
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

std::vector<ContactRole> specimen_contact_roles(bool concrete);
std::vector<std::uint8_t> specimen_groups(bool concrete);

}  // namespace demcal::dem
