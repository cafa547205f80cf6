#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "sim/error.h"
#include "sim/observables.h"
#include "sim/rng.h"

namespace gs {
namespace {

constexpr double pi = std::numbers::pi;

Snapshot make_snapshot(int dim, double box = 0) {
  Snapshot s;
  s.info.dim = dim;
  s.info.set_cubic_box(box);
  return s;
}

void add(Snapshot& s, Eigen::Vector3d x, Eigen::Vector3d v = Eigen::Vector3d::Zero(),
         bool active = true) {
  s.position.push_back(x);
  s.velocity.push_back(v);
  s.radius.push_back(0.5);
  s.active.push_back(active ? 1 : 0);
}

TEST(Observables, GyrationEigenvaluesOfRotatedEllipse) {
  // Evenly spaced angles on x = a cos, y = b sin: the mean of cos^2 over them is exactly 1/2, so
  // the gyration eigenvalues are a^2/2 and b^2/2 whatever the rotation.
  const double a = 7, b = 3, rot = 0.6;
  Snapshot s = make_snapshot(2);
  const Eigen::Vector3d offset(100, -40, 0);
  for (int i = 0; i < 360; ++i) {
    const double th = 2 * pi * i / 360;
    const double x = a * std::cos(th), y = b * std::sin(th);
    add(s, offset + Eigen::Vector3d(x * std::cos(rot) - y * std::sin(rot),
                                    x * std::sin(rot) + y * std::cos(rot), 0));
  }
  add(s, Eigen::Vector3d(1e6, 1e6, 0), Eigen::Vector3d::Zero(), false);  // passive: ignored
  const Shape sh = measure_shape(s);
  // Tolerances: round-off of sums of 360 terms of size ~50, relative 1e-12 is ~1e4 ulps of room.
  EXPECT_EQ(sh.active, 360u);
  EXPECT_NEAR(sh.centre.x(), 100, 1e-10);
  EXPECT_NEAR(sh.centre.y(), -40, 1e-10);
  EXPECT_NEAR(sh.eigenvalues[0], a * a / 2, 1e-10);
  EXPECT_NEAR(sh.eigenvalues[1], b * b / 2, 1e-10);
  EXPECT_NEAR(sh.radius_rms, std::sqrt((a * a + b * b) / 2), 1e-10);
  const double q = (a * a - b * b) / (a * a + b * b);
  EXPECT_NEAR(sh.anisotropy, q * q, 1e-12);
}

TEST(Observables, AnisotropyZeroForRingAndShell) {
  Snapshot ring = make_snapshot(2);
  for (int i = 0; i < 12; ++i)
    add(ring, Eigen::Vector3d(5 * std::cos(2 * pi * i / 12), 5 * std::sin(2 * pi * i / 12), 0));
  // Tolerance: an exactly isotropic set; only round-off (~1e-16 relative) separates l1 and l2.
  EXPECT_NEAR(measure_shape(ring).anisotropy, 0, 1e-14);

  // The 8 cube vertices plus the 6 octahedron vertices: gyration tensor proportional to identity.
  Snapshot shell = make_snapshot(3);
  for (int i = 0; i < 8; ++i)
    add(shell, Eigen::Vector3d(i & 1 ? 1 : -1, i & 2 ? 1 : -1, i & 4 ? 1 : -1) / std::sqrt(3.0));
  for (int k = 0; k < 3; ++k)
    for (int sgn : {-1, 1}) {
      Eigen::Vector3d x = Eigen::Vector3d::Zero();
      x[k] = sgn;
      add(shell, x);
    }
  const Shape sh = measure_shape(shell);
  EXPECT_NEAR(sh.anisotropy, 0, 1e-14);
  EXPECT_NEAR(sh.eigenvalues[0], 1.0 / 3.0, 1e-14);
  EXPECT_NEAR(sh.eigenvalues[2], 1.0 / 3.0, 1e-14);
}

TEST(Observables, RadialMomentumOfAHandMadeConfiguration) {
  // Three particles at (0,0), (4,0), (2,6): centre of mass (2,2). Directions u_i from it:
  // (-1,-1)/sqrt2, (1,-1)/sqrt2, (0,1), summing to w = (0, 1 - sqrt2). Each moves outward at
  // speed 1 plus a common drift (1,1): V = drift + w/3, so v_i - V = u_i - w/3 and
  // P_r = 3 - w.w/3 = 3 - (1 - sqrt2)^2/3 = 2.94281. In the lab frame the drift would add
  // (1,1).w = 1 - sqrt2 instead (2.58579).
  Snapshot s = make_snapshot(2);
  const Eigen::Vector3d drift(1, 1, 0);
  const double h = 1 / std::sqrt(2.0);
  add(s, {0, 0, 0}, drift + Eigen::Vector3d(-h, -h, 0));
  add(s, {4, 0, 0}, drift + Eigen::Vector3d(h, -h, 0));
  add(s, {2, 6, 0}, drift + Eigen::Vector3d(0, 1, 0));
  add(s, {50, 50, 0}, {9, 9, 0}, false);  // at rest in the count: not active, ignored
  // Tolerance: three terms of size 1, round-off only.
  const double w2 = (1 - std::sqrt(2.0)) * (1 - std::sqrt(2.0));
  EXPECT_NEAR(radial_momentum(s), 3 - w2 / 3, 1e-12);
  // Moving inward instead: the opposite. The drift alone: 0.
  Snapshot in = s, still = s;
  for (std::size_t i = 0; i < 3; ++i) {
    in.velocity[i] = drift - (s.velocity[i] - drift);
    still.velocity[i] = drift;
  }
  EXPECT_NEAR(radial_momentum(in), -(3 - w2 / 3), 1e-12);
  EXPECT_NEAR(radial_momentum(still), 0, 1e-12);
  // 3D: a particle on each axis moving out at 2: P_r = 6 x 2.
  Snapshot b = make_snapshot(3);
  for (int k = 0; k < 3; ++k)
    for (const double sign : {-1.0, 1.0}) {
      Eigen::Vector3d x = Eigen::Vector3d::Zero();
      x[k] = 5 * sign;
      add(b, x, 2 * x / 5);
    }
  EXPECT_NEAR(radial_momentum(b), 12, 1e-12);
}

TEST(Observables, IsotropicAnisotropyIsTheFiniteNFloor) {
  // N points on a ring (2D) or sphere (3D) with uniform directions: A = 2 tr(G'^2) / tr(G)^2
  // (G' the traceless part) has mean (1/N) x E tr((u u^T - I/d)^2) x d/(d-1)... worked for both:
  // 2D: ((l1-l2)/(l1+l2))^2 = |sum e^(2i theta)|^2 / N^2, mean 1/N; 3D: kappa^2 = (3/2)
  // tr(G'^2) / tr(G)^2, mean (3/2)(2/3)/N = 1/N. The centre's own scatter changes that by
  // O(1/N^2). So A N -> 1 whatever the input's shape: a straight line (A = 1) reads ~1/N too.
  for (int d : {2, 3}) {
    Snapshot line = make_snapshot(d);
    const int n = 400;
    for (int i = 0; i < n; ++i) add(line, {double(i) - n / 2.0, 0, 0});
    // Fold every point to the same distance from the centre: a ring or shell once shuffled.
    for (auto& x : line.position) x = {x[0] >= 0 ? 10.0 : -10.0, 0, 0};
    EXPECT_GT(measure_shape(line).anisotropy, 0.99);  // the line itself
    Rng rng(3, 0, Stream::Shuffle);
    // 400 draws: A N per draw is ~exponential (2D) with standard deviation ~1, so the mean
    // of 400 is 1 +- 0.05; 0.2 is 4 standard errors.
    const double a = isotropic_anisotropy(line, rng, 400);
    EXPECT_NEAR(a * n, 1, 0.2) << "d = " << d;
  }
  Snapshot one = make_snapshot(2);
  add(one, {1, 2, 0});
  Rng rng(1, 0, Stream::Shuffle);
  EXPECT_EQ(isotropic_anisotropy(one, rng), 0);  // no shape of one point
}

TEST(Observables, AnisotropyNearOneForThinLine) {
  for (int dim : {2, 3}) {
    Snapshot s = make_snapshot(dim);
    for (int i = 0; i < 101; ++i) {
      const double w = 0.01 * (i % 2 ? 1 : -1);
      add(s, Eigen::Vector3d(i, w, dim == 3 ? w * (i % 3 ? 1 : -1) : 0));
    }
    const Shape sh = measure_shape(s);
    // Transverse variance 1e-4 against 850 along the line: A = 1 - O(1e-6) < 1, so 0.999 is far
    // below the value and 1 is still excluded.
    EXPECT_GT(sh.anisotropy, 0.999) << dim;
    EXPECT_LT(sh.anisotropy, 1.0) << dim;
  }
}

TEST(Observables, AnisotropyStaysInUnitInterval) {
  Rng rng(7, 0, Stream::Positions);
  for (int dim : {2, 3})
    for (int trial = 0; trial < 50; ++trial) {
      Snapshot s = make_snapshot(dim);
      const Eigen::Vector3d scale(1 + 5 * rng.uniform(), 1 + 5 * rng.uniform(), rng.uniform());
      for (int i = 0; i < 200; ++i) {
        Eigen::Vector3d x(rng.normal(), rng.normal(), dim == 3 ? rng.normal() : 0);
        add(s, x.cwiseProduct(scale));
      }
      const double A = measure_shape(s).anisotropy;
      EXPECT_GE(A, 0.0);
      EXPECT_LT(A, 1.0);
    }
  // The 3D index of a disc-like set (l1 = l2, l3 = 0) is 1/4 by its definition.
  EXPECT_NEAR(anisotropy_index(3, Eigen::Vector3d(1, 1, 0)), 0.25, 1e-15);
  EXPECT_NEAR(anisotropy_index(3, Eigen::Vector3d(1, 0, 0)), 1.0, 1e-15);
}

Snapshot random_gas(int dim, int n, std::uint64_t seed) {
  Rng rng(seed, 0, Stream::Positions);
  Snapshot s = make_snapshot(dim);
  for (int i = 0; i < n; ++i) {
    Eigen::Vector3d x(rng.normal(), rng.normal(), dim == 3 ? rng.normal() : 0);
    Eigen::Vector3d v(rng.normal(), rng.normal(), dim == 3 ? rng.normal() : 0);
    add(s, 30 * x, v, i % 3 != 0);
  }
  return s;
}

TEST(Observables, DistributionsAreNormalised) {
  for (int dim : {2, 3}) {
    const Snapshot s = random_gas(dim, 3000, 11 + dim);
    // Tolerance 1e-12: a sum of 50 products of order 1 carries ~1e-15 round-off.
    const Histogram pr = radial_distribution(s, {.bins = 50});
    EXPECT_EQ(pr.samples, 2000u);
    EXPECT_EQ(pr.outside, 0u);
    EXPECT_NEAR(pr.integral(), 1.0, 1e-12);
    const Histogram pv = speed_distribution(s, {.bins = 37});
    EXPECT_NEAR(pv.integral(), 1.0, 1e-12);
    // Scaled forms keep the normalisation (Eqs. 9, 10 of the paper).
    EXPECT_NEAR(scaled_radial_distribution(pr, 5000, 1.0 / 3).integral(), 1.0, 1e-12);
    EXPECT_NEAR(scaled_speed_distribution(pv, 5000, 1.0 / 3).integral(), 1.0, 1e-12);
    EXPECT_NEAR(scaled_radial_distribution(pr, 5000, 1.0 / 3).edges.back(),
                pr.edges.back() * std::pow(5000, -1.0 / 3), 1e-12);
  }
  // With a fixed range the integral is the fraction inside it.
  const std::vector<double> x = {0.5, 1.5, 2.5, 9.0};
  const Histogram h = make_histogram(x, {.bins = 3, .lo = 0, .hi = 3});
  EXPECT_EQ(h.outside, 1u);
  EXPECT_NEAR(h.integral(), 0.75, 1e-15);
  EXPECT_THROW(make_histogram(x, {.bins = 0}), UserError);
  EXPECT_THROW(scaled_radial_distribution(h, 0.0, 0.5), UserError);
}

TEST(Observables, ActiveSubsetKeepsTheActiveParticlesAndTheirMeasures) {
  Snapshot s = random_gas(3, 3000, 7);
  s.first_collision.assign(s.size(), -1.0);
  for (std::size_t i = 0; i < s.size(); ++i)
    if (s.active[i]) s.first_collision[i] = double(i);
  const Snapshot a = active_subset(s);
  ASSERT_EQ(a.size(), 2000u);  // random_gas leaves every third particle inactive
  ASSERT_EQ(a.velocity.size(), a.size());
  ASSERT_EQ(a.radius.size(), a.size());
  ASSERT_EQ(a.first_collision.size(), a.size());
  EXPECT_EQ(std::count(a.active.begin(), a.active.end(), 1), 2000);
  // Particle order is kept: the k-th active particle of s is the k-th of the subset.
  for (std::size_t i = 0, k = 0; i < s.size(); ++i) {
    if (!s.active[i]) continue;
    EXPECT_EQ(a.position[k], s.position[i]);
    EXPECT_EQ(a.first_collision[k], double(i));
    ++k;
  }
  // Same particles in the same order, so the measures agree bit for bit.
  EXPECT_EQ(radial_distribution(a, {.bins = 40}).values,
            radial_distribution(s, {.bins = 40}).values);
  EXPECT_EQ(speed_distribution(a, {.bins = 40}).values, speed_distribution(s, {.bins = 40}).values);
  EXPECT_EQ(measure_shape(a).gyration, measure_shape(s).gyration);
  const RadialProfile pa = radial_profile(a, {.bins = 40}), ps = radial_profile(s, {.bins = 40});
  EXPECT_EQ(pa.edges, ps.edges);
  EXPECT_EQ(pa.count, ps.count);
  EXPECT_EQ(pa.speed_sum, ps.speed_sum);
  EXPECT_EQ(pa.radial_velocity_sum, ps.radial_velocity_sum);
}

// Before the first collision nothing is active: the subset has no particles, and so no speeds,
// which is not a snapshot without velocities (an ensemble sampled at t = 1 failed on it).
TEST(Observables, NothingActiveYetGivesNoSpeedsRatherThanAnError) {
  Snapshot s = random_gas(2, 500, 3);
  s.active.assign(s.size(), 0);
  const Snapshot a = active_subset(s);
  ASSERT_EQ(a.size(), 0u);
  EXPECT_TRUE(a.has_velocity());
  EXPECT_TRUE(active_speeds(a).empty());
  Snapshot no_velocities = s;
  no_velocities.velocity.clear();
  EXPECT_THROW(active_speeds(no_velocities), UserError);
}

// radial_profile bins by the histogram's own rule: its shells are P(R,t)'s bins, sample for
// sample, with the upper edge inside the last bin and samples on an inner edge in the bin above.
TEST(Observables, RadialProfileShellsAreTheHistogramBins) {
  for (int dim : {2, 3}) {
    const Snapshot s = random_gas(dim, 3000, 5 + dim);
    for (const Binning b : {Binning{.bins = 40}, Binning{.bins = 7, .lo = 2, .hi = 9}}) {
      const Histogram h = radial_distribution(s, b);
      const RadialProfile p = radial_profile(s, b);
      ASSERT_EQ(p.edges, h.edges);
      for (std::size_t k = 0; k < h.bins(); ++k)
        EXPECT_EQ(double(p.count[k]), std::round(h.values[k] * double(h.samples) * h.width(k)));
    }
  }
  const std::vector<double> edges = histogram_edges(std::vector<double>{0.3, 4.0}, {.bins = 4});
  ASSERT_EQ(edges, (std::vector<double>{0, 1, 2, 3, 4}));
  EXPECT_EQ(bin_of(edges, 0.0), 0u);
  EXPECT_EQ(bin_of(edges, 1.0), 1u);
  EXPECT_EQ(bin_of(edges, std::nextafter(3.0, 0.0)), 2u);
  EXPECT_EQ(bin_of(edges, 4.0), 3u);  // the upper edge: the last bin
}

TEST(Observables, BandPackingOfSquareLattice) {
  // Square lattice of spacing a = 1.25 in a periodic box of side 100: 64 discs per 10 x 10 cell,
  // packing 64 * pi/4 / 100 exactly, in every cell.
  const double a = 1.25, box = 100;
  Snapshot s = make_snapshot(2, box);
  for (int i = 0; i < 80; ++i)
    for (int j = 0; j < 80; ++j) {
      // The band lives at x < 50; unwrapped images (x - box) must land in the same cells.
      const double x = (i + 0.5) * a, y = (j + 0.5) * a;
      const bool band = x < 50;
      add(s, Eigen::Vector3d(band && j % 2 ? x - box : x, y, 0), Eigen::Vector3d::Zero(), band);
    }
  const BandPacking p = band_packing(s);
  const double expected = 64 * pi / 4 / 100;
  EXPECT_DOUBLE_EQ(p.cell_side, 10.0);
  EXPECT_EQ(p.fraction.size(), 50u);  // 5 columns of cells hold the band, 10 rows
  // Tolerance: identical cells, so only the round-off of 64 additions (~1e-14).
  EXPECT_NEAR(p.typical, expected, 1e-12);
  EXPECT_NEAR(p.mean, expected, 1e-12);
  EXPECT_NEAR(p.mode, expected, 0.5 / 50);  // the centre of the bin of width 1/50 holding it
  EXPECT_NEAR(p.distribution.integral(), 1.0, 1e-12);
  EXPECT_NEAR(p.upper, expected, 1e-12);

  // One stray active particle in a cell of the passive half: that cell becomes a band cell of
  // 64 passive + 1 active discs, weight 1 against 50 cells of weight 64. Its passive discs count
  // (packing of all particles), and the weighting keeps it from pulling the typical value.
  // Expected values from the definitions; round-off only.
  add(s, Eigen::Vector3d(75.1, 75.1, 0));
  const BandPacking q = band_packing(s);
  const double stray = 65 * pi / 4 / 100;
  EXPECT_EQ(q.fraction.size(), 51u);
  EXPECT_NEAR(q.typical, (50 * 64 * expected + stray) / (50 * 64 + 1), 1e-12);
  EXPECT_NEAR(q.mean, (50 * expected + stray) / 51, 1e-12);
  EXPECT_NEAR(q.upper, expected, 1e-12);
}

TEST(Observables, BandPackingWeighsCellsByTheirBandParticles) {
  // A full cell of 64 discs and, far away, a cell with one disc: the edge-of-band situation.
  Snapshot s = make_snapshot(2);
  for (int i = 0; i < 8; ++i)
    for (int j = 0; j < 8; ++j) add(s, Eigen::Vector3d((i + 0.5) * 1.25, (j + 0.5) * 1.25, 0));
  add(s, Eigen::Vector3d(55, 55, 0));
  const BandPacking p = band_packing(s);
  const double full = 64 * pi / 400, single = pi / 400;
  // Expected values from the definitions; round-off only.
  EXPECT_NEAR(p.typical, (64 * full + single) / 65, 1e-12);
  EXPECT_NEAR(p.mean, (full + single) / 2, 1e-12);
  EXPECT_NEAR(p.upper, full, 1e-12);  // 90% of the weight lies in the full cell
  EXPECT_THROW(band_packing(s, {.upper_quantile = 0}), UserError);
}

TEST(Observables, BandPackingOfHexagonalLattice) {
  // Triangular lattice of spacing a: packing pi / (2 sqrt 3 a^2); a = 1.1 gives 0.7495.
  const double a = 1.1;
  Snapshot s = make_snapshot(2);  // no box: unbounded cells of side 10
  const double h = a * std::sqrt(3.0) / 2;
  for (int j = 0; h * (j + 0.5) < 200; ++j)
    for (int i = 0;; ++i) {
      const double x = a * (i + 0.25 + 0.5 * (j % 2));
      if (x >= 200) break;
      add(s, Eigen::Vector3d(x, h * (j + 0.5), 0));
    }
  const BandPacking p = band_packing(s);
  const double expected = pi / (2 * std::sqrt(3.0) * a * a);
  // Tolerance 1%: a 10 x 10 cell cuts rows and columns of the lattice, so its count varies by
  // about one row (~9 of ~95 discs) from cell to cell, but these offsets average out over the 400
  // cells to about a row over the whole 200 x 200 region, i.e. a / 200 ~ 0.6%.
  EXPECT_NEAR(p.typical / expected, 1.0, 0.01);
  EXPECT_NEAR(p.mean / expected, 1.0, 0.01);
  EXPECT_EQ(p.fraction.size(), 400u);
}

TEST(Observables, BandPackingOfSimpleCubicLattice) {
  // Spacing 2 in a box of side 40: 125 spheres of volume pi/6 per 10^3 cell.
  Snapshot s = make_snapshot(3, 40);
  for (int i = 0; i < 20; ++i)
    for (int j = 0; j < 20; ++j)
      for (int k = 0; k < 20; ++k)
        add(s, Eigen::Vector3d(2 * i + 1, 2 * j + 1, 2 * k + 1), Eigen::Vector3d::Zero(), i < 5);
  const BandPacking p = band_packing(s);
  EXPECT_EQ(p.fraction.size(), 16u);
  EXPECT_NEAR(p.typical, 125 * pi / 6 / 1000, 1e-12);  // identical cells: round-off only
}

TEST(Observables, RadialProfileAndFastInnerEdge) {
  // Two rings around the origin: the inner one (R = 10) moving outward at 2, the outer one
  // (R = 20) at 1. The centre of mass is the origin and its velocity zero by symmetry.
  Snapshot s = make_snapshot(2);
  for (double R : {10.0, 20.0})
    for (int i = 0; i < 64; ++i) {
      const Eigen::Vector3d u(std::cos(2 * pi * i / 64), std::sin(2 * pi * i / 64), 0);
      add(s, R * u, (R == 10 ? 2.0 : 1.0) * u);
    }
  const RadialProfile p = radial_profile(s, {.bins = 4, .lo = 0, .hi = 24});
  ASSERT_EQ(p.count.size(), 4u);
  EXPECT_EQ(p.count[1], 64u);  // [6, 12)
  EXPECT_EQ(p.count[3], 64u);  // [18, 24]
  EXPECT_EQ(p.count[0] + p.count[2], 0u);
  // Tolerances: exact symmetric sets, round-off only.
  EXPECT_NEAR(p.density[1], 64 / (pi * (144 - 36)), 1e-12);
  EXPECT_NEAR(p.mean_speed[1], 2, 1e-12);
  EXPECT_NEAR(p.mean_radial_velocity[1], 2, 1e-12);
  EXPECT_NEAR(p.mean_radial_velocity[3], 1, 1e-12);
  EXPECT_TRUE(std::isnan(p.mean_speed[0]));
  const InnerEdge e = inner_edge_speed(s);
  EXPECT_NEAR(e.correlation, -1, 1e-12);  // speed is a decreasing function of R here
  EXPECT_NEAR(e.ratio, 2, 1e-12);
  // Reversed: faster outside gives the opposite signs.
  for (auto& v : s.velocity) v *= v.norm() > 1.5 ? 0.25 : 1.0;
  const InnerEdge f = inner_edge_speed(s);
  EXPECT_NEAR(f.correlation, 1, 1e-12);
  EXPECT_NEAR(f.ratio, 0.5, 1e-12);
}

// The profile from positions and speeds alone (a movie's inset) is radial_profile's, bit for
// bit, on an irregular band with particles at rest left out.
TEST(Observables, SpeedProfileIsTheRadialProfileOfTheActiveParticles) {
  Snapshot s = make_snapshot(2);
  std::vector<Eigen::Vector3d> x;
  std::vector<double> v;
  for (int i = 0; i < 500; ++i) {
    const double a = 0.37 * i, R = 30 + 7 * std::sin(1.3 * i);
    const Eigen::Vector3d u(std::cos(a), std::sin(a), 0), vel = (0.5 + 0.3 * std::cos(i)) * u;
    const bool active = i % 5 != 0;
    add(s, Eigen::Vector3d(50, 50, 0) + R * u, active ? vel : Eigen::Vector3d::Zero(), active);
    if (active) x.push_back(s.position.back()), v.push_back(vel.norm());
  }
  const Binning b{.bins = 17};
  const RadialProfile p = radial_profile(s, b), q = speed_profile(2, x, v, b);
  EXPECT_EQ(q.edges, p.edges);
  EXPECT_EQ(q.count, p.count);
  EXPECT_EQ(q.density, p.density);
  ASSERT_EQ(q.mean_speed.size(), p.mean_speed.size());
  for (std::size_t k = 0; k < p.mean_speed.size(); ++k)
    if (p.count[k]) {
      EXPECT_EQ(q.mean_speed[k], p.mean_speed[k]) << k;
    }
  EXPECT_TRUE(q.mean_radial_velocity.empty());
}

TEST(Observables, RejectsBadSnapshots) {
  Snapshot s = make_snapshot(4);
  add(s, Eigen::Vector3d::Zero());
  EXPECT_THROW(measure_shape(s), UserError);
  Snapshot t = make_snapshot(2);
  t.position.push_back(Eigen::Vector3d::Zero());
  EXPECT_THROW(speed_distribution(t), UserError);  // no velocities in the file
}

}  // namespace
}  // namespace gs
