#pragma once
// Forces on chosen disks that come from outside the model rather than from a
// contact: the static force a removed wall gave its disks, a viscous
// (absorbing) boundary's dashpots, an input boundary's wave. The world calls
// each once per step, after the contact forces and before the integration,
// so a boundary costs one virtual call per step and a loop over its own disks.
// A boundary that moves disks on a prescribed path (fixed disks, which the
// integration leaves in place) does so after the integration.
#include "demcal/dem/bodies.hpp"

namespace demcal::dem {

class ExternalForces {
 public:
  virtual ~ExternalForces() = default;
  // Adds to bodies.fx, fy and moment at time `time_s` (the step's start);
  // velocities are those of the half step before it.
  virtual void add(Bodies& bodies, double time_s, double dt_s) = 0;
  // After the integration of the step that began at `time_s`: moves the
  // disks whose motion is prescribed (bodies.fx, fy still hold the step's
  // forces). Most boundaries prescribe none.
  virtual void after_integration(Bodies& /*bodies*/, double /*time_s*/, double /*dt_s*/) {}
};

}  // namespace demcal::dem
