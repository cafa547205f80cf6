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

// Time until two unit-diameter spheres touch, from b = dr.dv, r2 = |dr|^2 and a = |dv|^2 for
// their separation dr = r2 - r1 and relative velocity dv = v2 - v1; kNever if they do not. An
// approaching pair that already overlaps collides at once (0): round-off may push a pair a hair
// inside contact, and it must never sink deeper. Branch-free, for the engine's batched search:
// half the pairs move apart, at random, and a branch on that costs more in mispredictions than
// the square roots it saves.
inline double contact_time(double b, double r2, double a) {
  const double c = r2 - 1.0, disc = b * b - a * c;
  // c / (-b + sqrt(disc)) is the smaller root without the cancellation of (-b - sqrt(disc)) / a;
  // when the pair overlaps (c <= 0) it is <= 0 and the max makes it 0.
  const double root = std::max(c / (std::sqrt(std::max(disc, 0.0)) - b), 0.0);
  return (b < 0) & (disc > 0) ? root : kNever;
}

template <int D>
inline double contact_time(const Vec<D>& dr, const Vec<D>& dv) {
  return contact_time(dr.dot(dv), dr.squaredNorm(), dv.squaredNorm());
}

}  // namespace gs
