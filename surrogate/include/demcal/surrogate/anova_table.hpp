#pragma once
// One row of an analysis-of-variance table, shared by the designed-experiment
// ANOVA and the response-surface ANOVA.
#include <cmath>
#include <limits>
#include <string>

namespace demcal::surrogate {

struct AnovaRow {
  std::string source;
  double ss = 0.0;
  int df = 0;
  double ms = std::numeric_limits<double>::quiet_NaN();
  double f = std::numeric_limits<double>::quiet_NaN();
  double p = std::numeric_limits<double>::quiet_NaN();
  bool pooled = false;   // moved into the error term
  int indent = 0;        // 0 top-level, 1 group member (Minitab's layout)
};

// ms = ss/df; F and p against `error` (left NaN when the error has no df).
void complete_row(AnovaRow& row, const AnovaRow& error);

}  // namespace demcal::surrogate
