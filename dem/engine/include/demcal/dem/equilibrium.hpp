#pragma once
// Measures of a packing at rest, as PFC users know them: the mean unbalanced
// force ratio (equilibrium), cycling until it is reached, and the mean stress
// the contacts carry (the locked-in stress of a bonded specimen).
#include <cstdint>

#include "demcal/dem/world.hpp"

namespace demcal::dem {

// Mean unbalanced force per body (a disk not in a clump, or a clump as a whole;
// contact and external forces and gravity) over the mean contact normal
// force (PFC's ratio); 0 when nothing touches.
double force_ratio(const World& world);

// The same ratio over the free disks of one material group (not fixed, not in clumps) and
// the disk pairs that touch one of them: a part whose contacts carry far
// smaller forces than the rest (a soft fill on a stiff bedrock) is judged
// against its own, so its creep is not hidden by the other part's rest.
double force_ratio(const World& world, std::uint8_t group);

// Cycles in blocks of 50 steps until force_ratio < `ratio`; false when
// `max_steps` pass first.
bool cycle_to_equilibrium(World& world, double ratio, std::uint64_t max_steps);

// Mean normal stress the disk-disk contacts carry by their models'
// normal_force_n (the contact springs, not the bonds), by the Love-Weber
// average sigma = sum(F_n d) / (2 V) over a volume V = area x thickness, Pa.
// Compression positive.
double contact_mean_stress_pa(const World& world, double area_m2);

}  // namespace demcal::dem
