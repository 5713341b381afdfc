#include "demcal/dem/lab_test.hpp"

#include <set>

#include <nlohmann/json.hpp>

#include "demcal/core/error.hpp"
#include "demcal/dem/scene.hpp"

namespace demcal::dem {

// By default every output is a headline (an external command's few).
std::vector<std::string> LabTest::headline_outputs(const Scene& scene) const {
  std::vector<std::string> names;
  for (const OutputSpec& o : outputs(scene)) names.push_back(o.name);
  return names;
}

namespace {

class NoContactModels : public ContactModelCatalog {
 public:
  std::string dimension() const override { return ""; }
  std::vector<std::string> names() const override { return {}; }
  const std::vector<std::string>& parameter_keys(const std::string& model) const override {
    throw Error("contact model \"" + model + "\": this test has no contact models of demcal's");
  }
  const nlohmann::json& peer_names(const std::string& model) const override { return parameter_keys(model), empty_; }
  void check(const std::string& model, const nlohmann::json&, const std::string& where) const override {
    throw Error(where + ": contact model \"" + model + "\": this test has no contact models of demcal's");
  }

 private:
  nlohmann::json empty_ = nlohmann::json::object();
};

}  // namespace

const ContactModelCatalog& no_contact_models() {
  static const NoContactModels none;
  return none;
}

void LabTestRegistry::add(std::unique_ptr<LabTest> test) {
  for (const auto& t : tests_)
    if (t->name() == test->name()) throw Error("lab test \"" + test->name() + "\" is registered twice");
  tests_.push_back(std::move(test));
}

const LabTest& LabTestRegistry::find(const std::string& name, const std::string& where) const {
  for (const auto& t : tests_)
    if (t->name() == name) return *t;
  std::string list;
  for (const auto& t : tests_) list += (list.empty() ? "\"" : ", \"") + t->name() + "\"";
  throw Error(where + ": \"test\" must be one of " + list + " (got \"" + name + "\")");
}

std::vector<std::string> LabTestRegistry::names() const {
  std::vector<std::string> out;
  for (const auto& t : tests_) out.push_back(t->name());
  return out;
}

TestResult run_test(const Scene& scene, const std::map<std::string, double>& parameters, const RunOptions& options) {
  const LabTest& test = LabTestRegistry::instance().find(scene.test(), scene.origin());
  TestResult result = test.run(scene, parameters, options);
  // A test reports what it declares: the study layer and describe rely on it.
  std::set<std::string> declared;
  for (const OutputSpec& o : test.outputs(scene)) {
    declared.insert(o.name);
    if (result.ok && o.always && !result.macro.count(o.name))
      throw Error("lab test " + test.name() + " declares output " + o.name + " but did not report it");
  }
  for (const auto& [name, value] : result.macro)
    if (!declared.count(name)) throw Error("lab test " + test.name() + " reported undeclared output " + name);
  return result;
}

}  // namespace demcal::dem
