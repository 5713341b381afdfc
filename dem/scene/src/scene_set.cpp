#include "demcal/dem/scene_set.hpp"

#include <sys/stat.h>

#include <algorithm>
#include <cctype>
#include <cstdio>

#include "demcal/core/atomic_file.hpp"
#include "demcal/core/error.hpp"
#include "demcal/core/file_path.hpp"
#include "demcal/core/fnv_hash.hpp"
#include "demcal/core/json_fields.hpp"
#include "demcal/core/number_format.hpp"
#include "demcal/dem/result_json.hpp"

namespace demcal::dem {
namespace {

using json = nlohmann::json;

// A scene's own parameters out of the set's (a resolved set holds them all).
std::map<std::string, double> own_parameters(const Scene& scene, const std::map<std::string, double>& parameters) {
  std::map<std::string, double> own;
  for (const auto& [name, p] : scene.parameters()) own[name] = parameters.at(name);
  return own;
}

std::string set_fingerprint(const std::string& text) {
  char buffer[40];
  std::snprintf(buffer, sizeof buffer, "%016llx-set", static_cast<unsigned long long>(fnv1a_64(text)));
  return buffer;
}

}  // namespace

bool SceneSet::is_test_list(const std::string& path) {
  const json root = read_json_file(path, "scene file");
  return root.is_object() && root.contains("tests");
}

SceneSet SceneSet::load(const std::string& path) {
  const json root = read_json_file(path, "scene file");
  if (!root.is_object() || !root.contains("tests")) {
    Scene scene = Scene::load(path);
    const std::string name = scene.name();
    return of({std::move(scene)}, path, name);
  }
  if (root.contains("test"))
    throw Error(path + ": a file has either \"test\" (a scene) or \"tests\" (a list of scene files), not both");
  require_known_fields(root, {"name", "description", "tests"}, path);
  const json& list = root.at("tests");
  if (!list.is_array() || list.empty())
    throw Error(path + ": \"tests\" must be a non-empty list of scene files, e.g. [\"ucs_rock_pb.json\", \"brazilian_rock_pb.json\"]");
  std::vector<Scene> scenes;
  for (std::size_t k = 0; k < list.size(); ++k) {
    if (!list[k].is_string() || list[k].get<std::string>().empty())
      throw Error(path + ": tests: entry " + std::to_string(k + 1) + " must be the path of a scene file");
    const std::string scene_path = path_beside(path, list[k].get<std::string>());
    if (is_test_list(scene_path))
      throw Error(path + ": tests: " + list[k].get<std::string>() + " is itself a test list (name its scenes instead)");
    scenes.push_back(Scene::load(scene_path));
  }
  if (root.contains("name") && !root.at("name").is_string()) throw Error(path + ": \"name\" must be a string");
  return of(std::move(scenes), path, root.value("name", std::string("tests")));
}

std::string SceneSet::write_with_finer_disks(const std::string& path, double factor, const std::string& out_path) {
  const json root = read_json_file(path, "scene file");
  if (!root.is_object() || !root.contains("tests")) {
    write_file_atomically(out_path, Scene::with_finer_disks(Scene::resolved_json(path), factor, path).dump(1) + "\n");
    return out_path;
  }
  const SceneSet set = load(path);  // checks the list
  json list = root;
  list["tests"] = json::array();
  const std::string stem = out_path.substr(0, out_path.rfind(".json"));
  for (std::size_t k = 0; k < set.size(); ++k) {
    const std::string scene_path = stem + "." + set.label(k) + ".json";
    json finer = Scene::with_finer_disks(Scene::resolved_json(set.scenes()[k].origin()), factor, set.scenes()[k].origin());
    finer["name"] = set.scenes()[k].name();  // the same labels, so the outputs keep their names
    write_file_atomically(scene_path, finer.dump(1) + "\n");
    // Entries are relative to the list file, which sits beside them.
    list["tests"].push_back(file_name(scene_path));
  }
  write_file_atomically(out_path, list.dump(1) + "\n");
  return out_path;
}

SceneSet SceneSet::of(std::vector<Scene> scenes, const std::string& origin, const std::string& name) {
  if (scenes.empty()) throw Error(origin + ": no scene");
  SceneSet set;
  set.origin_ = origin;
  set.name_ = name;
  set.scenes_ = std::move(scenes);
  // Labels: the test's name, unless another scene runs the same test. A
  // label prefixes output names and names files, so it is a plain word.
  for (const Scene& s : set.scenes_) {
    const auto same_test = std::count_if(set.scenes_.begin(), set.scenes_.end(),
                                         [&](const Scene& o) { return o.test() == s.test(); });
    const std::string label = same_test > 1 ? s.name() : s.test();
    const bool plain = !label.empty() && std::all_of(label.begin(), label.end(), [](char ch) {
      return std::isalnum(static_cast<unsigned char>(ch)) || ch == '_' || ch == '-';
    });
    if (!plain)
      throw Error(origin + ": tests: " + s.origin() + ": its name \"" + label +
                  "\" labels its outputs (another scene runs the same test) and must be letters, digits, '_' or '-'");
    set.labels_.push_back(label);
  }
  for (std::size_t a = 0; a < set.labels_.size(); ++a)
    for (std::size_t b = a + 1; b < set.labels_.size(); ++b)
      if (set.labels_[a] == set.labels_[b])
        throw Error(origin + ": tests: " + set.scenes_[a].origin() + " and " + set.scenes_[b].origin() +
                    " run the same test under the same scene name \"" + set.labels_[a] + "\" (give them different names)");
  // Shared parameters must mean the same thing in every scene.
  for (const Scene& s : set.scenes_)
    for (const auto& [pname, p] : s.parameters()) {
      auto [it, fresh] = set.parameters_.emplace(pname, p);
      if (fresh) continue;
      const SceneParameter& q = it->second;
      auto differ = [&](const std::string& what, const std::string& here, const std::string& there) {
        std::string first;
        for (const Scene& o : set.scenes_)
          if (o.parameters().count(pname)) {
            first = o.origin();
            break;
          }
        throw Error(origin + ": tests: parameter \"" + pname + "\" has " + what + " " + here + " in " + s.origin() +
                    " but " + there + " in " + first + " (the tests of a point share one parameter set)");
      };
      if (p.unit != q.unit) differ("unit", "\"" + p.unit + "\"", "\"" + q.unit + "\"");
      if (p.low != q.low || p.high != q.high)
        differ("bounds", "[" + format_double(p.low) + ", " + format_double(p.high) + "]",
               "[" + format_double(q.low) + ", " + format_double(q.high) + "]");
      if (p.value != q.value) differ("default", format_double(p.value), format_double(q.value));
    }
  for (const Scene& s : set.scenes_)
    for (const OutputSpec& o : s.lab_test().outputs(s)) ++set.output_count_[o.name];
  if (set.scenes_.size() == 1) {
    set.fingerprint_ = set.scenes_[0].fingerprint();
  } else {
    std::string text;
    for (std::size_t k = 0; k < set.scenes_.size(); ++k) text += set.labels_[k] + "=" + set.scenes_[k].fingerprint() + ";";
    set.fingerprint_ = set_fingerprint(text);
  }
  return set;
}

std::map<std::string, double> SceneSet::resolve(const std::map<std::string, double>& overrides) const {
  for (const auto& [pname, value] : overrides)
    if (!parameters_.count(pname)) {
      std::string list;
      for (const auto& [known, p] : parameters_) list += (list.empty() ? "" : ", ") + known;
      throw Error(origin_ + ": unknown parameter \"" + pname + "\" (" + (size() > 1 ? "the tests' " : "scene ") +
                  "parameters: " + list + ")");
    }
  std::map<std::string, double> values;
  for (const Scene& s : scenes_) {
    std::map<std::string, double> own;
    for (const auto& [pname, value] : overrides)
      if (s.parameters().count(pname)) own[pname] = value;
    for (const auto& [pname, value] : s.resolve(own)) values[pname] = value;
  }
  return values;
}

void SceneSet::check_space(const ParameterSpace& space, const std::string& space_path) const {
  if (size() == 1) return scenes_[0].check_space(space, space_path);
  check_space_against(parameters_, origin_, space, space_path);
}

bool SceneSet::shapes_specimen(const std::string& parameter) const {
  return std::any_of(scenes_.begin(), scenes_.end(), [&](const Scene& s) { return s.shapes_specimen(parameter); });
}

std::vector<SpecimenToPack> SceneSet::specimens(const std::map<std::string, double>& parameters,
                                                std::uint64_t seed) const {
  std::vector<SpecimenToPack> out;
  for (const Scene& s : scenes_)
    for (SpecimenToPack& p : s.lab_test().specimens_to_pack(s, own_parameters(s, parameters), seed))
      out.push_back(std::move(p));
  return out;
}

std::string SceneSet::output_name(std::size_t k, const std::string& name) const {
  auto it = output_count_.find(name);
  return it != output_count_.end() && it->second > 1 ? labels_[k] + "." + name : name;
}

std::vector<OutputSpec> SceneSet::outputs() const {
  std::vector<OutputSpec> out;
  for (std::size_t k = 0; k < size(); ++k)
    for (OutputSpec o : scenes_[k].lab_test().outputs(scenes_[k])) {
      o.name = output_name(k, o.name);
      if (size() > 1) o.description = labels_[k] + ": " + o.description;
      out.push_back(o);
    }
  return out;
}

json SceneSet::run(const std::map<std::string, double>& parameters, const RunOptions& options) const {
  if (size() == 1) {
    const TestResult r = run_test(scenes_[0], parameters, options);
    json out = result_json(r, parameters, options.seed);
    out["curve"] = curve_json(r);
    return out;
  }
  json out;
  out["parameters"] = parameters;
  out["seed"] = options.seed;
  out["macro"] = json::object();
  out["tests"] = json::object();
  out["curve"] = json::object();
  std::size_t particles = 0;
  std::uint64_t steps = 0;
  double wall_s = 0, test_wall_s = 0, particle_steps = 0, dt_s = 0;
  int threads = 0, runs = 0;
  std::string ended_by, reason;
  for (std::size_t k = 0; k < size() && reason.empty(); ++k) {
    const Scene& s = scenes_[k];
    const std::map<std::string, double> own = own_parameters(s, parameters);
    RunOptions own_options = options;
    if (!options.vtk_dir.empty()) {
      ::mkdir(options.vtk_dir.c_str(), 0755);
      own_options.vtk_dir = options.vtk_dir + "/" + labels_[k];
    }
    if (!options.work_dir.empty()) own_options.work_dir = options.work_dir + "/" + labels_[k];
    TestResult r;
    try {
      r = run_test(s, own, own_options);
    } catch (const std::exception& e) {  // bad input for this test: the point fails naming it
      r = TestResult{};
      r.reason = e.what();
    }
    ++runs;
    json one = result_json(r, own, options.seed);
    one.erase("seed");
    one["scene"] = s.origin();
    out["tests"][labels_[k]] = one;
    const json curve = curve_json(r);  // items() must not outlive it
    for (const auto& [column, values] : curve.items()) out["curve"][labels_[k] + "." + column] = values;
    particles += r.particles;
    steps += r.steps;
    particle_steps += static_cast<double>(r.particles) * static_cast<double>(r.steps);
    wall_s += r.wall_s;
    test_wall_s += r.test_wall_s;
    threads = std::max(threads, r.threads);
    dt_s = k == 0 ? r.dt_s : std::min(dt_s, r.dt_s);
    if (!r.ok) {
      reason = labels_[k] + ": " + r.reason;
      break;
    }
    for (const auto& [name, value] : r.macro) out["macro"][output_name(k, name)] = value;
    if (!r.ended_by.empty()) ended_by += (ended_by.empty() ? "" : "; ") + labels_[k] + ": " + r.ended_by;
  }
  out["status"] = reason.empty() ? "ok" : "failed";
  out["reason"] = reason;
  if (!reason.empty()) out["macro"] = json::object();  // a point is all its tests or nothing
  if (!ended_by.empty()) out["ended_by"] = ended_by;
  out["test_runs"] = runs;
  out["particles"] = particles;
  out["steps"] = steps;
  out["dt_s"] = dt_s;
  out["wall_s"] = wall_s;
  out["test_wall_s"] = test_wall_s;
  out["threads"] = threads;
  out["particle_steps_per_s"] = test_wall_s > 0 ? particle_steps / test_wall_s : 0.0;
  return out;
}

}  // namespace demcal::dem
