#include "demcal/dem/contact_role.hpp"

#include <map>

namespace demcal::dem {

const std::string& canonical_role_name(const std::string& name) {
  static const std::map<std::string, std::string> old_names = {
      {"disk-disk", "particle-particle"}, {"disk-platen", "particle-platen"}, {"disk-wall", "particle-wall"}};
  auto it = old_names.find(name);
  return it == old_names.end() ? name : it->second;
}

}  // namespace demcal::dem
