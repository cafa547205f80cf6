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

// A touching pair whose normal approach speed is below this fraction of their speeds is grazing:
// its speed is round-off. r = 0 leaves every pair it hits touching with none, and round-off then
// finds such a pair approaching at 1e-18 again and again at one instant: reflecting so small a
// speed changes no bit of either velocity, so the same collision comes back forever, whatever
// --cutoff says (the cutoff only chooses elastic or inelastic; a run of r = 0 in 2D hung so at
// t = 15.6 after 36 inelastic collisions). Such a pair parts instead at this fraction of their
// speeds, which their velocities resolve 4000 times over and their next search sees receding.
inline constexpr double kGrazingFraction = 1e-12;

struct CollisionResult {
  double impulse = 0;  // momentum transferred along n (>= 0); 0 if the pair was not approaching
  bool inelastic = false;
};

// v1, v2 are the velocities before, replaced by those after. n is the unit vector from 1 to 2.
// v1 <- v1 - eps [n.(v1 - v2)] n, v2 <- v2 + eps [n.(v1 - v2)] n with eps = (1 + r)/2, or eps = 1
// when n.(v1 - v2) < cutoff (the paper's guard against inelastic collapse); a grazing pair parts
// at kGrazingFraction of its speeds.
template <int D>
CollisionResult collide(Vec<D>& v1, Vec<D>& v2, const Vec<D>& n, double r, double cutoff) {
  const double w = n.dot(v1 - v2);  // normal approach speed
  if (!(w >= kRoundoffCutoff)) [[unlikely]] {
    const double part = kGrazingFraction * (v1.norm() + v2.norm());
    if (!(w > -part)) return {};  // receding
    if (w < part) {               // grazing: they part at `part`
      const double impulse = 0.5 * (w + part);
      v1 -= impulse * n;
      v2 += impulse * n;
      return {impulse, false};
    }
  }
  const bool inelastic = w >= std::max(cutoff, kRoundoffCutoff) && r < 1.0;
  const double eps = inelastic ? 0.5 * (1.0 + r) : 1.0;
  const double impulse = eps * w;
  v1 -= impulse * n;
  v2 += impulse * n;
  return {impulse, inelastic};
}

// Contact of two unit-diameter spheres, from b = dr.dv, r2 = |dr|^2 and a = |dv|^2 for their
// separation dr = r2 - r1 and relative velocity dv = v2 - v1: they touch in the future if they
// approach (b < 0) and their paths come within one diameter (disc > 0), after contact_delay.
// The engine's batched search tests every neighbour without branches (half the pairs move
// apart, at random, and a branch on that costs more in mispredictions than the arithmetic),
// then takes the square root and the division only for the few that pass.
inline double contact_discriminant(double b, double r2, double a) {
  return b * b - a * (r2 - 1.0);
}
inline bool will_touch(double b, double disc) {
  return (b < 0) & (disc > 0);
}

// c / (-b + sqrt(disc)) is the smaller root without the cancellation of (-b - sqrt(disc)) / a.
// An approaching pair that already overlaps (r2 <= 1) collides at once (0): round-off may push a
// pair a hair inside contact, and it must never sink deeper.
inline double contact_delay(double b, double r2, double disc) {
  return std::max((r2 - 1.0) / (std::sqrt(disc) - b), 0.0);
}

// Time until the spheres touch; kNever if they do not.
inline double contact_time(double b, double r2, double a) {
  const double disc = contact_discriminant(b, r2, a);
  return will_touch(b, disc) ? contact_delay(b, r2, disc) : kNever;
}

template <int D>
inline double contact_time(const Vec<D>& dr, const Vec<D>& dv) {
  return contact_time(dr.dot(dv), dr.squaredNorm(), dv.squaredNorm());
}

}  // namespace gs
