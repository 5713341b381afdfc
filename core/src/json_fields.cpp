#include "demcal/core/json_fields.hpp"

#include <fstream>

#include <nlohmann/json.hpp>

#include "demcal/core/error.hpp"

namespace demcal {

void require_known_fields(const nlohmann::json& object, std::initializer_list<const char*> allowed,
                          const std::string& where, const char* noun) {
  if (!object.is_object()) throw Error(where + ": must be a JSON object");
  for (auto it = object.begin(); it != object.end(); ++it) {
    bool known = false;
    for (const char* key : allowed) known = known || it.key() == key;
    if (known) continue;
    std::string list;
    for (const char* key : allowed) list += (list.empty() ? "" : ", ") + std::string(key);
    throw Error(where + ": unknown " + noun + " \"" + it.key() + "\" (allowed: " + list + ")");
  }
}

nlohmann::json read_json_file(const std::string& path, const std::string& what) {
  std::ifstream in(path);
  if (!in) throw Error(path + ": cannot open " + what);
  try {
    return nlohmann::json::parse(in);
  } catch (const nlohmann::json::parse_error& e) {
    throw Error(path + ": not valid JSON (" + std::string(e.what()) + ")");
  }
}

}  // namespace demcal
