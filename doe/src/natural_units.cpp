#include "demcal/doe/natural_units.hpp"

#include <cmath>

#include "demcal/core/error.hpp"

namespace demcal::doe {

double natural_value(const Parameter& p, double coded, int levels, Coding coding) {
  if (coding == Coding::Unit) return p.from_unit(coded);
  if (levels >= 2 && !p.levels.empty()) {
    if (static_cast<int>(p.levels.size()) != levels)
      throw Error("parameter \"" + p.name + "\" lists " + std::to_string(p.levels.size()) +
                  " levels but its design column has " + std::to_string(levels));
    int index = static_cast<int>(std::lround((coded + 1.0) / 2.0 * (levels - 1)));
    return p.levels[static_cast<std::size_t>(index)];
  }
  return p.from_symmetric(coded);
}

void name_factors(Design& design, const ParameterSpace& space) {
  if (design.factors() != space.size())
    throw Error("the space has " + std::to_string(space.size()) + " parameters but the design has " +
                std::to_string(design.factors()) + " factor columns");
  std::size_t next = 0, blank_number = 0;
  for (std::size_t j = 0; j < design.width(); ++j) {
    if (design.blank[j])
      design.columns[j] = "blank" + std::to_string(++blank_number);
    else
      design.columns[j] = space.parameters()[next++].name;
  }
}

Table design_table(const Design& design, const ParameterSpace* space) {
  std::vector<int> runs(design.runs());
  for (std::size_t i = 0; i < runs.size(); ++i) runs[i] = static_cast<int>(i) + 1;
  Table table(runs);
  auto coded_column = [&](std::size_t j) {
    Eigen::VectorXd c = design.coded.col(static_cast<Eigen::Index>(j));
    return std::vector<double>(c.data(), c.data() + c.size());
  };
  if (space == nullptr) {
    for (std::size_t j = 0; j < design.width(); ++j) table.add_column(design.columns[j], coded_column(j));
  } else {
    std::size_t next = 0;
    std::vector<std::size_t> factor_columns;
    for (std::size_t j = 0; j < design.width(); ++j) {
      if (design.blank[j]) continue;
      const Parameter& p = space->parameters()[next++];
      std::vector<double> values;
      for (double c : coded_column(j)) values.push_back(natural_value(p, c, design.levels[j], design.coding));
      table.add_column(p.name, values);
      factor_columns.push_back(j);
    }
    for (std::size_t j : factor_columns) table.add_column(design.columns[j] + "_coded", coded_column(j));
    for (std::size_t j = 0; j < design.width(); ++j)
      if (design.blank[j]) table.add_column(design.columns[j], coded_column(j));
  }
  auto& attributes = table.attributes();
  attributes["kind"] = design.kind;
  attributes["description"] = design.description;
  attributes["coding"] = design.coding == Coding::Unit ? "unit [0,1] -> [low,high]" : "symmetric [-1,1] -> [low,high]";
  std::string levels, blanks;
  for (std::size_t j = 0; j < design.width(); ++j) {
    levels += (j ? "," : "") + std::to_string(design.levels[j]);
    if (design.blank[j]) blanks += (blanks.empty() ? "" : ",") + design.columns[j];
  }
  attributes["levels"] = levels;
  if (!blanks.empty()) attributes["blank_columns"] = blanks;
  for (const auto& [key, value] : design.settings) attributes[key] = value;
  return table;
}

}  // namespace demcal::doe
