#pragma once
// The contact roles of a 2D specimen's own pairs, and the material groups of
// its disks: a one-phase specimen has "particle-particle"; a concrete has
// "mortar-mortar", "mortar-aggregate" (the interfacial transition zone) and
// "aggregate-aggregate". A lab test adds the roles of its boundaries.
#include <cstdint>
#include <vector>

#include "demcal/dem/contact_role.hpp"

namespace demcal::dem {

std::vector<ContactRole> specimen_contact_roles(bool concrete);
std::vector<std::uint8_t> specimen_groups(bool concrete);

}  // namespace demcal::dem
