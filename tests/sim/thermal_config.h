#pragma once
// A homogeneous gas with Maxwell velocities: the start of the equilibrium and cooling tests.
#include <cstdint>

#include "sim/config.h"

namespace gs::test {

inline PhysicsConfig thermal(int dim, std::int64_t n, double r) {
  PhysicsConfig c;
  c.dim = dim;
  c.particles = n;
  c.restitution = r;
  c.initial = Initial::Thermal;
  return c;
}

}  // namespace gs::test
