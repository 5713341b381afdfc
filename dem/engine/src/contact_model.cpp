#include "demcal/dem/contact_model.hpp"

#include <algorithm>
#include <cmath>

#include <nlohmann/json.hpp>

#include "demcal/core/error.hpp"
#include "demcal/core/json_fields.hpp"

namespace demcal::dem {

void ContactModel::make_force_free(PairBlock&, std::size_t, double) const {}

double ContactModel::max_bond_utilisation(const ConstPairBlock&, const Bodies&) const { return NAN; }

void ContactModel::add_rolling_limits(const ConstPairBlock&, const Bodies&, bool, double*) const {}

bool ContactModel::install_bond(PairBlock&, std::size_t, const PairInfo&, double, Rng&) const { return false; }

}  // namespace demcal::dem
