#include "demcal/core/json_fields.hpp"

#include <sys/stat.h>

#include <cmath>
#include <fstream>
#include <ios>

#include <nlohmann/json.hpp>

#include "demcal/core/error.hpp"

namespace demcal {

void require_known_fields(const nlohmann::json& object, const std::vector<std::string>& allowed,
                          const std::string& where, const char* noun) {
  if (!object.is_object()) throw Error(where + ": must be a JSON object");
  for (auto it = object.begin(); it != object.end(); ++it) {
    bool known = false;
    for (const std::string& key : allowed) known = known || it.key() == key;
    if (known) continue;
    std::string list;
    for (const std::string& key : allowed) list += (list.empty() ? "" : ", ") + key;
    throw Error(where + ": unknown " + noun + " \"" + it.key() + "\" (allowed: " + list + ")");
  }
}

void require_known_fields(const nlohmann::json& object, std::initializer_list<const char*> allowed,
                          const std::string& where, const char* noun) {
  require_known_fields(object, std::vector<std::string>(allowed.begin(), allowed.end()), where, noun);
}

double number_field(const nlohmann::json& object, const char* key, double fallback, const std::string& where) {
  if (!object.contains(key)) return fallback;
  const nlohmann::json& v = object.at(key);
  if (!v.is_number() || !std::isfinite(v.get<double>())) throw Error(where + ": \"" + key + "\" must be a finite number");
  return v.get<double>();
}

std::size_t choice_field(const nlohmann::json& object, const char* key, const std::vector<std::string>& choices,
                         std::size_t fallback, const std::string& where) {
  if (!object.contains(key)) return fallback;
  const nlohmann::json& v = object.at(key);
  for (std::size_t c = 0; c < choices.size(); ++c)
    if (v == choices[c]) return c;
  std::string allowed;
  for (const std::string& c : choices) allowed += (allowed.empty() ? "\"" : " or \"") + c + "\"";
  throw Error(where + ": \"" + key + "\" must be " + allowed + " (got " + v.dump() + ")");
}

nlohmann::json read_json_file(const std::string& path, const std::string& what) {
  struct stat info {};
  if (::stat(path.c_str(), &info) == 0 && S_ISDIR(info.st_mode)) throw Error(path + ": is a folder, not a " + what);
  std::ifstream in(path);
  if (!in) throw Error(path + ": cannot open " + what);
  try {
    return nlohmann::json::parse(in);
  } catch (const nlohmann::json::out_of_range& e) {
    // A number beyond double's range (1e999): nlohmann refuses it while parsing.
    throw Error(path + ": a number is out of range (" + std::string(e.what()) + ")");
  } catch (const nlohmann::json::exception& e) {
    throw Error(path + ": not valid JSON (" + std::string(e.what()) + ")");
  } catch (const std::ios_base::failure& e) {
    throw Error(path + ": cannot read " + what + " (" + std::string(e.what()) + ")");
  }
}

}  // namespace demcal
