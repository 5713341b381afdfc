#include "demcal/surrogate/anova_table.hpp"

#include "demcal/surrogate/f_test.hpp"

namespace demcal::surrogate {

void complete_row(AnovaRow& row, const AnovaRow& error) {
  row.ms = row.df > 0 ? row.ss / row.df : std::numeric_limits<double>::quiet_NaN();
  if (row.df > 0 && error.df > 0 && error.ms > 0) {
    row.f = row.ms / error.ms;
    row.p = f_upper_tail(row.f, row.df, error.df);
  } else if (row.df > 0 && error.df > 0 && error.ms == 0) {
    row.f = row.ss > 0 ? std::numeric_limits<double>::infinity() : std::numeric_limits<double>::quiet_NaN();
    row.p = row.ss > 0 ? 0.0 : std::numeric_limits<double>::quiet_NaN();
  }
}

}  // namespace demcal::surrogate
