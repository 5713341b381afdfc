#pragma once
// F tests and the significance marks printed in ANOVA tables.
#include <string>

namespace demcal::surrogate {

// Upper-tail probability P(F(df1, df2) > f) (Boost.Math); NaN when undefined
// (df <= 0 or f not finite and positive).
double f_upper_tail(double f, double df1, double df2);

// Critical value F_alpha(df1, df2): P(F > value) = alpha.
double f_critical(double alpha, double df1, double df2);

// Two-sided p of a t statistic with `df` degrees of freedom.
double t_two_sided(double t, double df);

// "**" (p < 0.01, highly significant), "*" (p < 0.05, significant), "" otherwise.
std::string significance_mark(double p);

}  // namespace demcal::surrogate
