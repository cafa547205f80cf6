#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "analysis/energy_scaling.h"
#include "sim/error.h"
#include "sim/rng.h"

namespace gs {
namespace {

// E_t / E_0 = g(t c^phi) with g(x) = 1 / (1 + x^gamma): one crossover shape shifted by
// t_c1 = c^-phi, the form the phi1 readings assume. Each of M realisations carries a 2%
// log-normal amplitude and 1% independent noise per sample, as an ensemble's scatter does.
EnergyCurves family_member(double r, double phi, double gamma, int M, std::uint64_t seed) {
  EnergyCurves c;
  c.control = 1 - r * r;
  c.label = "r = " + std::to_string(r);
  for (int i = 0; i <= 160; ++i) c.t.push_back(0.1 * std::pow(10.0, i / 20.0));  // 0.1 .. 1e7
  Rng rng(seed, std::uint64_t(1000 * r), Stream::Positions);
  for (int k = 0; k < M; ++k) {
    const double amp = std::exp(0.02 * rng.normal());
    std::vector<double> y;
    for (double t : c.t) {
      const double x = t * std::pow(c.control, phi);
      y.push_back(c.e0 * std::min(1.0, amp / (1 + std::pow(x, gamma))) *
                  std::exp(0.01 * rng.normal()));
    }
    c.realisations.push_back(std::move(y));
  }
  return c;
}

// The tolerance: with 20 realisations the mean's amplitude is off by ~0.5%, which moves
// ln t_f by ~0.005 / gamma = 0.007 on each curve; over ln(0.36 / 0.19) = 0.64 between r = 0.8
// and 0.9 that is ~0.015 in phi1, so 0.1 is more than six of those, and an interval that also
// holds phi1 +- 0.3 would not reject a wrong exponent.
constexpr double kTolerance = 0.1;

TEST(EnergyScaling, TimeToLevelIsExactOnAPowerLaw) {
  std::vector<double> t, y;
  for (int i = 0; i <= 40; ++i) {
    t.push_back(std::pow(10.0, i / 10.0));
    y.push_back(1 / t.back());
  }
  EXPECT_NEAR(time_to_level(t, y, 0.0125), 80.0, 1e-9);
  EXPECT_TRUE(std::isnan(time_to_level(t, y, 1e-5)));  // never reached
  EXPECT_TRUE(std::isnan(time_to_level(t, y, 2)));     // starts below
  EXPECT_THROW(time_to_level(t, y, 0), UserError);
}

// One r's time to a fraction of E_0 (fig10's points): on the family's form t_f = c^-phi x_f
// with g(x_f) = f, x_f = (1/f - 1)^(1/gamma). Tolerance: the mean amplitude of 20
// realisations is off by ~0.5% (2% / sqrt 20), which moves t_f by ~0.5% / gamma = 0.7%; 3% is
// four of those, and the 95% interval must hold t_f and not a time 20% off.
TEST(EnergyScaling, TimeToAFractionOfE0WithItsInterval) {
  const double phi = 2.25, gamma = 0.7;
  const auto c = family_member(0.9, phi, gamma, 20, 3);
  Phi1Options o;
  for (double f : {0.5, 0.1, 0.01}) {
    const double exact = std::pow(c.control, -phi) * std::pow(1 / f - 1, 1 / gamma);
    const FractionTime ft = time_to_fraction(c, f, o);
    EXPECT_NEAR(ft.t / exact, 1.0, 0.03) << "f = " << f;
    ASSERT_EQ(ft.draws.size(), std::size_t(o.resamples));
    std::vector<double> d = ft.draws;
    std::sort(d.begin(), d.end());
    const double lo = d[std::size_t(0.025 * d.size())], hi = d[std::size_t(0.975 * d.size())];
    EXPECT_LE(lo, exact * 1.02) << "f = " << f;
    EXPECT_GE(hi, exact / 1.02) << "f = " << f;
    EXPECT_FALSE(lo <= 1.2 * exact && 1.2 * exact <= hi) << "a wrong time passes, f = " << f;
  }
  EXPECT_TRUE(std::isnan(time_to_fraction(c, 1e-9, o).t));  // not within the run
  EnergyCurves one = c;
  one.realisations.resize(1);
  EXPECT_TRUE(time_to_fraction(one, 0.1, o).draws.empty());  // nothing to resample
}

TEST(EnergyScaling, LevelReadingRecoversPhiAtEveryLevelAndRejectsAWrongOne) {
  const double phi = 2.25;
  const auto a = family_member(0.8, phi, 0.7, 20, 1);
  const auto b = family_member(0.9, phi, 0.7, 20, 1);
  Phi1Options o;
  for (double level : {0.5, 0.1, 0.01}) {
    const Phi1Reading p = phi1_from_level(a, b, level, o);
    EXPECT_NEAR(p.phi, phi, kTolerance) << "level " << level;
    ASSERT_TRUE(std::isfinite(p.ci_lo)) << p.note;
    EXPECT_LE(p.ci_lo, phi);
    EXPECT_GE(p.ci_hi, phi);
    EXPECT_FALSE(p.ci_lo <= phi + 0.3 && phi + 0.3 <= p.ci_hi) << "a wrong phi1 passes";
    EXPECT_FALSE(p.ci_lo <= phi - 0.3 && phi - 0.3 <= p.ci_hi) << "a wrong phi1 passes";
  }
  // A family built with another phi1 is read as that one, not as the paper's.
  const auto c = family_member(0.8, 3.0, 0.7, 20, 2);
  const auto e = family_member(0.9, 3.0, 0.7, 20, 2);
  EXPECT_NEAR(phi1_from_level(c, e, 0.1, o).phi, 3.0, kTolerance);
  EXPECT_GT(std::fabs(phi1_from_level(c, e, 0.1, o).phi - phi), 0.5);
}

TEST(EnergyScaling, LevelDependenceShowsCurvesOfDifferentShape) {
  // The two r do not share one crossover shape (gamma differs): the level readings disagree with
  // each other by more than their intervals, which is what the level table is there to show.
  const auto a = family_member(0.8, 2.25, 0.7, 20, 3);
  const auto b = family_member(0.9, 2.25, 1.0, 20, 3);
  Phi1Options o;
  const Phi1Reading half = phi1_from_level(a, b, 0.5, o);
  const Phi1Reading hundredth = phi1_from_level(a, b, 0.01, o);
  ASSERT_TRUE(std::isfinite(half.ci_hi) && std::isfinite(hundredth.ci_lo));
  EXPECT_TRUE(half.ci_hi < hundredth.ci_lo || hundredth.ci_hi < half.ci_lo)
      << half.phi << " vs " << hundredth.phi;
}

TEST(EnergyScaling, CollapseRecoversPhiAndRejectsAWrongOne) {
  const double phi = 2.25;
  const auto a = family_member(0.8, phi, 0.7, 20, 4);
  const auto b = family_member(0.9, phi, 0.7, 20, 4);
  Phi1Options o;
  const auto ma = a.mean(), mb = b.mean();
  EXPECT_LT(collapse_misfit(a, ma, b, mb, phi, 0.01, 0.5),
            collapse_misfit(a, ma, b, mb, phi + 0.3, 0.01, 0.5));
  EXPECT_LT(collapse_misfit(a, ma, b, mb, phi, 0.01, 0.5),
            collapse_misfit(a, ma, b, mb, phi - 0.3, 0.01, 0.5));
  const Phi1Reading p = phi1_from_collapse(a, b, o);
  EXPECT_NEAR(p.phi, phi, kTolerance);
  ASSERT_TRUE(std::isfinite(p.ci_lo)) << p.note;
  EXPECT_LE(p.ci_lo, phi);
  EXPECT_GE(p.ci_hi, phi);
  EXPECT_GT(p.ci_lo, phi - 0.3);
  EXPECT_LT(p.ci_hi, phi + 0.3);
}

TEST(EnergyScaling, ReadingsBetweenNeighboursAndRefusals) {
  std::vector<EnergyCurves> family;
  for (double r : {0.7, 0.8, 0.9}) family.push_back(family_member(r, 2.0, 0.7, 10, 5));
  Phi1Options o;
  o.resamples = 20;
  const auto readings = phi1_readings(family, o);
  ASSERT_EQ(readings.size(), 2 * (1 + o.levels.size()));
  for (const auto& p : readings) EXPECT_NEAR(p.phi, 2.0, kTolerance) << p.from << " " << p.level;
  EXPECT_TRUE(std::isnan(readings.front().level));  // the collapse first
  EXPECT_THROW(phi1_from_level(family[0], family[0], 0.1, o), UserError);
  // A curve that never reaches the level gives no reading and says which.
  auto flat = family[2];
  for (auto& y : flat.realisations) std::fill(y.begin(), y.end(), flat.e0);
  const Phi1Reading none = phi1_from_level(family[1], flat, 0.1, o);
  EXPECT_TRUE(std::isnan(none.phi));
  EXPECT_NE(none.note.find(flat.label), std::string::npos);
  EXPECT_TRUE(std::isnan(phi1_from_collapse(family[1], flat, o).phi));
  EXPECT_DOUBLE_EQ(phi1_scaling_estimate(2), 2.0);
  EXPECT_DOUBLE_EQ(phi1_scaling_estimate(3), 2.5);
}

}  // namespace
}  // namespace gs
