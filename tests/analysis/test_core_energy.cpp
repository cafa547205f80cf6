// The hot core's share of the energy and the kinetic pressure profile (analysis/core_energy.h)
// on a synthetic blast: a hot, dilute core of known temperature inside an empty gap and a cold,
// dense shell moving outward. Each particle comes with its mirror image (-x, -v), so the centre
// of mass and its velocity are exactly 0, and thermal velocities have a fixed magnitude
// sqrt(d T) perpendicular to the radius, so that every sum the measures take is known exactly.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

#include "analysis/band_measures.h"
#include "analysis/core_energy.h"
#include "analysis/ensemble_sums.h"
#include "analysis/table.h"
#include "sim/error.h"
#include "sim/observables.h"

namespace gs {
namespace {

constexpr double kAmbient = 0.25;
constexpr double kCoreT = 1.0, kShellT = 0.01, kShellSpeed = 0.5;
constexpr double kCoreRadius = 60, kShellIn = 80, kShellOut = 86, kShellDensity = 0.7;
constexpr double kFlowAtEdge = 0.5;  // the core's homologous outward flow u = h rho at rho = 60

// A random unit vector perpendicular to x (x != 0) in the first d axes.
Eigen::Vector3d tangent(const Eigen::Vector3d& x, int d, std::mt19937_64& rng) {
  std::normal_distribution<double> g;
  const Eigen::Vector3d r = x.normalized();
  for (;;) {
    Eigen::Vector3d e(g(rng), g(rng), d == 3 ? g(rng) : 0.0);
    e -= e.dot(r) * r;
    if (e.norm() > 1e-6) return e.normalized();
  }
}

struct Blast {
  Snapshot s;
  double core_energy = 0, total_energy = 0;  // as built
  double core_spacing = 0;                   // lattice spacing of the core
};

void add_pair(Blast& b, const Eigen::Vector3d& x, const Eigen::Vector3d& v, bool core) {
  for (double sign : {1.0, -1.0}) {
    b.s.position.push_back(sign * x);
    b.s.velocity.push_back(sign * v);
    b.s.active.push_back(1);
    b.s.radius.push_back(0.5);
    const double e = 0.5 * v.squaredNorm();
    b.total_energy += e;
    if (core) b.core_energy += e;
  }
}

// The core on a lattice of spacing a (number density 1/a^d, 0.1 here) within kCoreRadius, or
// with `into_shell` each point put at the same direction and a radius in [80.5, 85.5] (its
// velocities kept); the shell at random in [kShellIn, kShellOut].
Blast make_blast(int d, bool into_shell = false) {
  Blast b;
  b.s.info.dim = d;
  std::mt19937_64 rng(7);
  const double a = std::pow(10.0, 1.0 / d);
  b.core_spacing = a;
  const int m = int(kCoreRadius / a) + 1;
  const double h = kFlowAtEdge / kCoreRadius;
  // Half the lattice (the first nonzero coordinate positive); the mirror adds the other half.
  for (int i = 0; i <= m; ++i)
    for (int j = -m; j <= m; ++j)
      for (int k = (d == 3 ? -m : 0); k <= (d == 3 ? m : 0); ++k) {
        if (i == 0 && (j < 0 || (j == 0 && k <= 0))) continue;
        const Eigen::Vector3d x(a * i, a * j, a * k);
        const double rho = x.norm();
        if (rho > kCoreRadius) continue;
        const Eigen::Vector3d v = h * x + std::sqrt(d * kCoreT) * tangent(x, d, rng);
        const double moved = kShellIn + 0.5 + 5 * rho / kCoreRadius;
        add_pair(b, into_shell ? Eigen::Vector3d(x * moved / rho) : x, v, true);
      }
  const double shell_volume = ball_volume(d, kShellOut) - ball_volume(d, kShellIn);
  const auto pairs = std::size_t(0.5 * kShellDensity * shell_volume);
  std::uniform_real_distribution<double> u(-kShellOut, kShellOut);
  for (std::size_t n = 0; n < pairs;) {
    const Eigen::Vector3d x(u(rng), u(rng), d == 3 ? u(rng) : 0.0);
    if (x.norm() < kShellIn || x.norm() > kShellOut) continue;
    add_pair(b, x,
             kShellSpeed * x.normalized() + std::sqrt(d * kShellT) * tangent(x, d, rng), false);
    ++n;
  }
  return b;
}

// The core's share as built: exact up to rounding (tolerance 1e-9 relative: sums of ~1e4
// terms in another order).
void expect_known_share(int d) {
  const Blast b = make_blast(d);
  const CoreEnergy c = core_energy(b.s, kAmbient);
  // The inner edge lies in the empty gap's last shell before the shell (width 2).
  EXPECT_GT(c.inner, kShellIn - 2) << d;
  EXPECT_LE(c.inner, kShellIn + 1e-9) << d;
  EXPECT_NEAR(c.front, kShellOut, 2) << d;
  const double known = b.core_energy / b.total_energy;
  EXPECT_NEAR(c.share, known, 1e-9 * known) << d;
  EXPECT_NEAR(c.total_energy, b.total_energy, 1e-9 * b.total_energy) << d;
}

TEST(CoreEnergy, HotCoreHasItsKnownShare) {
  expect_known_share(2);
  expect_known_share(3);
}

TEST(CoreEnergy, CoreMovedIntoTheShellIsNotCore) {
  // The same core put into the shell (radii 80.5-85.5): no longer behind the inner edge, so the
  // share read is far from the hot core's (it is 0: nothing lies inside the edge).
  for (int d : {2, 3}) {
    const Blast b = make_blast(d, true);
    const CoreEnergy c = core_energy(b.s, kAmbient);
    const double known = b.core_energy / b.total_energy;
    EXPECT_GT(known, 0.3) << d;
    EXPECT_LT(c.share, 0.05 * known) << d;
  }
}

// The kinetic pressure of the core, volume-averaged over the shells of rho / R_front below
// 0.6 (rho < ~51, inside the core of radius 60): n T with n = 1 / a^d. Tolerance 2%: the lattice
// points inside a ball of radius 51 differ from n V by the lattice-point error of the ball
// (Gauss's circle problem: +0.37% in 2D, +0.07% in 3D measured here); the flow's gradient
// within a shell adds h^2 (width)^2 / 12 ~ 1e-4 T per particle. Without subtracting the flow the
// average would be ~ n (T + <(h rho)^2> / d): 1.05 n T in 2D, 1.036 n T in 3D, outside it.
double core_pressure_ratio(int d) {
  const Blast b = make_blast(d);
  const CoreEnergy c = core_energy(b.s, kAmbient);
  const PressureProfile p = kinetic_pressure(b.s, c.front, {.bins = 30, .lo = 0, .hi = 1.5});
  double pv = 0, volume = 0;
  for (std::size_t k = 0; k + 1 < p.edges.size(); ++k) {
    if (p.edges[k + 1] > 0.6 + 1e-12) break;
    const double v =
        ball_volume(d, p.edges[k + 1] * c.front) - ball_volume(d, p.edges[k] * c.front);
    pv += p.pressure[k] * v;
    volume += v;
  }
  return pv / volume / (kCoreT / std::pow(b.core_spacing, d));
}

TEST(CoreEnergy, CorePressureIsItsIdealGasPressure) {
  EXPECT_NEAR(core_pressure_ratio(2), 1, 0.02);
  EXPECT_NEAR(core_pressure_ratio(3), 1, 0.02);
}

TEST(CoreEnergy, PressureOfTheEmptyGapIsZeroAndTheShellsIsItsOwn) {
  // The gap (rho from 60 to 80) holds nobody: pressure 0. The shell's flow is radial and
  // uniform, so its pressure is n_s T_s from the tangential motion alone: checked over the
  // shells wholly inside [80, 86] within 10% (its random positions: ~1e3 discs a shell).
  const Blast b = make_blast(2);
  const CoreEnergy c = core_energy(b.s, kAmbient);
  const PressureProfile p = kinetic_pressure(b.s, c.front, {.bins = 150, .lo = 0, .hi = 1.5});
  for (std::size_t k = 0; k + 1 < p.edges.size(); ++k) {
    const double lo = p.edges[k] * c.front, hi = p.edges[k + 1] * c.front;
    if (lo > kCoreRadius + 1 && hi < kShellIn - 1) {
      EXPECT_EQ(p.pressure[k], 0) << lo;
    }
    if (lo > kShellIn + 0.5 && hi < kShellOut - 0.5) {
      EXPECT_NEAR(p.pressure[k], kShellDensity * kShellT, 0.1 * kShellDensity * kShellT) << lo;
    }
  }
}

TEST(CoreEnergy, RefusesSnapshotsItCannotMeasure) {
  Blast b = make_blast(2);
  b.s.velocity.clear();
  EXPECT_THROW(core_energy(b.s, kAmbient), UserError);
  EXPECT_THROW(kinetic_pressure(make_blast(2).s, 80, {.bins = 0, .lo = 0, .hi = 1}), UserError);
}

// The share's trend over a decade: a share falling as t^-0.5 with 5% standard errors reads
// "falls" (slope -0.5, sigma 0.031: 16 sigma), a constant one "flat", a rising one "rises"; the
// same falling share with 50% errors (sigma 0.31) is no longer told from flat. Slope exact to
// rounding (1e-12) on a pure power law.
TEST(CoreEnergy, ShareTrendTellsAFallingCoreFromAFlatOne) {
  std::vector<double> t, falling, flat, rising, sem5, sem50;
  for (int i = 0; i <= 40; ++i) {
    t.push_back(std::pow(10.0, 2 + i / 20.0));
    falling.push_back(0.1 * std::pow(t.back() / 100, -0.5));
    flat.push_back(0.08);
    rising.push_back(0.01 * std::pow(t.back() / 100, 0.3));
  }
  for (double y : falling) {
    sem5.push_back(0.05 * y);
    sem50.push_back(0.5 * y);
  }
  const CoreShareTrend f = core_share_trend(t, falling, sem5, 1e3, 1e4);
  EXPECT_EQ(f.reading, "falls");
  EXPECT_NEAR(f.slope, -0.5, 1e-12);
  EXPECT_NEAR(f.sigma, std::sqrt(2.0) * 0.05 / std::log(10.0), 1e-12);
  EXPECT_EQ(core_share_trend(t, flat, sem5, 1e3, 1e4).reading, "flat");
  EXPECT_EQ(core_share_trend(t, rising, sem5, 1e3, 1e4).reading, "rises");
  EXPECT_EQ(core_share_trend(t, falling, sem50, 1e3, 1e4).reading, "flat");
  std::vector<double> none(t.size(), std::nan(""));
  EXPECT_EQ(core_share_trend(t, none, sem5, 1e3, 1e4).reading, "not measured");
  std::vector<double> zero(t.size(), 0.0);
  EXPECT_EQ(core_share_trend(t, zero, sem5, 1e3, 1e4).reading, "no core");
}

// A kicked 2D gas's realisation measures the core's share at every sample with a band (a
// fraction) and the pressure at its snapshots; a folder that lacks either column is refused in
// one line naming the file, not averaged as if the column were there.
TEST(CoreEnergy, RealisationsMeasureItAndAFolderWithoutItIsRefused) {
  EnsembleSpec spec;
  spec.physics.dim = 2;
  spec.physics.particles = 4000;
  spec.physics.restitution = 0.5;
  spec.physics.t_max = 300;
  spec.realisations = 1;
  spec = checked(spec);
  Realisation fresh;
  ASSERT_TRUE(simulate_realisation(spec, 0, fresh));
  const auto& share = fresh.timeseries.column("core_energy_share");
  ASSERT_TRUE(std::isfinite(share.back()));
  for (double x : share) {
    if (std::isfinite(x)) {
      EXPECT_TRUE(x >= 0 && x <= 1) << x;
    }
  }
  ASSERT_EQ(fresh.snapshots.back().pressure.size(), std::size_t(spec.bins));
  double total = 0;
  for (double p : fresh.snapshots.back().pressure) total += p;
  EXPECT_GT(total, 0);

  for (const char* drop : {"core_energy_share", "pressure"}) {
    std::vector<RealisationFile> files = realisation_files(fresh);
    (void)parse_realisation(files, 0, "whole");  // read back as written
    const std::string in = std::string(drop) == "pressure" ? "distributions.csv" : "timeseries.csv";
    for (auto& f : files) {
      if (f.name != in) continue;
      Table t = parse_csv(f.text, f.name);
      const auto k =
          std::size_t(std::find(t.names.begin(), t.names.end(), drop) - t.names.begin());
      ASSERT_LT(k, t.names.size()) << drop;
      t.names.erase(t.names.begin() + std::ptrdiff_t(k));
      t.columns.erase(t.columns.begin() + std::ptrdiff_t(k));
      f.text = to_csv(t);
    }
    try {
      (void)parse_realisation(files, 0, "cut");
      ADD_FAILURE() << "a folder without '" << drop << "' was read";
    } catch (const UserError& e) {
      EXPECT_EQ(std::string(e.what()), "cut/" + in + ": no column '" + drop + "'");
    }
  }
}

}  // namespace
}  // namespace gs
