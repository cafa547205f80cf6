// The plan of `grainshock figures` against what its readings need: enough r for phi1, sizes that
// keep each front inside its box, cutoffs whose crossover comes after the run.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "analysis/paper.h"
#include "jobs/figures_plan.h"
#include "sim/config.h"

namespace gs::jobs {
namespace {

std::vector<const FigureCase*> of_role(const FiguresPlan& p, CaseRole role) {
  std::vector<const FigureCase*> out;
  for (const auto& c : p.cases)
    if (c.role == role) out.push_back(&c);
  return out;
}

TEST(FiguresPlan, Phi1RestsOnSixRestitutionsInBothDimensions) {
  for (FiguresMode m : {FiguresMode::Quick, FiguresMode::Full})
    for (int d : {2, 3}) {
      std::set<double> r;
      for (const FigureCase* c : of_role(figures_plan(m, 1), CaseRole::Paper))
        if (c->spec.physics.dim == d && c->spec.physics.restitution < 1) {
          r.insert(c->spec.physics.restitution);
          EXPECT_GE(c->spec.realisations, 2u) << c->name;  // bootstrap intervals need two
        }
      EXPECT_GE(r.size(), 6u) << to_string(m) << " d = " << d;
      EXPECT_NE(find_case(figures_plan(m, 1), d, 1.0), nullptr);
    }
}

TEST(FiguresPlan, Full3DReachesTheEnergyPlateauAtLargeRWithoutWrapping) {
  // Measured (4e6 spheres, delta = 1e-6, 2 realisations each): E_t's local slope plateaus from
  // t ~ 2e4 at r = 0.7-0.85, and the plateau rule needs 0.5 decade of it; the fastest front
  // (r = 0.9) is at 76 at t = 6.3e4 and grows as t^0.29. Without the smaller cutoff the slope
  // turns back up from ~3e4 (t_c2), so every 3D r < 1 runs with delta <= 1e-6.
  std::set<double> long_runs;
  for (const FigureCase* c : of_role(figures_plan(FiguresMode::Full, 1), CaseRole::Paper)) {
    const auto& p = c->spec.physics;
    if (p.dim != 3 || p.restitution >= 1) continue;
    EXPECT_LE(p.cutoff, 1e-6) << c->name;
    if (p.restitution < 0.7 || p.restitution > 0.85) continue;
    long_runs.insert(p.restitution);
    EXPECT_GE(p.t_max, 2e4 * std::pow(10.0, 0.5)) << c->name;
    const double half_box = 0.5 * std::cbrt(double(p.particles) / p.density);
    EXPECT_LE(76 * std::pow(p.t_max / 6.3e4, 0.29), 0.7 * half_box) << c->name;
  }
  EXPECT_EQ(long_runs.size(), 3u);  // 0.7, 0.8, 0.85: with 0.1, 0.3, 0.5 the six values of phi1
}

TEST(FiguresPlan, DeltaScanHasFourCutoffsWhoseTc2FallsInsideTheRuns) {
  // t_c2 ~ delta^-3/2 (the paper's phi2 in 2D), anchored at t_c2 = 2.2e4 measured for delta =
  // 5e-4 (--quick, 12 realisations); the measured phi2 (~1.55) moves it by < 10% over these
  // cutoffs. A t_c2 is usable when it comes well after t_c1 ~ 1e3 (3x) and the run goes on for
  // >= 3 t_c2, so that the slope is above the band at the end.
  for (FiguresMode m : {FiguresMode::Quick, FiguresMode::Full}) {
    std::set<double> cutoffs;
    for (const FigureCase* c : of_role(figures_plan(m, 1), CaseRole::DeltaScan)) {
      const auto& p = c->spec.physics;
      EXPECT_EQ(p.dim, 2);
      EXPECT_EQ(p.restitution, 0.1);
      const double tc2 = 2.2e4 * std::pow(p.cutoff / 5e-4, -1.5);
      EXPECT_GE(tc2, 3e3) << c->name;
      EXPECT_GE(p.t_max, 3 * tc2) << c->name;
      EXPECT_TRUE(c->delta_scan);
      cutoffs.insert(p.cutoff);
    }
    EXPECT_GE(cutoffs.size(), 4u) << to_string(m);
  }
}

TEST(FiguresPlan, FullRunsTheLargeElasticBlast) {
  const auto large = of_role(figures_plan(FiguresMode::Full, 1), CaseRole::Elastic3D);
  ASSERT_EQ(large.size(), 1u);
  const auto& p = large.front()->spec.physics;
  EXPECT_EQ(p.dim, 3);
  EXPECT_EQ(p.restitution, 1.0);
  EXPECT_GE(p.particles, 4000000);  // the 3D elastic slopes plateau by 2e4 at N = 4e6
  EXPECT_GE(p.t_max, 2e4);
}

TEST(FiguresPlan, RLessThanOneRunsWithASmallCutoffAndLongRunsAreOptIn) {
  // At delta = 1e-4 the 2D N_t slope drifts into the delta crossover before t_max.
  // t_c2 ~ 2.2e4 (5e-4 / delta)^(3/2) (measured in the delta scan, 2D r = 0.1) must come at
  // least 10 times after every 2D r < 1 paper run; 3D keeps 1e-6 (its E_t slope turns at 1e-4).
  // The delta scan keeps its larger cutoffs.
  for (FiguresMode m : {FiguresMode::Quick, FiguresMode::Full}) {
    const FiguresPlan plan = figures_plan(m, 1);
    for (const FigureCase* c : of_role(plan, CaseRole::Paper)) {
      const auto& p = c->spec.physics;
      if (p.restitution >= 1) continue;
      if (p.dim == 3) {
        EXPECT_LE(p.cutoff, 1e-6) << c->name;
      } else if (p.dim == 2) {
        EXPECT_GE(2.2e4 * std::pow(5e-4 / p.cutoff, 1.5), 10 * p.t_max) << c->name;
      }
    }
    for (const FigureCase* c : of_role(plan, CaseRole::DeltaScan))
      EXPECT_GE(c->spec.physics.cutoff, 1e-4) << c->name;
    EXPECT_TRUE(of_role(plan, CaseRole::Long3D).empty());
    const auto with = of_role(figures_plan(m, 1, true), CaseRole::Long3D);
    ASSERT_EQ(with.size(), 2u);
    for (const FigureCase* c : with) {
      const auto& p = c->spec.physics;
      EXPECT_EQ(p.dim, 3);
      EXPECT_LE(p.cutoff, 1e-6);
      EXPECT_GE(p.t_max, 1e6);
      EXPECT_GE(c->spec.realisations, 16u);
      // The front stays below 0.6 L/2: by t = 1e6 it reached 0.59 L/2 (r = 0.1) and
      // 0.72 L/2 (r = 0.5) of a box of 4e6 spheres (`figures --quick --long`, 81eb19d).
      const double half_l4 = 0.5 * std::cbrt(4e6 / p.density);
      const double front = (p.restitution < 0.3 ? 0.59 : 0.72) * half_l4;
      EXPECT_LE(front, 0.6 * 0.5 * std::cbrt(double(p.particles) / p.density)) << c->name;
    }
  }
}

TEST(FiguresPlan, LimitCasesAreUnboundedPastTheirPlateauAndFitInMemory) {
  // --limit: 2D and 3D r = 0.9 and 0.95, opt-in, in the unbounded medium. Each but 3D
  // r = 0.95 runs at least half a decade past its expected plateau start (the plateau rule's
  // shortest window), 2D r = 0.95's start at least r = 0.9's times ((1 - 0.95^2) /
  // (1 - 0.9^2))^-2.25; 3D r = 0.95 (no plateau: 2.4 days) runs until its E_t has fallen to
  // E_0/20 if phi1 <= 3 (r = 0.9's measured 5.3e4 times 0.513^-3). The realisations run at once
  // on 2 cores fit in 24 GB by the engine's own estimate with their cap on made particles and a
  // snapshot each. t_c2 stays far beyond t_max.
  for (FiguresMode m : {FiguresMode::Quick, FiguresMode::Full}) {
    EXPECT_TRUE(of_role(figures_plan(m, 1), CaseRole::Limit).empty());
    const FiguresPlan plan = figures_plan(m, 1, false, true);
    const auto limit = of_role(plan, CaseRole::Limit);
    ASSERT_EQ(limit.size(), 10u);
    std::map<std::pair<int, double>, const FigureCase*> by;
    auto at = [&](int d, double r) { return by.count({d, r}) ? by.at({d, r}) : nullptr; };
    for (const FigureCase* c : limit) {
      const PhysicsConfig& p = c->spec.physics;
      by[{p.dim, p.restitution}] = c;
      EXPECT_TRUE(p.unbounded()) << c->name;
      if (p.restitution >= 0.97) {
        // Near the elastic limit only the time to E_0/2 is read: each run goes past the
        // measured or scaled one (2D r = 0.99: 1.41e4; 3D r = 0.99: ~1e5, extrapolated),
        // scaled to the other r by (1 - r^2)^-phi1 with the smaller phi1 on offer (the scaling
        // estimate's 2 in 2D, 2.5 in 3D: the later time), with room for the realisations'
        // spread (1.4 times).
        const double r = p.restitution;
        const double ratio = (1 - r * r) / (1 - 0.99 * 0.99);
        const double half = p.dim == 2 ? 1.41e4 * std::pow(ratio, -2.0) : 1e5 * std::pow(ratio, -2.5);
        EXPECT_GE(p.t_max, 1.4 * half) << c->name;
        EXPECT_EQ(c->plateau_start, 0) << c->name;
      } else if (p.dim == 3 && p.restitution == 0.95) {
        EXPECT_EQ(c->plateau_start, 0) << c->name;
        EXPECT_GE(p.t_max, 5.3e4 * std::pow((1 - 0.95 * 0.95) / (1 - 0.9 * 0.9), -3.0));
      } else {
        EXPECT_GT(c->plateau_start, 0) << c->name;
        EXPECT_GE(std::log10(p.t_max / c->plateau_start), 0.5) << c->name;
      }
      EXPECT_LE(c->threads_of(2) * estimated_bytes(p, 1), 24e9) << c->name;
      EXPECT_GE(c->spec.realisations, 8u) << c->name;
      EXPECT_GT(c->estimate_t_max, 0) << c->name;
      EXPECT_LT(c->estimate_t_max, p.t_max) << c->name;
      if (p.dim == 2)
        EXPECT_GE(2.2e4 * std::pow(5e-4 / p.cutoff, 1.5), 10 * p.t_max) << c->name;
      else  // 3D: t_c2 ~ 3e4 (1e-4 / delta)^(4/3) (E_t's slope turning up at r = 0.7)
        EXPECT_GE(3e4 * std::pow(1e-4 / p.cutoff, 4.0 / 3), 10 * p.t_max) << c->name;
    }
    for (int d : {2, 3}) ASSERT_TRUE(at(d, 0.9) && at(d, 0.95)) << d;
    const double ratio = std::pow((1 - 0.95 * 0.95) / (1 - 0.9 * 0.9), -2.25);
    EXPECT_GE(at(2, 0.95)->plateau_start, ratio * at(2, 0.9)->plateau_start * 0.99);
    // 3D r = 0.9 needs t ~ 1e6 for E_t's slope to plateau.
    EXPECT_GE(at(3, 0.9)->spec.physics.t_max, 1e6);
    // --limit-dim keeps one dimension's cases, the same ones.
    for (int d : {2, 3}) {
      const auto only = of_role(figures_plan(m, 1, false, true, d), CaseRole::Limit);
      ASSERT_EQ(only.size(), 5u) << d;
      for (const FigureCase* c : only) {
        EXPECT_EQ(c->spec.physics.dim, d) << c->name;
        EXPECT_EQ(c->spec.physics.t_max, at(d, c->spec.physics.restitution)->spec.physics.t_max);
      }
    }
  }
}

TEST(FiguresPlan, SnowplowCasesAreOptInUnboundedAndLongEnoughForADecadeOfPlateau) {
  // 3D r = 0.1 and 0.5 to 1.2e6 and 2D r = 0.1 and 0.5 to 2e6 in the unbounded medium, 20
  // realisations each; each at least a decade past the plateau start it expects (the plateau
  // rule's shortest window), fitting in 24 GB two at a time, with t_c2 far beyond t_max.
  for (FiguresMode m : {FiguresMode::Quick, FiguresMode::Full}) {
    EXPECT_TRUE(of_role(figures_plan(m, 1), CaseRole::Snowplow).empty());
    const FiguresPlan plan = figures_plan(m, 1, false, false, 0, true);
    const auto cases = of_role(plan, CaseRole::Snowplow);
    ASSERT_EQ(cases.size(), 4u);
    std::set<std::pair<int, double>> seen;
    for (const FigureCase* c : cases) {
      const PhysicsConfig& p = c->spec.physics;
      seen.insert({p.dim, p.restitution});
      EXPECT_TRUE(p.unbounded()) << c->name;
      EXPECT_EQ(c->spec.realisations, 20u) << c->name;
      EXPECT_EQ(p.t_max, p.dim == 3 ? 1.2e6 : 2e6) << c->name;
      EXPECT_GE(std::log10(p.t_max / c->plateau_start), 1 - 1e-9) << c->name;
      EXPECT_LE(c->threads_of(2) * estimated_bytes(p, 1), 24e9) << c->name;
      EXPECT_GT(c->estimate_t_max, 0) << c->name;
      EXPECT_LT(c->estimate_t_max, p.t_max) << c->name;
      EXPECT_NE(c->name.find("_snowplow"), std::string::npos) << c->name;
      if (p.dim == 2)
        EXPECT_GE(2.2e4 * std::pow(5e-4 / p.cutoff, 1.5), 10 * p.t_max) << c->name;
      else
        EXPECT_GE(3e4 * std::pow(1e-4 / p.cutoff, 4.0 / 3), 10 * p.t_max) << c->name;
    }
    EXPECT_EQ(seen, (std::set<std::pair<int, double>>{{2, 0.1}, {2, 0.5}, {3, 0.1}, {3, 0.5}}));
  }
}

TEST(FiguresPlan, TheCollapseIsDrawnAtThePapersTimesWhereTheRunReachesThem) {
  // The paper's Fig. 4 (2D, r = 0.1) at t = 25000, 37500, 50000 and Fig. 5 (3D) at 30000, 50000,
  // 75000, in its unit 1/(v_0 n^(1/d)). --full's runs reach them (2D t_max = 2e5 is t_paper =
  // 1e5); before, its snapshots were the paper's ratios ending at t_max, twice the paper's times
  // in 2D. A run longer than the paper's times keeps a snapshot at t_max for the readings made
  // at the last snapshot (packing, inner edge).
  const FiguresPlan full = figures_plan(FiguresMode::Full, 1);
  const std::vector<double> paper[2] = {{25000, 37500, 50000}, {30000, 50000, 75000}};
  for (int d : {2, 3}) {
    const FigureCase* c = find_case(full, d, 0.1);
    ASSERT_NE(c, nullptr);
    ASSERT_TRUE(c->collapse);
    EXPECT_TRUE(c->paper_times) << c->name;
    const auto& p = c->spec.physics;
    ASSERT_EQ(c->figure_times.size(), 3u) << c->name;
    for (std::size_t k = 0; k < 3; ++k) {
      EXPECT_NEAR(p.paper_time(c->figure_times[k]), paper[d - 2][k], 1e-9 * paper[d - 2][k])
          << c->name;
      EXPECT_TRUE(std::count(c->spec.snapshot_times.begin(), c->spec.snapshot_times.end(),
                             c->figure_times[k]))
          << c->name << " has no snapshot at " << c->figure_times[k];
    }
    EXPECT_EQ(c->spec.snapshot_times.back(), p.t_max) << c->name;
  }
  // --quick's 3D run (t_max 3e4, t_paper 1.9e4) does not reach 75000: the paper's times in
  // ratio, ending at t_max, and said to be.
  const FiguresPlan quick = figures_plan(FiguresMode::Quick, 1);
  const FigureCase* q = find_case(quick, 3, 0.1);
  ASSERT_NE(q, nullptr);
  EXPECT_FALSE(q->paper_times);
  ASSERT_EQ(q->figure_times.size(), 3u);
  EXPECT_EQ(q->figure_times.back(), q->spec.physics.t_max);
  EXPECT_NEAR(q->figure_times.front() / q->figure_times.back(), 30000.0 / 75000, 1e-12);
}

TEST(FiguresPlan, PackingCasesRunAtThePapersDeltaWithSnapshotsOverADecade) {
  for (FiguresMode m : {FiguresMode::Tiny, FiguresMode::Quick, FiguresMode::Full}) {
    const FiguresPlan plan = figures_plan(m, 1);  // of_role points into it
    const auto cases = of_role(plan, CaseRole::Packing);
    ASSERT_EQ(cases.size(), 3u);
    for (const FigureCase* c : cases) {
      const auto& p = c->spec.physics;
      EXPECT_EQ(p.dim, 2);
      EXPECT_LT(p.restitution, 1);
      EXPECT_EQ(p.cutoff, kPaperCutoff) << c->name;
      ASSERT_EQ(c->spec.snapshot_times.size(), 4u);
      EXPECT_DOUBLE_EQ(c->spec.snapshot_times.back() / c->spec.snapshot_times.front(), 8);
      EXPECT_EQ(c->spec.snapshot_times.back(), p.t_max);
      if (m == FiguresMode::Full) {
        EXPECT_EQ(p.particles, kFig1Particles);         // the paper's box
        EXPECT_DOUBLE_EQ(p.paper_time(p.t_max), 5e4);  // the paper's Fig. 4 last time
      }
    }
  }
}

TEST(FiguresPlan, Fig1IsAtThePapersTimesInThePapersBox) {
  // The paper's Fig. 1: r = 0.1 at t = 5000, 10000, 20000, 50000 and r = 1 at 25000 in its time
  // unit, 2.5e5 discs at n = 0.25 (the kick at (500, 500) of a box of side 1000).
  for (FiguresMode m : {FiguresMode::Quick, FiguresMode::Full}) {
    const FiguresPlan::Fig1& f = figures_plan(m, 1).fig1;
    EXPECT_TRUE(f.paper_times);
    const std::vector<double> paper = {5000, 10000, 20000, 50000};
    ASSERT_EQ(f.a_times.size(), paper.size());
    for (std::size_t k = 0; k < paper.size(); ++k)
      EXPECT_NEAR(f.a.paper_time(f.a_times[k]), paper[k], 1e-9 * paper[k]) << to_string(m);
    EXPECT_NEAR(f.b.paper_time(f.b.t_max), 25000, 1e-9 * 25000) << to_string(m);
    for (const PhysicsConfig* p : {&f.a, &f.b}) {
      EXPECT_EQ(p->dim, 2);
      EXPECT_EQ(p->particles, 250000);
      EXPECT_NEAR(p->box(), 1000, 1e-9);
    }
    EXPECT_EQ(f.a.restitution, 0.1);
    EXPECT_EQ(f.b.restitution, 1.0);
    EXPECT_EQ(f.a.t_max, f.a_times.back());
  }
  // --tiny: the paper's times in ratio, scaled into its small box, and said to be.
  const FiguresPlan tiny = figures_plan(FiguresMode::Tiny, 1);
  EXPECT_FALSE(tiny.fig1.paper_times);
  EXPECT_EQ(tiny.fig1.a_times.back(), find_case(tiny, 2, 0.1)->spec.physics.t_max);
  EXPECT_DOUBLE_EQ(tiny.fig1.a_times.front() * 10, tiny.fig1.a_times.back());
  EXPECT_EQ(tiny.fig1.a.particles, find_case(tiny, 2, 0.1)->spec.physics.particles);
}

}  // namespace
}  // namespace gs::jobs
