// The observables and the collapse measure on real runs of the engine: small 2D systems, a few
// realisations, fixed seeds.
#include <gtest/gtest.h>

#include <cmath>

#include "analysis/collapse.h"
#include "analysis/ensemble.h"
#include "sim/engine.h"
#include "sim/observables.h"

namespace gs {
namespace {

TEST(BandPhysics, ShapeAgreesWithTheEngineSample) {
  // Two independent codes for N_t, R_t and v_t: the engine's Sample and measure_shape on its
  // snapshot (unwrapped positions). Tolerance 1e-9 relative: the same sums in other orders.
  PhysicsConfig c;
  c.dim = 2;
  c.particles = 20000;
  c.restitution = 0.5;
  auto sim = make_simulation(c);
  for (double t : {30.0, 300.0, 3000.0}) {
    sim->run_until(t);
    const Sample smp = sim->sample();
    const Shape sh = measure_shape(sim->snapshot());
    EXPECT_EQ(std::int64_t(sh.active), smp.active);
    EXPECT_NEAR(sh.radius_rms, smp.radius_rms, 1e-9 * smp.radius_rms);
    EXPECT_NEAR(sh.speed_rms, smp.speed_rms, 1e-9 * smp.speed_rms);
  }
}

TEST(BandPhysics, AnisotropyOfElasticBlastVanishes) {
  // The paper: A(t) -> 0 for r = 1. 1e5 discs (box 632), up to t = 1e4 where N_t ~ 3e4 and
  // R ~ 130. A shapeless cloud of N points has A ~ 1.3 / N from sampling alone (4e-5 here); the
  // early blast is still elongated along the kick (A ~ 0.03 at t = 100). Thresholds: below 0.01
  // at the end (far above the sampling floor, far below the early value) and ten times below
  // its value at t = 100.
  PhysicsConfig c;
  c.dim = 2;
  c.particles = 100000;
  c.restitution = 1.0;
  const std::vector<double> times = {100, 300, 1000, 3000, 10000};
  std::vector<double> mean_a(times.size(), 0.0);
  const int realisations = 4;
  for (int k = 0; k < realisations; ++k) {
    c.realisation = std::uint64_t(k);
    auto sim = make_simulation(c);
    for (std::size_t i = 0; i < times.size(); ++i) {
      sim->run_until(times[i]);
      const double a = measure_shape(sim->snapshot()).anisotropy;
      EXPECT_GE(a, 0.0);
      EXPECT_LT(a, 1.0);
      mean_a[i] += a / realisations;
    }
  }
  EXPECT_LT(mean_a.back(), 0.01);
  EXPECT_LT(mean_a.back(), mean_a.front() / 10);
}

TEST(BandPhysics, ScaledDistributionsCollapseWithAlphaOneThird) {
  // The paper's Fig. 4 setting: 2.5e5 discs, r = 0.1, three times a factor 2 apart (paper units
  // t = 25000 ... 50000 are simulation t = 50000 ... 100000 at n = 0.25), three realisations.
  // The collapse quality must be best at alpha = 1/3 among 1/4 (the 3D value) and 1/2 (the 1D
  // value): a comparison, no tolerance.
  PhysicsConfig c;
  c.dim = 2;
  c.particles = 250000;
  c.restitution = 0.1;
  const std::vector<double> times = {50000, 75000, 100000};
  std::vector<HistogramAverage> pr(times.size()), pv(times.size());
  double ratio = 0, correlation = 0;
  const int realisations = 3;
  for (int k = 0; k < realisations; ++k) {
    c.realisation = std::uint64_t(k);
    auto sim = make_simulation(c);
    for (std::size_t i = 0; i < times.size(); ++i) {
      sim->run_until(times[i]);
      const Snapshot s = sim->snapshot();
      // Fixed bins that scale as R_t ~ 1.9 t^(1/3) and v_t ~ 0.65 t^(-2/3) (measured at these
      // sizes), so that the realisations share them: about 2 R_t and 4.6 v_t wide.
      const double t = times[i];
      pr[i].add(radial_distribution(s, {.bins = 30, .lo = 0, .hi = 4 * std::cbrt(t)}), "P(R)");
      pv[i].add(speed_distribution(s, {.bins = 30, .lo = 0, .hi = 3 * std::pow(t, -2.0 / 3)}),
                "P(v)");
      if (i + 1 == times.size()) {
        const InnerEdge e = inner_edge_speed(s);
        ratio += e.ratio / realisations;
        correlation += e.correlation / realisations;
      }
    }
  }
  auto quality = [&](double alpha) {
    std::vector<Curve> r, v;
    for (std::size_t i = 0; i < times.size(); ++i) {
      r.push_back(curve_of(scaled_radial_distribution(pr[i].mean(), times[i], alpha)));
      v.push_back(curve_of(scaled_speed_distribution(pv[i].mean(), times[i], alpha)));
    }
    return std::pair{collapse_quality(r), collapse_quality(v)};
  };
  const auto third = quality(1.0 / 3), quarter = quality(0.25), half = quality(0.5);
  EXPECT_LT(third.first, quarter.first);
  EXPECT_LT(third.first, half.first);
  EXPECT_LT(third.second, quarter.second);
  EXPECT_LT(third.second, half.second);
  // The paper: "the faster particles are in the inside edge of the collapsed band".
  EXPECT_GT(ratio, 1.0);
  EXPECT_LT(correlation, 0.0);
}

}  // namespace
}  // namespace gs
