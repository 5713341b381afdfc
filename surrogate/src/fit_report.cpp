#include <algorithm>
#include <cmath>
#include <sstream>

#include "demcal/surrogate/reports.hpp"

namespace demcal::surrogate {

std::string surface_markdown(const SurfaceFit& fit) {
  std::ostringstream md;
  md << "## Response surface of " << fit.response << " (" << to_string(fit.kind) << ", " << fit.runs << " runs, "
     << fit.distinct_points << " distinct points)\n\n";
  if (!fit.eliminated.empty()) {
    md << "Terms removed by backward elimination (hierarchy kept), in order:";
    for (const std::string& t : fit.eliminated) md << " " << t;
    md << "\n\n";
  }
  md << "### Coded coefficients\n\nCoding: x = (X - center) / half_range;";
  for (std::size_t j = 0; j < fit.factors.size(); ++j)
    md << " " << fit.factors[j] << ": center " << format_number(fit.coding[j].center) << ", half_range "
       << format_number(fit.coding[j].half_range) << (j + 1 < fit.factors.size() ? ";" : "");
  md << "\n\n| Term | Coef | SE Coef | T-Value | P-Value | VIF |\n|---|---|---|---|---|---|\n";
  for (const CoefficientRow& r : fit.coded)
    md << "| " << (r.term == "1" ? "Constant" : r.term) << " | " << format_number(r.coef) << " | "
       << format_number(r.se) << " | " << format_number(r.t, 4) << " | " << format_p(r.p) << " | "
       << format_number(r.vif, 4) << " |\n";
  md << "\n### Model summary\n\n| S | R-sq | R-sq(adj) | R-sq(pred) | PRESS |\n|---|---|---|---|---|\n| "
     << format_number(fit.s) << " | " << format_number(100.0 * fit.r2, 5) << " % | "
     << format_number(100.0 * fit.r2_adj, 5) << " % | "
     << (std::isfinite(fit.r2_pred) ? format_number(100.0 * std::max(0.0, fit.r2_pred), 5) + " %" : std::string("*"))
     << " | " << (std::isfinite(fit.press) ? format_number(fit.press) : std::string("*")) << " |\n";
  if (!std::isfinite(fit.r2_pred))
    md << "\nR-sq(pred) is undefined (*): a point has leverage 1, so leaving it out leaves its term unestimable "
          "(e.g. a single centre point); add replicates.\n";
  else if (fit.r2_pred < 0)
    md << "\nPredicted R-sq is negative (" << format_number(fit.r2_pred, 4) << "); shown as 0 as Minitab does.\n";
  md << "\n### Analysis of variance (adjusted SS)\n\n| Source | DF | Adj SS | Adj MS | F-Value | P-Value |\n"
     << "|---|---|---|---|---|---|\n";
  for (const AnovaRow& r : fit.anova) {
    std::string indent;
    for (int i = 0; i < r.indent; ++i) indent += "&nbsp;&nbsp;";
    md << "| " << indent << r.source << " | " << r.df << " | " << format_number(r.ss) << " | " << format_number(r.ms)
       << " | " << format_number(r.f, 5) << " | " << format_p(r.p) << " |\n";
  }
  if (!fit.note.empty()) md << "\nNote: " << fit.note << ".\n";
  md << "\n### Regression equation in natural units\n\n" << fit.response << " =";
  bool first = true;
  for (const CoefficientRow& r : fit.natural) {
    double c = r.coef;
    md << (first ? " " : (c < 0 ? " - " : " + ")) << format_number(first ? c : std::fabs(c), 6);
    if (r.term != "1") md << " " << r.term;
    first = false;
  }
  md << "\n\n| Term | Coef (natural) | SE Coef | T-Value | P-Value |\n|---|---|---|---|---|\n";
  for (const CoefficientRow& r : fit.natural)
    md << "| " << (r.term == "1" ? "Constant" : r.term) << " | " << format_number(r.coef, 8) << " | "
       << format_number(r.se) << " | " << format_number(r.t, 4) << " | " << format_p(r.p) << " |\n";
  md << "\nFitted domain:";
  for (const InputRange& r : fit.domain) md << " " << r.name << " [" << format_number(r.low) << ", " << format_number(r.high) << "]";
  md << "\n\n";
  return md.str();
}

std::string gabp_markdown(const GabpFit& fit) {
  std::ostringstream md;
  md << "## GA-BP network: " << fit.inputs.size() << " inputs, " << fit.network.hidden() << " tanh hidden, "
     << fit.outputs.size() << " linear outputs\n\n"
     << "Training rows " << fit.training_rows.size() << ", validation rows " << fit.validation_rows.size()
     << "; GA population " << fit.options.ga_population << " x " << fit.options.ga_generations
     << " generations (best scaled MSE " << format_number(fit.ga_best_mse, 4) << "), then Levenberg-Marquardt for "
     << fit.epochs << " epochs (stopped: " << fit.stop_reason << ").\n\n";
  if (fit.trials.size() > 1) {
    md << "| Hidden | Validation R^2 | Training MSE (scaled) | LM epochs |\n|---|---|---|---|\n";
    for (const HiddenTrial& t : fit.trials)
      md << "| " << t.hidden << (t.hidden == fit.network.hidden() ? " (chosen)" : "") << " | "
         << format_number(t.validation_r2, 4) << " | " << format_number(t.training_mse, 4) << " | " << t.epochs << " |\n";
    md << "\n";
  }
  md << "| Output | Training R^2 | Training RMSE | Validation R^2 | Validation RMSE |\n|---|---|---|---|---|\n";
  for (std::size_t o = 0; o < fit.outputs.size(); ++o) {
    md << "| " << fit.outputs[o] << " | " << format_number(fit.training[o].r2, 4) << " | "
       << format_number(fit.training[o].rmse, 4) << " | ";
    if (o < fit.validation.size())
      md << format_number(fit.validation[o].r2, 4) << " | " << format_number(fit.validation[o].rmse, 4) << " |\n";
    else
      md << " |  |\n";
  }
  md << "\n";
  return md.str();
}

}  // namespace demcal::surrogate
