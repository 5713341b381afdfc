#pragma once
// The lab tests one design point runs: a scene, or several scenes that share
// one parameter set (a rock calibrated against UCS, Brazilian and biaxial
// tests at once). Everything that runs points (batches, shards, MPI, the DEM
// in the loop, verification) takes a SceneSet, so a test list works wherever
// a scene does.
//
// A test list is a file of its own:
//
//   {"name": "rock_three_tests", "description": "...",
//    "tests": ["ucs_rock_pb.json", "brazilian_rock_pb.json", "biaxial_rock_pb.json"]}
//
// (paths relative to it). Every scene runs with the point's seed. A parameter
// two scenes share must agree on its unit, bounds and default. Outputs keep
// their names where one test has them and take the test's name as a prefix
// where several do (`ucs.E_GPa`, `brazilian.cracks_tension`); the scene's
// name is the prefix instead when two scenes run the same test.
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "demcal/dem/lab_test.hpp"
#include "demcal/dem/scene.hpp"

namespace demcal::dem {

class SceneSet {
 public:
  // A scene file (a set of one) or a test list.
  static SceneSet load(const std::string& path);
  // A set of already loaded scenes; `origin` names it in messages.
  static SceneSet of(std::vector<Scene> scenes, const std::string& origin, const std::string& name);
  // Whether the file is a test list (it has "tests").
  static bool is_test_list(const std::string& path);

  // Writes the set at `path` with every specimen's disk radii divided by
  // `factor` (Scene::with_finer_disks) as `out_path` (a list also writes its
  // finer scenes beside it) and returns out_path.
  static std::string write_with_finer_disks(const std::string& path, double factor, const std::string& out_path);

  const std::vector<Scene>& scenes() const { return scenes_; }
  std::size_t size() const { return scenes_.size(); }
  // The prefix of scene k's clashing outputs and its label in messages: its
  // test's name, or its own name when another scene runs the same test.
  const std::string& label(std::size_t k) const { return labels_[k]; }
  const std::string& origin() const { return origin_; }
  const std::string& name() const { return name_; }
  // A set of one has its scene's fingerprint (its stored results stay
  // valid); a list combines its scenes' with their labels.
  const std::string& fingerprint() const { return fingerprint_; }
  // The union of the scenes' parameters.
  const std::map<std::string, SceneParameter>& parameters() const { return parameters_; }
  // Defaults with `overrides` applied (each checked against its bounds); an
  // override no scene declares is an error.
  std::map<std::string, double> resolve(const std::map<std::string, double>& overrides) const;
  void check_space(const ParameterSpace& space, const std::string& space_path) const;
  bool shapes_specimen(const std::string& parameter) const;
  // The specimens a point at `parameters` needs packed, one per scene that
  // packs one (LabTest::specimens_to_pack; an external test packs its own).
  std::vector<SpecimenToPack> specimens(const std::map<std::string, double>& parameters, std::uint64_t seed) const;

  // Every output under its name in the set, in scene order.
  std::vector<OutputSpec> outputs() const;
  // The name in the set of scene k's output `name`.
  std::string output_name(std::size_t k, const std::string& name) const;

  // Runs every scene's test at `parameters` (its own ones taken from them)
  // with options.seed; the point's result as JSON (status, reason, macro,
  // parameters, seed, cost, curve). A set of one gives exactly its test's
  // result_json plus its curve. A list stops at the first test that fails
  // (the point fails with that test's label and reason), sums the cost
  // (`test_runs` counts the tests run), keeps each test's own result under
  // "tests" and its curve's columns as "LABEL.column". Bad input throws.
  nlohmann::json run(const std::map<std::string, double>& parameters, const RunOptions& options) const;

 private:
  std::vector<Scene> scenes_;
  std::vector<std::string> labels_;
  std::string origin_, name_, fingerprint_;
  std::map<std::string, SceneParameter> parameters_;
  std::map<std::string, int> output_count_;  // in how many scenes each output name occurs
};

}  // namespace demcal::dem
