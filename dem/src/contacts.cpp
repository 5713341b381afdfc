#include "demcal/dem/contacts.hpp"

namespace demcal::dem {
namespace {

// Every per-pair double column, so that adding one is a one-line change here.
using Column = std::vector<double> ContactSet::*;
constexpr Column kStateColumns[] = {
    &ContactSet::kn,          &ContactSet::ks,          &ContactSet::mu,          &ContactSet::fs,
    &ContactSet::bond_kn,     &ContactSet::bond_ks,     &ContactSet::bond_area,   &ContactSet::bond_inertia,
    &ContactSet::bond_radius, &ContactSet::bond_fn,     &ContactSet::bond_fs,     &ContactSet::bond_m,
    &ContactSet::strength_n,  &ContactSet::strength_s,  &ContactSet::bond_overlap,
};

}  // namespace

void ContactSet::clear() {
  i.clear();
  j.clear();
  model.clear();
  flags.clear();
  for (Column c : kStateColumns) (this->*c).clear();
}

void ContactSet::reserve(std::size_t n) {
  i.reserve(n);
  j.reserve(n);
  model.reserve(n);
  flags.reserve(n);
  for (Column c : kStateColumns) (this->*c).reserve(n);
}

std::size_t ContactSet::add(std::int32_t a, std::int32_t b, std::uint8_t model_index) {
  i.push_back(a);
  j.push_back(b);
  model.push_back(model_index);
  flags.push_back(0);
  for (Column c : kStateColumns) (this->*c).push_back(0.0);
  return i.size() - 1;
}

void ContactSet::copy_state(std::size_t to, const ContactSet& other, std::size_t from) {
  flags[to] = other.flags[from];
  for (Column c : kStateColumns) (this->*c)[to] = (other.*c)[from];
}

}  // namespace demcal::dem
