#pragma once
// From coded designs to the table a DEM batch runs: factor names and natural
// units from a parameter space.
#include "demcal/core/parameter_space.hpp"
#include "demcal/core/table.hpp"
#include "demcal/doe/design.hpp"

namespace demcal::doe {

// Natural value of coded value `coded` in a column with `levels` discrete
// levels (0 = continuous) for parameter `p`. A parameter with listed levels
// takes them by level index when the column has as many levels; otherwise the
// value is interpolated between low and high (log scale if set).
double natural_value(const Parameter& p, double coded, int levels, Coding coding);

// The design as a table. Without a space: columns x1..xN in coded units.
// With a space: the factor names in natural units, then `<factor>_coded`
// columns, then any blank columns (coded). The design's kind, description,
// coding and settings go into the table attributes.
Table design_table(const Design& design, const ParameterSpace* space);

// Names the design's factor columns after the space's parameters (in order)
// and checks that their numbers agree.
void name_factors(Design& design, const ParameterSpace& space);

}  // namespace demcal::doe
