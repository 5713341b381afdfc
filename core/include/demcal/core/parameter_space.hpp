#pragma once
// The micro-parameters of a study: what is varied (with bounds and optional
// discrete levels), what is fixed, and what is tied to another parameter.
//
// JSON layout:
//   {
//     "parameters": [ {"name": "Ec_GPa", "unit": "GPa", "low": 10, "high": 30,
//                      "levels": [10, 20, 30], "reference": 16, "log_scale": false}, ... ],
//     "fixed": {"Ec_g_GPa": 30, ...},
//     "tied":  [ {"name": "pb_Ec_GPa", "source": "Ec_GPa", "factor": 1.0, "offset": 0.0} ]
//   }
#include <nlohmann/json_fwd.hpp>

#include <map>
#include <optional>
#include <string>
#include <vector>

namespace demcal {

struct Parameter {
  std::string name;
  std::string unit;
  double low = 0.0;
  double high = 0.0;
  std::vector<double> levels;        // optional discrete levels, increasing, inside [low, high]
  std::optional<double> reference;   // optional reference value inside [low, high]
  bool log_scale = false;            // coded units map to log(value); needs low > 0

  // Natural value of a coded value where -1 is `low` and +1 is `high`
  // (values beyond +-1, e.g. CCD axial points, extrapolate on the same scale).
  double from_symmetric(double coded) const;
  // Natural value of a unit-interval value where 0 is `low` and 1 is `high`.
  double from_unit(double unit_value) const;
  // Inverse of from_symmetric.
  double to_symmetric(double natural) const;
};

// value = factor * value(source) + offset
struct TiedParameter {
  std::string name;
  std::string source;
  double factor = 1.0;
  double offset = 0.0;
};

class ParameterSpace {
 public:
  // `origin` names where the JSON came from (a file name) for error messages.
  static ParameterSpace from_json(const nlohmann::json& json, const std::string& origin);
  static ParameterSpace load(const std::string& path);
  nlohmann::json to_json() const;

  const std::vector<Parameter>& parameters() const { return parameters_; }
  const std::map<std::string, double>& fixed() const { return fixed_; }
  const std::vector<TiedParameter>& tied() const { return tied_; }
  std::size_t size() const { return parameters_.size(); }

  // Index of a varied parameter; throws an Error naming the known ones.
  std::size_t index_of(const std::string& name) const;
  bool contains(const std::string& name) const;

  // Every value a run needs: the varied ones (in order), the fixed ones and the
  // tied ones computed from them. Throws if `varied` has the wrong size or a
  // value that is not finite. Bounds are not enforced here: CCD axial points
  // legitimately lie outside [low, high].
  std::map<std::string, double> complete(const std::vector<double>& varied) const;

  // Keeps only the named varied parameters; the others become fixed at
  // `fixed_values` (or their reference when not given there).
  ParameterSpace subset(const std::vector<std::string>& keep,
                        const std::map<std::string, double>& fixed_values) const;

 private:
  void validate(const std::string& origin) const;

  std::vector<Parameter> parameters_;
  std::map<std::string, double> fixed_;
  std::vector<TiedParameter> tied_;
};

}  // namespace demcal
