#include "demcal/dem/external_test.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>

#include "demcal/core/atomic_file.hpp"
#include "demcal/core/error.hpp"
#include "demcal/core/file_path.hpp"
#include "demcal/core/fnv_hash.hpp"
#include "demcal/core/json_fields.hpp"
#include "demcal/core/number_format.hpp"
#include "demcal/core/subprocess.hpp"
#include "demcal/core/units.hpp"
#include "demcal/dem/scene.hpp"

namespace demcal::dem {
namespace {

using json = nlohmann::json;
namespace fs = std::filesystem;

// An output's optional "range": [low, high], null for an open end (default: any value).
OutputRange output_range(const json& output, const std::string& where) {
  OutputRange range;
  if (!output.contains("range")) return range;
  const json& r = output.at("range");
  const auto end = [&](std::size_t k, double open) {
    if (r.at(k).is_null()) return open;
    if (!r.at(k).is_number() || !std::isfinite(r.at(k).get<double>()))
      throw Error(where + ".range: each end must be a number or null (open)");
    return r.at(k).get<double>();
  };
  if (!r.is_array() || r.size() != 2) throw Error(where + ".range: must be [low, high] (null for an open end)");
  range.low = end(0, -std::numeric_limits<double>::infinity());
  range.high = end(1, std::numeric_limits<double>::infinity());
  if (!(range.low < range.high)) throw Error(where + ".range: low must be below high");
  return range;
}

const char* const kBuiltinPlaceholders[] = {"seed", "params_json", "out_json", "workdir", "scene_dir"};

bool identifier_char(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }

// Calls `found(name)` for every {name} in `text` (name: letters, digits, '_');
// other braces are left alone.
template <class F>
void for_each_placeholder(const std::string& text, F found) {
  for (std::size_t open = text.find('{'); open != std::string::npos; open = text.find('{', open + 1)) {
    const std::size_t close = text.find('}', open + 1);
    if (close == std::string::npos) return;
    const std::string name = text.substr(open + 1, close - open - 1);
    if (!name.empty() && std::all_of(name.begin(), name.end(), identifier_char)) found(name, open, close);
  }
}

std::string read_whole_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// The last non-empty line of a file (a command's stderr), shortened.
std::string last_line(const std::string& path) {
  std::istringstream lines(read_whole_file(path));
  std::string line, last;
  while (std::getline(lines, line))
    if (line.find_first_not_of(" \t\r") != std::string::npos) last = line;
  if (last.size() > 200) last = last.substr(0, 200) + "...";
  return last;
}

// Where an input is copied in a point's folder: its path as the scene names
// it, unless that climbs out of the folder (then its own name).
std::string copied_name(const std::string& input) {
  if (input.empty() || input[0] == '/' || input.find("..") != std::string::npos) return file_name(input);
  return input;
}

}  // namespace

ExternalSpec parse_external_spec(const json& root, const std::string& origin,
                                 const std::map<std::string, SceneParameter>& parameters) {
  ExternalSpec spec;
  const std::size_t slash = origin.find_last_of('/');
  spec.scene_dir = slash == std::string::npos ? "." : origin.substr(0, slash);
  if (!root.contains("command") || !root.at("command").is_array() || root.at("command").empty())
    throw Error(origin + ": command: missing (a list of arguments, program first: [\"python3\", \"run_point.py\", ...])");
  const json& command = root.at("command");
  for (std::size_t k = 0; k < command.size(); ++k) {
    const std::string where = origin + ": command[" + std::to_string(k) + "]";
    if (!command[k].is_string()) throw Error(where + ": must be a string (the command runs without a shell)");
    spec.command.push_back(command[k].get<std::string>());
    for_each_placeholder(spec.command.back(), [&](const std::string& name, std::size_t, std::size_t) {
      const bool builtin = std::find(std::begin(kBuiltinPlaceholders), std::end(kBuiltinPlaceholders), name) !=
                           std::end(kBuiltinPlaceholders);
      if (!builtin && !parameters.count(name)) {
        std::string known;
        for (const auto& [p, unused] : parameters) known += ", {" + p + "}";
        throw Error(where + ": placeholder {" + name + "} is neither a parameter of the scene nor one of {seed}, "
                    "{params_json}, {out_json}, {workdir}, {scene_dir}" + (known.empty() ? "" : " (parameters: " +
                    known.substr(2) + ")"));
      }
    });
  }
  if (spec.command[0].empty()) throw Error(origin + ": command[0]: the program is empty");
  if (root.contains("workdir")) {
    if (!root.at("workdir").is_string() || root.at("workdir").get<std::string>().empty())
      throw Error(origin + ": workdir: must be \"per_point\" or a folder");
    const std::string w = root.at("workdir").get<std::string>();
    spec.per_point = w == "per_point";
    if (!spec.per_point) spec.shared_workdir = path_beside(origin, w);
  }
  if (root.contains("timeout_s")) {
    const json& t = root.at("timeout_s");
    if (!t.is_number() || !(t.get<double>() > 0) || !std::isfinite(t.get<double>()))
      throw Error(origin + ": timeout_s: must be a positive number of seconds");
    spec.timeout_s = t.get<double>();
  }
  if (root.contains("exact_scaling")) {
    if (!root.at("exact_scaling").is_boolean()) throw Error(origin + ": exact_scaling: must be true or false");
    spec.exact_scaling = root.at("exact_scaling").get<bool>();
  }
  std::string hashed;
  if (root.contains("inputs")) {
    if (!root.at("inputs").is_array()) throw Error(origin + ": inputs: must be a list of files (relative to the scene)");
    for (std::size_t k = 0; k < root.at("inputs").size(); ++k) {
      const json& item = root.at("inputs")[k];
      const std::string where = origin + ": inputs[" + std::to_string(k) + "]";
      if (!item.is_string() || item.get<std::string>().empty()) throw Error(where + ": must be a file name");
      const std::string path = path_beside(origin, item.get<std::string>());
      if (!fs::is_regular_file(path)) throw Error(where + ": " + path + " is not a file");
      spec.inputs.push_back(item.get<std::string>());
      spec.input_paths.push_back(path);
      hashed += item.get<std::string>() + "\n" + read_whole_file(path) + "\n";
    }
  }
  char buffer[20];
  std::snprintf(buffer, sizeof buffer, "%016llx", static_cast<unsigned long long>(fnv1a_64(hashed)));
  spec.inputs_hash = buffer;
  if (!root.contains("outputs") || !root.at("outputs").is_object() || root.at("outputs").empty())
    throw Error(origin + ": outputs: missing (an object of name: {\"unit\": ...} for what the command reports)");
  for (auto it = root.at("outputs").begin(); it != root.at("outputs").end(); ++it) {
    const std::string where = origin + ": outputs." + it.key();
    if (!it.value().is_object()) throw Error(where + ": must be an object {\"unit\": ..., \"description\": ...}");
    require_known_fields(it.value(), {"unit", "description", "range"}, where);
    if (!it.value().contains("unit") || !it.value().at("unit").is_string())
      throw Error(where + ": missing \"unit\" (a string such as \"MPa\", or \"1\" for dimensionless)");
    const std::string unit = it.value().at("unit").get<std::string>();
    quantity_of_unit(unit, where + ".unit");  // a unit the study layer can read (stress-like or not)
    if (it.value().contains("description") && !it.value().at("description").is_string())
      throw Error(where + ": \"description\" must be a string");
    spec.outputs.push_back({it.key(), unit, it.value().value("description", "reported by the external command"), true,
                            output_range(it.value(), where)});
  }
  return spec;
}

std::vector<std::string> expand_command(const ExternalSpec& spec, const std::map<std::string, double>& parameters,
                                        std::uint64_t seed, const std::string& params_json,
                                        const std::string& out_json, const std::string& workdir) {
  std::vector<std::string> out;
  for (const std::string& arg : spec.command) {
    std::string expanded;
    std::size_t copied = 0;
    for_each_placeholder(arg, [&](const std::string& name, std::size_t open, std::size_t close) {
      std::string value;
      if (name == "seed") value = std::to_string(seed);
      else if (name == "params_json") value = params_json;
      else if (name == "out_json") value = out_json;
      else if (name == "workdir") value = workdir;
      else if (name == "scene_dir") value = spec.scene_dir;
      else value = format_double(parameters.at(name));
      expanded += arg.substr(copied, open - copied) + value;
      copied = close + 1;
    });
    out.push_back(expanded + arg.substr(copied));
  }
  return out;
}

void read_external_outputs(const std::string& out_json, const ExternalSpec& spec, TestResult& result) {
  result.ok = false;
  if (!fs::exists(out_json)) {
    result.reason = "the command wrote no " + file_name(out_json);
    return;
  }
  const std::string text = read_whole_file(out_json);
  json out;
  try {
    out = json::parse(text);
  } catch (const json::parse_error& e) {
    const bool non_finite = text.find("NaN") != std::string::npos || text.find("Infinity") != std::string::npos;
    result.reason = file_name(out_json) + " is not JSON" +
                    (non_finite ? " (it holds NaN or Infinity, which JSON has no numbers for: an output is not a finite number)"
                                : std::string(": ") + e.what());
    return;
  }
  if (!out.is_object() || !out.contains("status") || !out.at("status").is_string() ||
      (out.at("status") != "ok" && out.at("status") != "failed")) {
    result.reason = file_name(out_json) + ": \"status\" must be \"ok\" or \"failed\"";
    return;
  }
  if (out.at("status") == "failed") {
    const json reason = out.value("reason", json("no reason given"));
    result.reason = "the command reported failure: " + (reason.is_string() ? reason.get<std::string>() : reason.dump());
    return;
  }
  if (!out.contains("outputs") || !out.at("outputs").is_object()) {
    result.reason = file_name(out_json) + ": status \"ok\" without an \"outputs\" object";
    return;
  }
  const json& values = out.at("outputs");
  for (const OutputSpec& o : spec.outputs) {
    if (!values.contains(o.name)) {
      result.reason = file_name(out_json) + ": output " + o.name + " is missing";
      return;
    }
    const json& v = values.at(o.name);
    if (!v.is_number() || !std::isfinite(v.get<double>())) {
      result.reason = file_name(out_json) + ": output " + o.name + " is not a finite number (got " + v.dump() + ")";
      return;
    }
    result.macro[o.name] = v.get<double>();
  }
  for (auto it = values.begin(); it != values.end(); ++it)  // extra numbers are kept beside the declared ones
    if (!result.macro.count(it.key()) && it.value().is_number()) result.extra_outputs[it.key()] = it.value().get<double>();
  if (out.contains("curve")) {
    const json& c = out.at("curve");
    auto column = [&](const char* name) -> std::vector<double> {
      std::vector<double> v;
      if (c.is_object() && c.contains(name) && c.at(name).is_array())
        for (const json& x : c.at(name)) v.push_back(x.is_number() ? x.get<double>() : std::nan(""));
      return v;
    };
    const std::vector<double> strain = column("axial_strain"), stress = column("stress_MPa"),
                              lateral = column("lateral_strain");
    if (strain.empty() || strain.size() != stress.size() || (!lateral.empty() && lateral.size() != strain.size())) {
      result.reason = file_name(out_json) + ": curve: needs equally long lists axial_strain and stress_MPa "
                      "(lateral_strain optional)";
      return;
    }
    for (std::size_t k = 0; k < strain.size(); ++k) {
      CurvePoint p;
      p.axial_strain = strain[k];
      p.stress_pa = stress[k] * 1e6;
      p.lateral_strain = lateral.empty() ? 0.0 : lateral[k];
      result.curve.push_back(p);
    }
  }
  result.ok = true;
}

namespace {

class ExternalTest : public LabTest {
 public:
  std::string name() const override { return "external"; }
  std::string description() const override {
    return "an external command (another simulator) run per point: parameters in, outputs from its out.json";
  }
  int dimension() const override { return 0; }  // the command's simulator decides
  const ContactModelCatalog& contact_models() const override { return no_contact_models(); }
  std::vector<BoundaryRole> boundary_roles() const override { return {}; }
  std::vector<ContactRole> specimen_roles(const Scene&) const override { return {}; }
  std::vector<OutputSpec> outputs(const Scene& scene) const override { return scene.external().outputs; }
  TestResult run(const Scene& scene, const std::map<std::string, double>& parameters,
                 const RunOptions& options) const override {
    const ExternalSpec& spec = scene.external();
    if (options.work_dir.empty())
      throw Error(scene.origin() + ": an external test needs a folder for its files (demcal-dem run: --work DIR)");
    fs::create_directories(options.work_dir);
    const std::string point_dir = fs::absolute(options.work_dir).lexically_normal().string();
    const std::string params_json = point_dir + "/params.json", out_json = point_dir + "/out.json";
    fs::remove(out_json);  // a result is only ever what this run wrote
    json params = {{"parameters", parameters}, {"seed", options.seed}};
    write_file_atomically(params_json, params.dump(1) + "\n");
    std::string cwd = point_dir;
    if (spec.per_point) {
      for (std::size_t k = 0; k < spec.inputs.size(); ++k) {
        const fs::path target = fs::path(point_dir) / copied_name(spec.inputs[k]);
        fs::create_directories(target.parent_path());
        fs::copy_file(spec.input_paths[k], target, fs::copy_options::overwrite_existing);
      }
    } else {
      fs::create_directories(spec.shared_workdir);
      cwd = fs::absolute(spec.shared_workdir).lexically_normal().string();
    }
    const std::vector<std::string> argv = expand_command(spec, parameters, options.seed, params_json, out_json, cwd);
    const std::string stderr_path = point_dir + "/stderr.txt";
    const CommandOutcome outcome = run_command(argv, cwd, point_dir + "/stdout.txt", stderr_path, spec.timeout_s);
    TestResult result;
    result.wall_s = result.test_wall_s = outcome.wall_s;
    if (!outcome.started || outcome.timed_out || outcome.signal != 0 || outcome.exit_status != 0) {
      result.reason = describe_outcome(outcome, spec.command[0]);
      const std::string said = outcome.started ? last_line(stderr_path) : "";
      if (!said.empty()) result.reason += "; stderr: " + said;
      return result;
    }
    read_external_outputs(out_json, spec, result);
    return result;
  }
};

}  // namespace

void register_external_test(LabTestRegistry& registry) { registry.add(std::make_unique<ExternalTest>()); }

}  // namespace demcal::dem
