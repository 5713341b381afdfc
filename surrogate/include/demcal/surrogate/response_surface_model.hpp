#pragma once
// A saved set of response surfaces (one per output, all on the same inputs)
// as a Model, and its JSON form:
//   {"kind": "quadratic"|"linear", "format": ..., "inputs": [{"name","low","high"}],
//    "outputs": [...], "responses": [{"name", "terms": [{"name","inputs"}],
//    "coefficients": {term: natural coefficient}, "coded_coefficients", "coding",
//    statistics, "anova"}],
//    and, for a single output, "coefficients", "r2", "r2_adj", "r2_pred" at the top.}
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "demcal/core/model.hpp"
#include "demcal/surrogate/response_surface.hpp"

namespace demcal::surrogate {

class ResponseSurfaceModel : public BoxModel {
 public:
  struct Surface {
    std::string output;
    std::vector<SurfaceTerm> terms;   // factor indices refer to inputs()
    std::vector<double> coefficients; // natural units, one per term
    // For the prediction interval (empty when the file has none):
    std::vector<FactorCoding> coding;  // per input
    Eigen::MatrixXd coded_covariance;  // (Z'Z)^-1 over terms, coded units
    double s = 0.0;
    int error_df = 0;
  };

  ResponseSurfaceModel(std::vector<InputRange> domain, std::vector<Surface> surfaces);
  static std::unique_ptr<ResponseSurfaceModel> from_json(const nlohmann::json& file, const std::string& origin);

  void predict(const double* x, double* y) const override;
  bool prediction_interval_95(const double* x, double* low, double* high) const override;

 private:
  std::vector<Surface> surfaces_;
};

// The model file of fits made on the same factors (one fit per output).
nlohmann::json surface_model_json(const std::vector<SurfaceFit>& fits, const std::string& data_path);

void register_response_surface_kinds();

}  // namespace demcal::surrogate
