#include "sim/initial.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "sim/cell_grid.h"
#include "sim/error.h"
#include "sim/huge_pages.h"
#include "sim/melt.h"
#include "sim/resting_store.h"
#include "sim/stop.h"

namespace gs {

template <int D>
VecArray<D> random_sequential_addition(std::int64_t n, double box, Rng& rng) {
  // Trials are tested against cells of about two particles' volume (at least a diameter wide):
  // at n = 0.25 the engine's cells, a diameter wide, would put 4 cells on each particle, and their
  // heads alone would cost 16 B a particle. The placed spheres' centres become the result, and
  // each one's link to the next sphere of its cell becomes the sort's order: a start peaks at
  // 36 B a sphere in 3D (sim/bytes_per_particle_3d).
  const double density = static_cast<double>(n) / std::pow(box, D);
  const CellGrid<D> grid(box, std::max(1.0, std::pow(0.5 / density, 1.0 / D)));
  HugeVector<std::int32_t> head(grid.cell_count(), -1);
  VecArray<D> x;
  std::vector<std::int32_t> next;
  reserve_huge(x, static_cast<std::size_t>(n));  // read at random: huge pages spare the TLB
  reserve_huge(next, static_cast<std::size_t>(n));
  // A trial costs two dependent cache misses (its cells' heads, then their occupants).
  // Trials are drawn kAhead steps before they are tested, in the same order, so the heads of a
  // trial are prefetched kAhead steps early and its occupants kAhead / 2 steps early: the misses
  // of many trials overlap, and the placement is that of drawing and testing one at a time.
  constexpr int kAhead = 8;
  struct Trial {
    Vec<D> x;
    std::int32_t cell[27];
    int cells = 0;
  };
  Trial ring[kAhead];
  // Only the cells within a diameter of the trial (cells wider than one leave out a neighbour
  // along an axis when the trial is far enough from that side: 17 of 27 on average in 3D).
  const double reach = 1.0 + 1e-9;  // round-off in the cell a centre is put in
  auto draw = [&](Trial& t) {
    for (int k = 0; k < D; ++k) t.x[k] = rng.uniform() * box;
    const IVec<D> home = grid.coords_of(t.x);
    int along[3][3], len[3] = {1, 1, 1};
    for (int k = 0; k < 3; ++k) along[k][0] = 0;
    for (int k = 0; k < D; ++k) {
      const double u = t.x[k] - home[k] * grid.side();
      len[k] = 0;
      along[k][len[k]++] = home[k];
      if (u < reach) along[k][len[k]++] = grid.wrap(home[k] - 1);
      if (u > grid.side() - reach) along[k][len[k]++] = grid.wrap(home[k] + 1);
    }
    t.cells = 0;
    IVec<D> c;
    for (int z = 0; z < len[2]; ++z)
      for (int y = 0; y < len[1]; ++y)
        for (int a = 0; a < len[0]; ++a) {
          const int at[3] = {along[0][a], along[1][y], along[2][z]};
          for (int k = 0; k < D; ++k) c[k] = at[k];
          t.cell[t.cells] = grid.index(c);
          __builtin_prefetch(&head[t.cell[t.cells++]]);
        }
  };
  for (auto& t : ring) draw(t);
  // Near the jamming limit the acceptance rate collapses; give up long before that becomes a hang.
  const std::int64_t max_trials = 1000 * n + 1000000;
  for (std::int64_t trial = 0; static_cast<std::int64_t>(x.size()) < n; ++trial) {
    if (trial >= max_trials)
      throw UserError("--density: random sequential addition could not place particle " +
                      std::to_string(x.size() + 1) + " of " + std::to_string(n) +
                      "; the box is too full");
    if ((trial & 0xFFFF) == 0) throw_if_stopped();  // 2e6 spheres take seconds
    const Trial& soon = ring[(trial + kAhead / 2) % kAhead];
    for (int k = 0; k < soon.cells; ++k)
      if (const std::int32_t h = head[soon.cell[k]]; h >= 0) {
        __builtin_prefetch(&x[h]);
        __builtin_prefetch(&next[h]);
      }
    Trial& t = ring[trial % kAhead];
    bool free = true;
    for (int k = 0; k < t.cells && free; ++k)
      for (std::int32_t j = head[t.cell[k]]; free && j >= 0; j = next[j])
        if (grid.minimum_image(x[j] - t.x).squaredNorm() < 1.0) free = false;
    if (free) {
      const std::int32_t cell = grid.index(grid.coords_of(t.x));
      x.push_back(t.x);
      next.push_back(head[cell]);
      head[cell] = static_cast<std::int32_t>(x.size() - 1);
    }
    draw(t);  // the trial kAhead steps on takes this slot
  }
  // Returned cell by cell of the engine's grid in row-major order, the latest placed first in
  // each (the order the cell lists once gave, and so the particles' tags), so that particles
  // close in space are close in the array and a box's resting store (sim/resting_store.h) sorts
  // them with little movement.
  head = HugeVector<std::int32_t>();  // freed, not cleared
  const CellGrid<D> cells(box);
  const int side = cells.per_side();
  const auto row_major = [&](const Vec<D>& p) {
    const IVec<D> c = cells.coords_of(p);
    std::int32_t i = 0;
    for (int k = D - 1; k >= 0; --k) i = i * side + c[k];
    return i;
  };
  std::size_t count = 1;
  for (int k = 0; k < D; ++k) count *= static_cast<std::size_t>(side);
  sort_into_cells(x, count, row_major, true, next);
  return x;
}

template <int D>
VecArray<D> cubic_lattice(std::int64_t n, double box, Rng& rng) {
  const std::int64_t k = lattice_side(n, D);
  const double a = box / static_cast<double>(k);
  GS_CHECK_MSG(a >= 1.0, "lattice spacing below one diameter");
  std::int64_t sites = 1;
  for (int d = 0; d < D; ++d) sites *= k;
  // A partial Fisher-Yates shuffle picks the sites to leave empty.
  std::vector<std::int64_t> site(static_cast<std::size_t>(sites));
  for (std::int64_t s = 0; s < sites; ++s) site[s] = s;
  std::vector<bool> empty(site.size(), false);
  for (std::int64_t v = 0; v < sites - n; ++v) {
    const auto pick = v + static_cast<std::int64_t>(rng.below(static_cast<std::uint64_t>(sites - v)));
    std::swap(site[v], site[pick]);
    empty[site[v]] = true;
  }
  VecArray<D> pos;
  pos.reserve(static_cast<std::size_t>(n));
  for (std::int64_t s = 0; s < sites; ++s) {
    if (empty[s]) continue;
    Vec<D> x;
    std::int64_t rest = s;
    for (int d = 0; d < D; ++d, rest /= k) x[d] = (static_cast<double>(rest % k) + 0.5) * a;
    pos.push_back(x);
  }
  return pos;
}

template <int D>
VecArray<D> thermal_velocities(std::int64_t count, double temperature, Rng& rng) {
  const auto n = static_cast<std::size_t>(count);
  VecArray<D> vel(n);
  Vec<D> mean = Vec<D>::Zero();
  for (auto& v : vel) {
    for (int k = 0; k < D; ++k) v[k] = rng.normal();
    mean += v;
  }
  mean /= static_cast<double>(n);
  double sum_v2 = 0;
  for (auto& v : vel) {
    v -= mean;
    sum_v2 += v.squaredNorm();
  }
  // Rescale so that T = sum v^2 / (d N) is exactly the requested temperature (unit mass).
  const double scale = std::sqrt(temperature * D * static_cast<double>(n) / sum_v2);
  for (auto& v : vel) v *= scale;
  return vel;
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

// Translates the periodic system so that the kicked particle sits at the centre of the box, as in
// the paper's Fig. 1 (kick at (500, 500) in a box of side 1000). The disturbance then grows from
// the middle and its unwrapped positions never straddle the box edge while it fits in the box.
// In 1D the particles are renumbered so that indices still run along the line.
template <int D>
void centre_on(InitialState<D>& s, double box) {
  const Vec<D> shift = Vec<D>::Constant(0.5 * box) - s.position[s.kicked];
  for (auto& x : s.position) {
    x += shift;
    for (int k = 0; k < D; ++k) x[k] -= box * std::floor(x[k] / box);
  }
  if constexpr (D == 1) {
    const auto first =
        std::min_element(s.position.begin(), s.position.end(),
                         [](const Vec<1>& a, const Vec<1>& b) { return a[0] < b[0]; });
    const auto rotate_by = first - s.position.begin();
    std::rotate(s.position.begin(), first, s.position.end());
    if (!s.velocity.empty())
      std::rotate(s.velocity.begin(), s.velocity.begin() + rotate_by, s.velocity.end());
    const auto n = static_cast<std::int32_t>(s.position.size());
    s.kicked = static_cast<std::int32_t>((s.kicked - rotate_by + n) % n);
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
      for (std::size_t i = 0; i < n; ++i)
        s.position[i][0] = (static_cast<double>(i) + 0.5) * c.lattice;
    } else {
      s.position = random_rods(c.particles, box, pos_rng);
    }
  } else if (c.density > max_rsa_density(D)) {
    GS_CHECK(c.initial == Initial::Thermal);  // validate() refuses a denser kick
    return melted_lattice<D>(c);
  } else {
    s.position = random_sequential_addition<D>(c.particles, box, pos_rng);
  }

  if (c.initial == Initial::Thermal) {
    Rng vel_rng(c.seed, c.realisation, Stream::Velocities);
    s.velocity = thermal_velocities<D>(c.particles, c.temperature, vel_rng);
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
    s.kick_velocity = c.speed * random_direction<D>(kick_rng);
    centre_on(s, box);
  }
  return s;
}

template VecArray<1> random_sequential_addition<1>(std::int64_t, double, Rng&);
template VecArray<2> random_sequential_addition<2>(std::int64_t, double, Rng&);
template VecArray<3> random_sequential_addition<3>(std::int64_t, double, Rng&);
template VecArray<1> cubic_lattice<1>(std::int64_t, double, Rng&);
template VecArray<2> cubic_lattice<2>(std::int64_t, double, Rng&);
template VecArray<3> cubic_lattice<3>(std::int64_t, double, Rng&);
template VecArray<1> thermal_velocities<1>(std::int64_t, double, Rng&);
template VecArray<2> thermal_velocities<2>(std::int64_t, double, Rng&);
template VecArray<3> thermal_velocities<3>(std::int64_t, double, Rng&);
template Vec<1> random_direction<1>(Rng&);
template Vec<2> random_direction<2>(Rng&);
template Vec<3> random_direction<3>(Rng&);
template InitialState<1> make_initial_state<1>(const PhysicsConfig&);
template InitialState<2> make_initial_state<2>(const PhysicsConfig&);
template InitialState<3> make_initial_state<3>(const PhysicsConfig&);

}  // namespace gs
