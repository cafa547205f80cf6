#include "sim/melt.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "sim/engine.h"
#include "sim/error.h"
#include "sim/format.h"
#include "sim/stop.h"

namespace gs {

template <int D>
double lattice_order(const VecArray<D>& x, double box, std::int64_t side) {
  const double k = 2 * std::numbers::pi * static_cast<double>(side) / box;
  double sum = 0;
  for (int d = 0; d < D; ++d) {
    double re = 0, im = 0;
    for (const auto& p : x) {
      re += std::cos(k * p[d]);
      im += std::sin(k * p[d]);
    }
    const double n = static_cast<double>(x.size());
    sum += (re * re + im * im) / (n * n);
  }
  return sum / D;
}

double melted_order(std::int64_t n) {
  return std::min(0.05, 20.0 / static_cast<double>(n));
}

template <int D>
InitialState<D> melted_lattice(const PhysicsConfig& c, MeltReport* report) {
  const double box = c.box();
  const std::int64_t n = c.particles, side = lattice_side(n, D);
  InitialState<D> s;
  Rng pos_rng(c.seed, c.realisation, Stream::Positions);
  Rng vel_rng(c.seed, c.realisation, Stream::Velocities);
  s.position = cubic_lattice<D>(n, box, pos_rng);
  s.velocity = thermal_velocities<D>(n, c.temperature, vel_rng);
  PhysicsConfig elastic = c;
  elastic.restitution = 1.0;
  Engine<D> melt(elastic, std::move(s));
  // Steps of time short enough that a look at the order parameter comes within a collision or
  // two per particle of its due count (the collision rate is over 10 per particle here).
  const double dt = 0.1 / std::sqrt(c.temperature);
  double t = 0, order = 1;
  Snapshot snap;
  VecArray<D> x(static_cast<std::size_t>(n));
  for (std::int64_t due = kMeltCheckCollisions * n;; due += kMeltCheckCollisions * n) {
    while (melt.stats().collisions < due) {
      melt.run_until(t += dt);
      throw_if_stopped();  // run_until returns at once once a stop is asked for
    }
    melt.snapshot(snap);
    for (std::size_t i = 0; i < x.size(); ++i) x[i] = snap.position[i].template head<D>();
    order = lattice_order<D>(x, box, side);
    if (order <= melted_order(n)) break;
    if (melt.stats().collisions >= kMeltMaxCollisions * n)
      throw UserError("--density " + format_double(c.density) + ": the lattice start of a " +
                      "thermal gas did not melt in " + std::to_string(kMeltMaxCollisions) +
                      " collisions per particle; the gas is not a fluid at this density");
  }
  GS_CHECK(melt.stats().overlaps == 0);
  if (report) *report = {melt.stats().collisions, melt.time(), order};

  InitialState<D> out;
  out.position.resize(x.size());
  out.velocity.resize(x.size());
  Vec<D> momentum = Vec<D>::Zero();
  for (std::size_t i = 0; i < x.size(); ++i) {
    for (int k = 0; k < D; ++k) out.position[i][k] = x[i][k] - box * std::floor(x[i][k] / box);
    out.velocity[i] = snap.velocity[i].template head<D>();
    momentum += out.velocity[i];
  }
  momentum /= static_cast<double>(n);
  double sum_v2 = 0;
  for (auto& v : out.velocity) {
    v -= momentum;
    sum_v2 += v.squaredNorm();
  }
  const double scale = std::sqrt(c.temperature * D * static_cast<double>(n) / sum_v2);
  for (auto& v : out.velocity) v *= scale;
  return out;
}

template double lattice_order<1>(const VecArray<1>&, double, std::int64_t);
template double lattice_order<2>(const VecArray<2>&, double, std::int64_t);
template double lattice_order<3>(const VecArray<3>&, double, std::int64_t);
template InitialState<2> melted_lattice<2>(const PhysicsConfig&, MeltReport*);
template InitialState<3> melted_lattice<3>(const PhysicsConfig&, MeltReport*);

}  // namespace gs
