#include "demcal/dem/specimen_roles.hpp"

#include "demcal/dem/concrete_specimen.hpp"

namespace demcal::dem {

namespace {
constexpr std::uint8_t kMortarGroup = 0;  // the disks of a one-phase specimen, or a concrete's mortar
}

std::vector<ContactRole> specimen_contact_roles(bool concrete) {
  if (!concrete) return {{"particle-particle", {{kMortarGroup, kMortarGroup}}, "the specimen's disks against each other"}};
  return {{"mortar-mortar", {{kMortarGroup, kMortarGroup}}, "mortar disks against each other"},
          {"mortar-aggregate", {{kMortarGroup, kAggregateGroup}}, "the interfacial transition zone (ITZ)"},
          {"aggregate-aggregate", {{kAggregateGroup, kAggregateGroup}}, "two aggregates in contact"}};
}

std::vector<std::uint8_t> specimen_groups(bool concrete) {
  if (!concrete) return {kMortarGroup};
  return {kMortarGroup, kAggregateGroup};
}

}  // namespace demcal::dem
