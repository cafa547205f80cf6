#pragma once
// The binary collision rule of the paper (Jabeen, Rajesh & Ray 2010, Eq. 1) and the time of
// contact of two hard spheres of unit diameter. Both are pure functions so that tests can check
// them in isolation.
#include <algorithm>
#include <cmath>
#include <limits>

#include "sim/vec.h"

namespace gs {

inline constexpr double kNever = std::numeric_limits<double>::infinity();

// Below this normal relative speed a collision is always elastic, whatever --cutoff says:
// with delta = 0 and r = 0, round-off could otherwise leave a touching pair with a relative
// speed of 1e-17 that keeps colliding at the same instant.
inline constexpr double kRoundoffCutoff = 1e-12;

struct CollisionResult {
  double impulse = 0;  // momentum transferred along n (>= 0); 0 if the pair was not approaching
  bool inelastic = false;
};

// v1, v2 are the velocities before, replaced by those after. n is the unit vector from 1 to 2.
// v1 <- v1 - eps [n.(v1 - v2)] n, v2 <- v2 + eps [n.(v1 - v2)] n with eps = (1 + r)/2, or eps = 1
// when n.(v1 - v2) < cutoff (the paper's guard against inelastic collapse).
template <int D>
CollisionResult collide(Vec<D>& v1, Vec<D>& v2, const Vec<D>& n, double r, double cutoff) {
  const double w = n.dot(v1 - v2);  // normal approach speed
  if (!(w > 0)) return {};
  const bool inelastic = w >= std::max(cutoff, kRoundoffCutoff) && r < 1.0;
  const double eps = inelastic ? 0.5 * (1.0 + r) : 1.0;
  const double impulse = eps * w;
  v1 -= impulse * n;
  v2 += impulse * n;
  return {impulse, inelastic};
}

// Time until two unit-diameter spheres with separation dr = r2 - r1 and relative velocity
// dv = v2 - v1 touch, or kNever. An approaching pair that already overlaps collides at once (0):
// round-off may push a pair a hair inside contact, and it must never sink deeper.
template <int D>
inline double contact_time(const Vec<D>& dr, const Vec<D>& dv) {
  const double b = dr.dot(dv);
  if (b >= 0) return kNever;
  const double c = dr.squaredNorm() - 1.0;
  if (c <= 0) return 0.0;
  const double a = dv.squaredNorm();
  const double disc = b * b - a * c;
  if (disc <= 0) return kNever;
  // c / (-b + sqrt(disc)) is the smaller root without the cancellation of (-b - sqrt(disc)) / a.
  return c / (-b + std::sqrt(disc));
}

}  // namespace gs
