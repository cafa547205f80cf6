// Dense thermal starts (sim/melt.h): a melted lattice is a fluid at the asked density.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "sim/engine.h"
#include "sim/error.h"
#include "sim/initial.h"
#include "sim/melt.h"
#include "tests/sim/thermal_config.h"

namespace gs {
namespace {

PhysicsConfig dense(int dim, std::int64_t n, double packing) {
  PhysicsConfig c = test::thermal(dim, n, 0.9);  // melting is elastic whatever r
  c.density = packing / (dim == 2 ? std::numbers::pi / 4 : std::numbers::pi / 6);
  c.temperature = 2.0;
  validate(c);
  return c;
}

// Kolmogorov-Smirnov distance of the velocity components from the normal law of variance T.
template <int D>
double ks_distance(const VecArray<D>& v, double temperature) {
  std::vector<double> u;
  for (const auto& x : v)
    for (int k = 0; k < D; ++k) u.push_back(x[k] / std::sqrt(temperature));
  std::sort(u.begin(), u.end());
  double worst = 0;
  const double n = static_cast<double>(u.size());
  for (std::size_t i = 0; i < u.size(); ++i) {
    const double cdf = 0.5 * std::erfc(-u[i] / std::sqrt(2.0));
    worst = std::max({worst, cdf - static_cast<double>(i) / n, (i + 1) / n - cdf});
  }
  return worst;
}

template <int D>
void check_melted(const PhysicsConfig& c) {
  MeltReport report;
  const InitialState<D> s = melted_lattice<D>(c, &report);
  const auto n = static_cast<std::size_t>(c.particles);
  ASSERT_EQ(s.position.size(), n);
  ASSERT_EQ(s.velocity.size(), n);
  const double box = c.box();

  // The density asked for, spread through the box: each of the 2^D orthants holds N / 2^D
  // within 5 standard deviations of an ideal gas's count (a dense fluid's are smaller). The
  // first N sites of the lattice, which left a slab empty, would fail in 3D.
  std::vector<int> count(1 << D, 0);
  for (const auto& x : s.position) {
    int orthant = 0;
    for (int k = 0; k < D; ++k) {
      ASSERT_GE(x[k], 0.0);
      ASSERT_LT(x[k], box);
      orthant |= (x[k] >= box / 2) << k;
    }
    ++count[orthant];
  }
  const double mean = static_cast<double>(n) / (1 << D);
  for (const int m : count) EXPECT_NEAR(m, mean, 5 * std::sqrt(mean));

  // No overlaps: an engine started from it finds none.
  const Engine<D> engine(c, s);
  EXPECT_LE(engine.max_overlap_now(), 1e-9);

  // Maxwell velocities: zero momentum, the temperature exactly, the kurtosis of a component 3
  // (its standard error is sqrt(24 / (D N)), 0.045 in 2D and 0.037 in 3D; 0.2 is over 4 of it),
  // and the KS distance under 1.95 / sqrt(D N), the 0.1% critical value.
  Vec<D> p = Vec<D>::Zero();
  double v2 = 0, v4 = 0;
  for (const auto& v : s.velocity) {
    p += v;
    for (int k = 0; k < D; ++k) v2 += v[k] * v[k], v4 += std::pow(v[k], 4);
  }
  const double samples = static_cast<double>(D * n);
  EXPECT_LT(p.norm(), 1e-9);
  EXPECT_NEAR(v2 / samples, c.temperature, 1e-12);
  EXPECT_NEAR((v4 / samples) / std::pow(v2 / samples, 2), 3.0, 0.2);
  EXPECT_LT(ks_distance<D>(s.velocity, c.temperature), 1.95 / std::sqrt(samples));

  // The lattice is gone: its order parameter at a fluid's level, where the lattice itself (with
  // its vacancies) has 1.
  const std::int64_t side = lattice_side(c.particles, D);
  EXPECT_LE(lattice_order<D>(s.position, box, side), melted_order(c.particles));
  EXPECT_NEAR(report.order, lattice_order<D>(s.position, box, side), 1e-12);
  Rng rng(c.seed, c.realisation, Stream::Positions);
  EXPECT_NEAR(lattice_order<D>(cubic_lattice<D>(c.particles, box, rng), box, side), 1.0, 1e-9);
  EXPECT_GE(report.collisions, kMeltCheckCollisions * c.particles);
}

TEST(Melt, DenseSphereFluidFromALattice) {
  check_melted<3>(dense(3, 4000, 0.45));
}

TEST(Melt, DenseDiscFluidFromALattice) {
  check_melted<2>(dense(2, 4000, 0.65));
}

// Above the random sequential addition limit a thermal start is the melted lattice, the same
// bits from the same seed; a kick there is still refused.
TEST(Melt, ThermalStartAboveTheRsaLimitIsTheMeltedLattice) {
  const PhysicsConfig c = dense(3, 1000, 0.45);
  const InitialState<3> a = make_initial_state<3>(c), b = melted_lattice<3>(c);
  ASSERT_EQ(a.position.size(), b.position.size());
  for (std::size_t i = 0; i < a.position.size(); ++i) {
    EXPECT_EQ(a.position[i], b.position[i]);
    EXPECT_EQ(a.velocity[i], b.velocity[i]);
  }
  PhysicsConfig kick = c;
  kick.initial = Initial::Kick;
  EXPECT_THROW(validate(kick), UserError);
}

// Past the fluid's limit, or a lattice that does not fit with a gap, is refused by name.
TEST(Melt, TooDenseIsRefused) {
  for (const auto& [dim, packing] : {std::pair{3, 0.53}, std::pair{2, 0.72}}) {
    PhysicsConfig c = test::thermal(dim, 100000, 1.0);
    c.density = packing / (dim == 2 ? std::numbers::pi / 4 : std::numbers::pi / 6);
    try {
      validate(c);
      ADD_FAILURE() << dim << "D packing " << packing << " accepted";
    } catch (const UserError& e) {
      EXPECT_NE(std::string(e.what()).find("--density"), std::string::npos) << e.what();
    }
  }
  // 1e5 spheres need 47 sites per side, which at packing 0.515 are under 1.001 apart.
  PhysicsConfig c = test::thermal(3, 100000, 1.0);
  c.density = 0.515 * 6 / std::numbers::pi;
  EXPECT_THROW(validate(c), UserError);
  c.density = 0.5 * 6 / std::numbers::pi;
  EXPECT_NO_THROW(validate(c));
}

}  // namespace
}  // namespace gs
