#include "demcal/surrogate/response_surface_model.hpp"

#include <algorithm>
#include <cmath>

#include <boost/math/distributions/students_t.hpp>

#include <nlohmann/json.hpp>

#include "demcal/core/error.hpp"
#include "demcal/surrogate/json_numbers.hpp"
#include "demcal/surrogate/model_file.hpp"

namespace demcal::surrogate {

using nlohmann::json;

namespace {

std::vector<std::string> output_names(const std::vector<ResponseSurfaceModel::Surface>& surfaces) {
  std::vector<std::string> names;
  for (const auto& s : surfaces) names.push_back(s.output);
  return names;
}

}  // namespace

namespace {

// The interval's inputs when the file has them (files written before it did
// simply give no interval).
void read_prediction(const json& response, ResponseSurfaceModel::Surface& s, const std::vector<InputRange>& domain,
                     const std::string& origin) {
  if (!response.contains("prediction_interval") || response.at("prediction_interval").is_null()) return;
  const json& pi = response.at("prediction_interval");
  const json& rows = pi.at("coded_covariance_unscaled");
  const auto p = static_cast<Eigen::Index>(s.terms.size());
  if (!rows.is_array() || static_cast<Eigen::Index>(rows.size()) != p)
    throw Error(origin + ": response " + s.output + ": prediction_interval.coded_covariance_unscaled must be " +
                std::to_string(p) + " x " + std::to_string(p) + " (one row and column per term)");
  s.coded_covariance.resize(p, p);
  for (Eigen::Index i = 0; i < p; ++i) {
    if (!rows[i].is_array() || static_cast<Eigen::Index>(rows[i].size()) != p)
      throw Error(origin + ": response " + s.output + ": prediction_interval row " + std::to_string(i) + " has the wrong length");
    for (Eigen::Index j = 0; j < p; ++j) s.coded_covariance(i, j) = rows[i][j].get<double>();
  }
  s.error_df = pi.at("error_df").get<int>();
  s.s = response.at("s").get<double>();
  const json& coding = response.at("coding");
  for (const InputRange& r : domain) {
    if (!coding.contains(r.name)) throw Error(origin + ": response " + s.output + ": no coding for input " + r.name);
    s.coding.push_back({coding.at(r.name).at("center").get<double>(), coding.at(r.name).at("half_range").get<double>()});
  }
}

}  // namespace

ResponseSurfaceModel::ResponseSurfaceModel(std::vector<InputRange> domain, std::vector<Surface> surfaces)
    : BoxModel(std::move(domain), output_names(surfaces)), surfaces_(std::move(surfaces)) {}

void ResponseSurfaceModel::predict(const double* x, double* y) const {
  for (std::size_t o = 0; o < surfaces_.size(); ++o) {
    const Surface& s = surfaces_[o];
    double v = 0.0;
    for (std::size_t t = 0; t < s.terms.size(); ++t) v += s.coefficients[t] * term_value(s.terms[t], x);
    y[o] = v;
  }
}

bool ResponseSurfaceModel::prediction_interval_95(const double* x, double* low, double* high) const {
  std::vector<double> y(surfaces_.size()), z(inputs().size());
  predict(x, y.data());
  for (std::size_t o = 0; o < surfaces_.size(); ++o) {
    const Surface& s = surfaces_[o];
    if (s.error_df < 1 || s.coding.size() != z.size()) return false;
    for (std::size_t j = 0; j < z.size(); ++j) z[j] = (x[j] - s.coding[j].center) / s.coding[j].half_range;
    Eigen::VectorXd f(static_cast<Eigen::Index>(s.terms.size()));
    for (std::size_t t = 0; t < s.terms.size(); ++t) f(static_cast<Eigen::Index>(t)) = term_value(s.terms[t], z.data());
    // A new observation: s^2 (1 + f' (Z'Z)^-1 f) (Montgomery, Design and Analysis of Experiments, 11.4).
    const double half = boost::math::quantile(boost::math::students_t(s.error_df), 0.975) * s.s *
                        std::sqrt(1.0 + f.dot(s.coded_covariance * f));
    low[o] = y[o] - half;
    high[o] = y[o] + half;
  }
  return true;
}

std::unique_ptr<ResponseSurfaceModel> ResponseSurfaceModel::from_json(const json& file, const std::string& origin) {
  std::vector<InputRange> domain;
  for (const json& input : file.at("inputs"))
    domain.push_back({input.at("name").get<std::string>(), input.at("low").get<double>(), input.at("high").get<double>()});
  if (domain.empty()) throw Error(origin + ": model has no inputs");
  auto input_index = [&](const std::string& name) {
    auto it = std::find_if(domain.begin(), domain.end(), [&](const InputRange& r) { return r.name == name; });
    if (it == domain.end()) throw Error(origin + ": a term names \"" + name + "\", which is not an input");
    return static_cast<int>(it - domain.begin());
  };
  std::vector<Surface> surfaces;
  for (const json& response : file.at("responses")) {
    Surface s;
    s.output = response.at("name").get<std::string>();
    const json& coefficients = response.at("coefficients");
    for (const json& term_json : response.at("terms")) {
      SurfaceTerm term;
      term.name = term_json.at("name").get<std::string>();
      for (const json& input : term_json.at("inputs")) term.factors.push_back(input_index(input.get<std::string>()));
      if (term.factors.size() > 2) throw Error(origin + ": term " + term.name + " has more than two factors");
      if (!coefficients.contains(term.name))
        throw Error(origin + ": response " + s.output + " has no coefficient for term " + term.name);
      s.coefficients.push_back(coefficients.at(term.name).get<double>());
      s.terms.push_back(term);
    }
    read_prediction(response, s, domain, origin);
    surfaces.push_back(s);
  }
  if (surfaces.empty()) throw Error(origin + ": model has no responses");
  return std::make_unique<ResponseSurfaceModel>(domain, surfaces);
}

namespace {

json coefficient_map(const std::vector<CoefficientRow>& rows) {
  json map = json::object();
  for (const CoefficientRow& row : rows) map[row.term] = row.coef;
  return map;
}

json coefficient_table_json(const std::vector<CoefficientRow>& rows) {
  json table = json::array();
  for (const CoefficientRow& row : rows)
    table.push_back({{"term", row.term}, {"coef", json_number(row.coef)}, {"se", json_number(row.se)},
                     {"t", json_number(row.t)}, {"p", json_number(row.p)}, {"vif", json_number(row.vif)}});
  return table;
}

json anova_json(const std::vector<AnovaRow>& rows) {
  json table = json::array();
  for (const AnovaRow& r : rows)
    table.push_back({{"source", r.source}, {"level", r.indent}, {"df", r.df}, {"ss", json_number(r.ss)},
                     {"ms", json_number(r.ms)}, {"F", json_number(r.f)}, {"p", json_number(r.p)}});
  return table;
}

// What the 95 % prediction interval needs: (Z'Z)^-1 over the terms in coded
// units (rows and columns in the order of "terms") and the error's df.
json prediction_json(const SurfaceFit& fit) {
  const Eigen::MatrixXd& c = fit.coded_covariance_unscaled;
  if (c.rows() != static_cast<Eigen::Index>(fit.terms.size()) || fit.error_df < 1) return nullptr;
  json rows = json::array();
  for (Eigen::Index i = 0; i < c.rows(); ++i) {
    json row = json::array();
    for (Eigen::Index j = 0; j < c.cols(); ++j) row.push_back(c(i, j));
    rows.push_back(row);
  }
  return {{"coded_covariance_unscaled", rows}, {"error_df", fit.error_df}};
}

json response_json(const SurfaceFit& fit) {
  json terms = json::array();
  for (const SurfaceTerm& t : fit.terms) {
    json names = json::array();
    for (int f : t.factors) names.push_back(fit.factors[static_cast<std::size_t>(f)]);
    terms.push_back({{"name", t.name}, {"inputs", names}});
  }
  json coding = json::object();
  for (std::size_t j = 0; j < fit.factors.size(); ++j)
    coding[fit.factors[j]] = {{"center", fit.coding[j].center}, {"half_range", fit.coding[j].half_range}};
  return {{"name", fit.response},
          {"terms", terms},
          {"coefficients", coefficient_map(fit.natural)},
          {"natural_table", coefficient_table_json(fit.natural)},
          {"coded_coefficients", coefficient_table_json(fit.coded)},
          {"coding", coding},
          {"eliminated_terms", fit.eliminated},
          {"runs", fit.runs},
          {"distinct_points", fit.distinct_points},
          {"s", json_number(fit.s)},
          {"r2", json_number(fit.r2)},
          {"r2_adj", json_number(fit.r2_adj)},
          {"r2_pred", json_number(fit.r2_pred)},
          {"press", json_number(fit.press)},
          {"validation", {{"method", "leave-one-out (PRESS)"},
                          {"r2", json_number(fit.r2_pred)},
                          {"rmse", json_number(std::sqrt(fit.press / fit.runs))}}},
          {"anova", anova_json(fit.anova)},
          {"prediction_interval", prediction_json(fit)},
          {"note", fit.note}};
}

}  // namespace

json surface_model_json(const std::vector<SurfaceFit>& fits, const std::string& data_path) {
  if (fits.empty()) throw Error("no fits to save");
  json inputs = json::array();
  for (const InputRange& r : fits.front().domain) inputs.push_back({{"name", r.name}, {"low", r.low}, {"high", r.high}});
  json outputs = json::array(), responses = json::array();
  for (const SurfaceFit& fit : fits) {
    outputs.push_back(fit.response);
    responses.push_back(response_json(fit));
  }
  json file = {{"format", kModelFormat},
               {"kind", to_string(fits.front().kind)},
               {"data", data_path},
               {"inputs", inputs},
               {"outputs", outputs},
               {"responses", responses}};
  if (fits.size() == 1) {
    // Single-output shorthand: the natural coefficients and fit statistics at the top.
    const json& only = responses.front();
    for (const char* key : {"coefficients", "r2", "r2_adj", "r2_pred"}) file[key] = only.at(key);
  }
  return file;
}

void register_response_surface_kinds() {
  auto loader = [](const json& file, const std::string& origin) -> std::unique_ptr<Model> {
    return ResponseSurfaceModel::from_json(file, origin);
  };
  register_model_kind("quadratic", loader);
  register_model_kind("linear", loader);
}

}  // namespace demcal::surrogate
