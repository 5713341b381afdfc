#pragma once
// The message a scene's loading throws (a demcal::Error), or "" when it loads:
// the scene is written to a scratch file `file_name` first, so the message
// names that file as it would name the user's.
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "demcal/core/error.hpp"
#include "demcal/dem/scene.hpp"
#include "scratch.hpp"

namespace demcal::test {

inline std::string scene_error(const nlohmann::json& scene, const std::string& file_name) {
  const std::string path = scratch_path(file_name);
  std::ofstream(path) << scene.dump();
  try {
    dem::Scene::load(path);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

}  // namespace demcal::test
