#include "sim/initial.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "sim/cell_grid.h"
#include "sim/error.h"

namespace gs {

template <int D>
VecArray<D> random_sequential_addition(std::int64_t n, double box, Rng& rng) {
  const CellGrid<D> grid(box);
  std::vector<std::int32_t> head(grid.cell_count(), -1), next(static_cast<std::size_t>(n), -1);
  VecArray<D> pos;
  pos.reserve(static_cast<std::size_t>(n));
  // Near the jamming limit the acceptance rate collapses; give up long before that becomes a hang.
  const std::int64_t max_trials = 1000 * n + 1000000;
  std::int64_t trials = 0;
  while (static_cast<std::int64_t>(pos.size()) < n) {
    if (++trials > max_trials)
      throw UserError("--density: random sequential addition could not place particle " +
                      std::to_string(pos.size() + 1) + " of " + std::to_string(n) +
                      "; the box is too full");
    Vec<D> x;
    for (int k = 0; k < D; ++k) x[k] = rng.uniform() * box;
    const IVec<D> c = grid.coords_of(x);
    bool free = true;
    grid.for_each_neighbour(c, [&](std::int32_t cell) {
      for (std::int32_t j = head[cell]; free && j >= 0; j = next[j])
        if (grid.minimum_image(pos[j] - x).squaredNorm() < 1.0) free = false;
    });
    if (!free) continue;
    const auto id = static_cast<std::int32_t>(pos.size());
    const std::int32_t cell = grid.index(c);
    next[id] = head[cell];
    head[cell] = id;
    pos.push_back(x);
  }
  return pos;
}

namespace {

// In 1D an exact uniform sample of non-overlapping rods exists: N uniform points on a line of
// length L - N, sorted, the i-th shifted by i diameters. It reaches any density below 1.
VecArray<1> random_rods(std::int64_t n, double box, Rng& rng) {
  std::vector<double> u(static_cast<std::size_t>(n));
  for (auto& x : u) x = rng.uniform() * (box - static_cast<double>(n));
  std::sort(u.begin(), u.end());
  VecArray<1> pos(u.size());
  for (std::size_t i = 0; i < u.size(); ++i) pos[i][0] = u[i] + static_cast<double>(i) + 0.5;
  return pos;
}

template <int D>
Vec<D> random_direction(Rng& rng) {
  if constexpr (D == 1) {
    return Vec<D>::Constant(rng.uniform() < 0.5 ? -1.0 : 1.0);
  } else {
    for (;;) {  // an isotropic Gaussian vector, normalised, is uniform on the sphere
      Vec<D> v;
      for (int k = 0; k < D; ++k) v[k] = rng.normal();
      const double norm = v.norm();
      if (norm > 1e-12) return v / norm;
    }
  }
}

}  // namespace

template <int D>
InitialState<D> make_initial_state(const PhysicsConfig& c) {
  GS_CHECK(c.dim == D);
  const double box = c.box();
  const auto n = static_cast<std::size_t>(c.particles);
  InitialState<D> s;

  Rng pos_rng(c.seed, c.realisation, Stream::Positions);
  if constexpr (D == 1) {
    if (c.lattice > 0) {
      s.position.resize(n);
      for (std::size_t i = 0; i < n; ++i) s.position[i][0] = (static_cast<double>(i) + 0.5) * c.lattice;
    } else {
      s.position = random_rods(c.particles, box, pos_rng);
    }
  } else {
    s.position = random_sequential_addition<D>(c.particles, box, pos_rng);
  }

  s.velocity.assign(n, Vec<D>::Zero());
  if (c.initial == Initial::Thermal) {
    Rng vel_rng(c.seed, c.realisation, Stream::Velocities);
    Vec<D> mean = Vec<D>::Zero();
    for (auto& v : s.velocity) {
      for (int k = 0; k < D; ++k) v[k] = vel_rng.normal();
      mean += v;
    }
    mean /= static_cast<double>(n);
    double sum_v2 = 0;
    for (auto& v : s.velocity) {
      v -= mean;
      sum_v2 += v.squaredNorm();
    }
    // Rescale so that T = sum v^2 / (d N) is exactly the requested temperature (unit mass).
    const double scale = std::sqrt(c.temperature * D * static_cast<double>(n) / sum_v2);
    for (auto& v : s.velocity) v *= scale;
  } else {
    Rng kick_rng(c.seed, c.realisation, Stream::Kick);
    if (c.kick_site == KickSite::Centre) {
      const Vec<D> centre = Vec<D>::Constant(0.5 * box);
      double best = std::numeric_limits<double>::infinity();
      for (std::size_t i = 0; i < n; ++i) {
        const double d2 = (s.position[i] - centre).squaredNorm();
        if (d2 < best) best = d2, s.kicked = static_cast<std::int32_t>(i);
      }
    } else {
      s.kicked = static_cast<std::int32_t>(kick_rng.below(n));
    }
    s.velocity[s.kicked] = c.speed * random_direction<D>(kick_rng);
  }
  return s;
}

template VecArray<1> random_sequential_addition<1>(std::int64_t, double, Rng&);
template VecArray<2> random_sequential_addition<2>(std::int64_t, double, Rng&);
template VecArray<3> random_sequential_addition<3>(std::int64_t, double, Rng&);
template InitialState<1> make_initial_state<1>(const PhysicsConfig&);
template InitialState<2> make_initial_state<2>(const PhysicsConfig&);
template InitialState<3> make_initial_state<3>(const PhysicsConfig&);

}  // namespace gs
