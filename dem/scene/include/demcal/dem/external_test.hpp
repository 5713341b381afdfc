#pragma once
// The external test: a scene whose "lab test" is a command of another
// simulator (YADE, PFC, LIGGGHTS, a user's script), so that designs, surfaces,
// inversion and verification run around a DEM that is not ours.
//
//   {"name": "yade_cpm", "test": "external",
//    "command": ["python3", "run_point.py", "--params", "{params_json}", "--out", "{out_json}"],
//    "workdir": "per_point", "timeout_s": 600, "inputs": ["run_point.py"],
//    "parameters": {"young_GPa": {"value": 30, "low": 5, "high": 80, "unit": "GPa"}},
//    "outputs": {"sigma_u_MPa": {"unit": "MPa"}, "E_GPa": {"unit": "GPa"}}}
//
// Placeholders in the command: {NAME} for each parameter (full precision),
// {seed}, {params_json} (a file written before the run:
// {"parameters": {...}, "seed": N}), {out_json} (where the command writes
// {"status": "ok", "outputs": {...}, "curve": {...}} or {"status": "failed",
// "reason": "..."}), {workdir} (the folder it runs in) and {scene_dir} (the
// scene file's folder). The command runs without a shell, in `workdir`:
// "per_point" (default) is the point's own folder beside its stored result,
// where the "inputs" are copied first so that relative names work; another
// value is a folder (relative to the scene file) all points share. The
// point's folder always keeps params.json, out.json, stdout.txt and
// stderr.txt. The inputs' contents enter the scene's fingerprint: editing the
// driver never reuses a result it did not make.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "demcal/dem/lab_test.hpp"

namespace demcal::dem {

struct SceneParameter;

struct ExternalSpec {
  std::vector<std::string> command;
  bool per_point = true;
  std::string shared_workdir;  // when not per_point: the folder, resolved against the scene file
  double timeout_s = 600;
  std::vector<std::string> inputs;          // as the scene names them (relative to it)
  std::vector<std::string> input_paths;     // resolved
  std::string scene_dir;
  std::vector<OutputSpec> outputs;
  std::string inputs_hash;                  // FNV-1a over the inputs' names and contents
  // "exact_scaling": true declares that every stress output scales with the
  // stress-like parameters (as in our bonded DEM); make calibrate then uses
  // the dimensionless form. Off by default: another program need not obey it.
  bool exact_scaling = false;
};

// Reads and checks the external fields of scene `root` (the command, each
// placeholder against the parameters, workdir, timeout, inputs, outputs).
// Throws a one-line Error naming `origin` and the field.
ExternalSpec parse_external_spec(const nlohmann::json& root, const std::string& origin,
                                 const std::map<std::string, SceneParameter>& parameters);

// The command with every placeholder replaced.
std::vector<std::string> expand_command(const ExternalSpec& spec, const std::map<std::string, double>& parameters,
                                        std::uint64_t seed, const std::string& params_json,
                                        const std::string& out_json, const std::string& workdir);

// What a command wrote into its out.json, read into `result` (ok, reason,
// macro, extra outputs, curve): a missing or unreadable file, a status that
// is neither "ok" nor "failed", a declared output that is missing, not a
// number or not finite, all make a failed result saying so.
void read_external_outputs(const std::string& out_json, const ExternalSpec& spec, TestResult& result);

void register_external_test(LabTestRegistry& registry);

}  // namespace demcal::dem
