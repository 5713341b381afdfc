#pragma once
// How far predicted macro values are from their targets, in relative terms so
// that MPa, GPa and a Poisson's ratio weigh alike:
//   sum-rel  sum_i |y_i - t_i| / |t_i|          (Su et al. 2021)
//   max-rel  max_i |y_i - t_i| / |t_i|          (Wang & Cao 2017)
//   sse-rel  sum_i ((y_i - t_i) / t_i)^2        (least squares)
//   minimise sum_i y_i / |t_i|                  (no target to meet: drive the outputs down, each over its
//                                                reference t_i, e.g. Ma et al. 2022's total recovery time
//                                                over the fixed boundary's; an inversion of it is never
//                                                "not met")
#include <string>
#include <vector>

namespace demcal::inverse {

enum class ObjectiveKind { SumRel, MaxRel, SseRel, Minimise };

ObjectiveKind parse_objective(const std::string& name);  // throws naming the allowed names
std::vector<std::string> objective_names();
std::string to_string(ObjectiveKind kind);

double relative_objective(ObjectiveKind kind, const std::vector<double>& predicted, const std::vector<double>& targets);
double max_relative_error(const std::vector<double>& predicted, const std::vector<double>& targets);

}  // namespace demcal::inverse
