// The report's verdicts as statistics (analysis/paper.h) and the plateau rule's absolute bounds
// (analysis/effective_exponent.h): each verdict is fed a right and a wrong input and must tell
// them apart; each rejected slope shape is one the old rule let through.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "analysis/effective_exponent.h"
#include "analysis/energy_scaling.h"
#include "analysis/ensemble_fits.h"
#include "analysis/paper.h"
#include "analysis/shock.h"
#include "analysis/snowplow.h"
#include "sim/rng.h"
#include "tests/analysis/log_grid.h"

namespace gs {
namespace {

using test::log_grid;

// M realisations of exp(integral of the slope s(ln t) d ln t) with relative noise per sample.
template <class S>
std::vector<std::vector<double>> series_with_slope(std::span<const double> t, S slope, int M,
                                                   std::uint64_t seed, double noise) {
  std::vector<double> ln_x(t.size(), 0.0);
  for (std::size_t i = 1; i < t.size(); ++i) {  // trapezoids in ln t
    const double u0 = std::log(t[i - 1]), u1 = std::log(t[i]);
    ln_x[i] = ln_x[i - 1] + 0.5 * (slope(u0) + slope(u1)) * (u1 - u0);
  }
  Rng rng(seed, 0, Stream::Positions);
  std::vector<std::vector<double>> c(std::size_t(M), std::vector<double>(t.size()));
  for (auto& curve : c)
    for (std::size_t i = 0; i < t.size(); ++i)
      curve[i] = std::exp(ln_x[i]) * (1 + noise * rng.normal());
  return c;
}

// The rule as it stood before its absolute bounds: half-decade windows, errors only.
PlateauOptions errors_only_rule() {
  PlateauOptions o = asymptotic_plateau();
  o.min_decades = 0.5;
  o.max_drift = std::numeric_limits<double>::infinity();
  o.reference_decades = 0;
  return o;
}

double gauss_in_decades(double u, double centre_decade, double width_decades) {
  const double z = (u / std::numbers::ln10 - centre_decade) / width_decades;
  return std::exp(-0.5 * z * z);
}

// The shapes of plateaus that were not: a run ending at a dip's bottom or a hump's top (3D
// r = 0.1 R_front, r = 0.8 N_t), whose last half decade is flat though the decade before it
// falls or climbs by 0.02, and a slope still rising (2D r = 1 R_front: 0.36 to 0.496 over two
// decades) under noise that leaves sigma_D ~ 0.015 over half a decade. The errors-only rule with
// half-decade windows passes each; the rule of a decade, bounded drift and curvature and the
// last decade's slope must not.
struct Shape {
  const char* name;
  double (*slope)(double u);
  int realisations;
  double noise;
};
const Shape kNotPlateaus[] = {
    {"dip", [](double u) { return 0.25 - 0.04 * gauss_in_decades(u, 3.85, 0.4); }, 16, 0.005},
    {"hump", [](double u) { return 0.25 + 0.04 * gauss_in_decades(u, 3.85, 0.4); }, 16, 0.005},
    {"rising", [](double u) { return 0.36 + 0.07 * (u / std::numbers::ln10 - 2.4); }, 8, 0.02}};

TEST(PlateauRule, RejectsADipAHumpAndARisingSlopeThatErrorsAlonePass) {
  const auto t = log_grid(1, 1e4, 20);
  for (const Shape& shape : kNotPlateaus) {
    int old_found = 0;
    for (std::uint64_t seed = 30; seed < 40; ++seed) {
      const auto x = series_with_slope(t, shape.slope, shape.realisations, seed, shape.noise);
      const SlopeBand band = local_slope_band(t, x);
      old_found += find_plateau(band, errors_only_rule()).found;
      const Plateau p = find_plateau(band, asymptotic_plateau());
      EXPECT_FALSE(p.found) << shape.name << " seed " << seed << ": [" << p.window.t_lo << ", "
                            << p.window.t_hi << "] slope " << p.exponent;
    }
    // The old rule's verdicts, counted so that this test shows what the new bounds add: it took
    // the flat end or the rise for a plateau in many of the ten ensembles.
    EXPECT_GE(old_found, 4) << shape.name;  // measured: 7, 5 and 10 of 10
    std::printf("%s: the errors-only rule found a plateau in %d of 10\n", shape.name, old_found);
  }
}

TEST(PlateauRule, RejectsTheSameShapesWithoutNoise) {
  // Exact series: no error to hide in, so only the bounds decide.
  const auto t = log_grid(1, 1e4, 20);
  for (const Shape& shape : kNotPlateaus) {
    const auto x = series_with_slope(t, shape.slope, 1, 1, 0.0);
    EXPECT_FALSE(find_plateau(local_slope_band(t, x), asymptotic_plateau()).found) << shape.name;
  }
}

TEST(PlateauRule, AcceptsAPurePowerLawWithItsWindowSpread) {
  // 16 realisations with 0.5% noise a sample: sigma_D ~ 0.002, inside the 0.005 bound.
  const auto t = log_grid(1, 1e4, 20);
  const auto x = series_with_slope(t, [](double) { return 0.25; }, 16, 22, 0.005);
  const Plateau p = find_plateau(local_slope_band(t, x), asymptotic_plateau());
  ASSERT_TRUE(p.found) << p.note;
  EXPECT_EQ(p.window.t_hi, t.back());
  EXPECT_GE(std::log10(p.window.t_hi / p.window.t_lo), 1);
  EXPECT_NEAR(p.exponent, 0.25, 0.005);
  EXPECT_GT(p.passing_windows, 1u);
  // The windows' readings scatter by the noise's few 1e-4, not by more than the bound.
  EXPECT_GT(p.window_spread, 0);
  EXPECT_LT(p.window_spread, 0.005);
  // A window shorter than a decade is not enough: a run of 0.9 decade has no plateau.
  const auto short_t = log_grid(1e3, 1e3 * std::pow(10.0, 0.9), 20);
  const auto y = series_with_slope(short_t, [](double) { return 0.25; }, 16, 23, 0.005);
  EXPECT_FALSE(find_plateau(local_slope_band(short_t, y), asymptotic_plateau()).found);
}

// Verdicts.

Comparison exponent_row(double measured, double sigma, double sigma_sys, double theory) {
  Comparison c;
  c.quantity = "exponent of E_t";
  c.measured = measured;
  c.sigma_stat = sigma;
  c.sigma_sys = sigma_sys;
  c.theory = theory;
  return c;
}

TEST(Verdicts, AgreeMeansWithinTwoCombinedSigmaAndNoTolerance) {
  // 2D E_t, measured -0.634 +- 0.002 against -2/3: 16 sigma off. A tolerance of 0.02 on alpha
  // (0.08 on this exponent) passed it; the statistics must not.
  const Comparison off = exponent_row(-0.634, 0.002, 0.001, -2.0 / 3);
  EXPECT_NEAR(off.z(), (-0.634 + 2.0 / 3) / 0.002, 1e-9);
  EXPECT_FALSE(off.agrees());
  // The same error about the theory agrees; 2 sigma is the edge.
  EXPECT_TRUE(exponent_row(-2.0 / 3 + 0.003, 0.002, 0.001, -2.0 / 3).agrees());
  const double edge = 2 * std::sqrt(0.002 * 0.002 + 0.001 * 0.001);
  EXPECT_TRUE(exponent_row(-2.0 / 3 + 0.999 * edge, 0.002, 0.001, -2.0 / 3).agrees());
  EXPECT_FALSE(exponent_row(-2.0 / 3 + 1.001 * edge, 0.002, 0.001, -2.0 / 3).agrees());
  // The window's systematic counts: a reading 3 sigma_stat off agrees when the windows scatter
  // by as much, and not without it.
  EXPECT_FALSE(exponent_row(0.256, 0.002, std::nan(""), 0.25).agrees());
  EXPECT_TRUE(exponent_row(0.256, 0.002, 0.003, 0.25).agrees());
  // Not measured is neither.
  EXPECT_FALSE(exponent_row(std::nan(""), 0.002, 0.001, 0.25).agrees());
  // A lopsided interval (the best-collapsing alpha): the theory inside it or not.
  Comparison inside = exponent_row(0.3425, 0.005, std::nan(""), 1.0 / 3);
  inside.relation = Relation::Inside;
  inside.ci_lo = 0.33;
  inside.ci_hi = 0.3525;
  EXPECT_TRUE(inside.agrees());
  inside.theory = 0.25;  // 3D's alpha against a 2D collapse
  EXPECT_FALSE(inside.agrees());
}

// An ensemble's fits made by hand: every exponent at the theory's value with sigma 0.002.
EnsembleFits fits_at_theory(const PhysicsConfig& p) {
  EnsembleFits f;
  f.alpha_theory = theory_alpha(p);
  const Quantity all[] = {Quantity::ActiveCount, Quantity::Energy,         Quantity::RadiusRms,
                          Quantity::FrontRadius, Quantity::RadialMomentum, Quantity::RadialSpeed,
                          Quantity::Collisions,  Quantity::KickedDisplacement,
                          Quantity::KickedSpeed, Quantity::KickedCollisions};
  for (Quantity q : all) {
    ExponentFit e;
    e.kind = q;
    e.quantity = quantity_name(q);
    e.theory = q == Quantity::Collisions
                   ? (p.elastic() ? 2.0 * (p.dim + 1) / (p.dim + 2) : std::nan(""))
                   : exponent_from_alpha(q, p.dim, f.alpha_theory);
    if (q == Quantity::Energy && p.elastic()) e.theory = 0;
    if (is_kicked(q)) e.theory = p.elastic() ? impurity_exponent(q, p.dim) : std::nan("");
    e.fit.exponent = std::isfinite(e.theory) ? e.theory : 1.5;
    e.fit.confidence = 0.95;
    e.fit.ci_lo = e.fit.exponent - 0.002 * 1.959964;
    e.fit.ci_hi = e.fit.exponent + 0.002 * 1.959964;
    e.window_systematic = 0.001;
    e.corrected.found = true;
    e.corrected.note = "omega at the edge of its grid [0.1, 2]";
    f.exponents.push_back(e);
  }
  f.speed_identity_error = 1e-14;
  f.anisotropy = 4.0 / 1000;
  f.anisotropy_sem = 0.3 / 1000;
  f.anisotropy_floor = 3.9 / 1000;
  f.anisotropy_floor_sem = 0.1 / 1000;
  f.active_last = 1000;
  f.anisotropy_slope = 0.01;
  f.anisotropy_slope_error = 0.02;
  f.last_scalars.assign(kSnapshotScalars.size(), 0.0);
  f.last_scalars_sem.assign(kSnapshotScalars.size(), 0.002);
  auto set = [&](const char* name, double v) {
    for (std::size_t k = 0; k < kSnapshotScalars.size(); ++k)
      if (std::string(kSnapshotScalars[k]) == name) f.last_scalars[k] = v;
  };
  set("packing_typical", p.elastic() ? 0.47 * std::numbers::pi / 4 : 0.80);
  set("packing_voronoi_median", 0.80);
  set("shell_peak_density", strong_shock_compression(p.dim, p.density) * p.density);
  return f;
}

EnsembleSpec spec_of(int d, double r) {
  EnsembleSpec s;
  s.physics.dim = d;
  s.physics.restitution = r;
  return s;
}

const Comparison& row(const std::vector<Comparison>& cmp, const std::string& quantity) {
  for (const auto& c : cmp)
    if (c.quantity == quantity) return c;
  ADD_FAILURE() << "no row " << quantity;
  static const Comparison none;
  return none;
}

TEST(Verdicts, EveryCountedRowOfACaseFailsOnAWrongInput) {
  for (const double r : {0.5, 1.0}) {
    const EnsembleSpec spec = spec_of(2, r);
    const CaseContext context{"d2", "fig8.png", false, false};
    const EnsembleFits right = fits_at_theory(spec.physics);
    const auto cmp = case_comparisons(context, spec, right);
    std::size_t counted = 0;
    for (const auto& c : cmp) {
      if (!c.counted()) continue;
      ++counted;
      EXPECT_TRUE(c.agrees()) << c.quantity << " r = " << r << " z = " << c.z();
    }
    EXPECT_GE(counted, 5u);
    // A wrong exponent (the theory's + 0.02, 10 sigma) and a shifted mean (packing + 0.05) fail.
    EnsembleFits wrong = right;
    for (auto& e : wrong.exponents) e.fit.exponent += 0.02;
    for (auto& v : wrong.last_scalars) v += 0.05;
    wrong.anisotropy_slope += 0.1;                     // A still changing (r < 1)
    wrong.anisotropy = right.anisotropy_floor * 2.5;  // A of a cloud that is not round (r = 1)
    for (const auto& c : case_comparisons(context, spec, wrong)) {
      if (!c.counted()) continue;
      EXPECT_FALSE(c.agrees()) << c.quantity << " r = " << r << " z = " << c.z();
    }
  }
}

TEST(Verdicts, BandPackingIsCountedOnTheVoronoiMedianAtThePapersDelta) {
  EnsembleSpec spec = spec_of(2, 0.1);
  spec.physics.cutoff = 1e-4;
  EnsembleFits f = fits_at_theory(spec.physics);
  // A band at the paper's packing whose cells of 10 are diluted at its edges (a hexagonal band
  // 15 diameters thick: 0.907 by Voronoi, 0.703 by cells of 10, analysis tests).
  auto set = [&](const char* name, double v) {
    for (std::size_t k = 0; k < kSnapshotScalars.size(); ++k)
      if (std::string(kSnapshotScalars[k]) == name) f.last_scalars[k] = v;
  };
  set("packing_voronoi_median", 0.80);
  set("packing_typical", 0.62);
  auto cmp = case_comparisons({"d2_r0.1_packing", "", false, false, true}, spec, f);
  std::size_t counted = 0;
  for (const auto& c : cmp) {
    EXPECT_NE(c.quantity.find("band "), std::string::npos) << c.quantity;  // packing rows only
    counted += c.counted();
  }
  EXPECT_EQ(counted, 1u);
  const Comparison& declared = row(cmp, "band packing (Voronoi, median)");
  EXPECT_EQ(declared.role, Role::Counted);
  EXPECT_TRUE(declared.agrees());
  const Comparison& cells = row(cmp, "band packing (typical, cells of 10)");
  EXPECT_EQ(cells.role, Role::Sensitivity);
  EXPECT_FALSE(cells.agrees());
  EXPECT_NE(cells.note.find("band-edge dilution"), std::string::npos);
  // The same band at delta = 1e-5: nothing counted.
  spec.physics.cutoff = 1e-5;
  cmp = case_comparisons({"d2_r0.1", "", false, false}, spec, f);
  EXPECT_EQ(row(cmp, "band packing (Voronoi, median)").role, Role::Sensitivity);
  EXPECT_NE(row(cmp, "band packing (Voronoi, median)").note.find("not the paper's 1e-4"),
            std::string::npos);
}

TEST(ImpurityExponents, AreKumarDharKrapivskysIn2DAnd3D) {
  // Their abstract: "In 2D, the predictions for impurity displacement, collision numbers, and
  // speed are t^(2/5), t^(2/5) and t^(-2/5)"; 3D from their formulas: 2/5 x 31/35, 2/5 x 26/35
  // and -3 x 29 / (5 x 35).
  EXPECT_NEAR(impurity_exponent(Quantity::KickedDisplacement, 2), 0.4, 1e-15);
  EXPECT_NEAR(impurity_exponent(Quantity::KickedCollisions, 2), 0.4, 1e-15);
  EXPECT_NEAR(impurity_exponent(Quantity::KickedSpeed, 2), -0.4, 1e-15);
  EXPECT_NEAR(impurity_exponent(Quantity::KickedDisplacement, 3), 62.0 / 175, 1e-15);
  EXPECT_NEAR(impurity_exponent(Quantity::KickedCollisions, 3), 52.0 / 175, 1e-15);
  EXPECT_NEAR(impurity_exponent(Quantity::KickedSpeed, 3), -87.0 / 175, 1e-15);
  EXPECT_TRUE(std::isnan(impurity_exponent(Quantity::RadiusRms, 2)));
  // Their rows are reported with a z, not counted, and fail when off by 10 sigma.
  const EnsembleSpec spec = spec_of(2, 1.0);
  EnsembleFits f = fits_at_theory(spec.physics);
  const Comparison& x = row(case_comparisons({"d2_r1", "", false, false}, spec, f),
                            "exponent of x_kick (the kicked particle)");
  EXPECT_EQ(x.role, Role::Reported);
  EXPECT_NEAR(x.theory, 0.4, 1e-15);
  EXPECT_TRUE(x.agrees());
  for (auto& e : f.exponents) e.fit.exponent += 0.02;
  EXPECT_FALSE(row(case_comparisons({"d2_r1", "", false, false}, spec, f),
                   "exponent of v_kick (the kicked particle)")
                   .agrees());
}

TEST(Verdicts, IdentitiesTheShockJump3DAnisotropyAndPrAreNotCounted) {
  const EnsembleSpec spec = spec_of(3, 1.0);
  EnsembleFits f = fits_at_theory(spec.physics);
  const auto cmp = case_comparisons({"d3", "", false, false}, spec, f);
  const Comparison& identity = row(cmp, "v_rms^2 = 2E/N (identity)");
  EXPECT_EQ(identity.role, Role::Check);
  EXPECT_TRUE(identity.agrees());
  const Comparison& shock = row(cmp, "shell peak density / ambient");
  EXPECT_EQ(shock.role, Role::Check);
  EXPECT_TRUE(shock.agrees());
  EXPECT_EQ(row(cmp, "exponent of P_r").role, Role::Reported);
  EXPECT_EQ(row(cmp, "A(t_max) -> 0: against an isotropic cloud's (angle-shuffled)").role,
            Role::Reported);
  // The shock jump's check is real: 1.718 against 1.950 with an error of 0.0012 is z ~ -190.
  f.last_scalars_sem.assign(kSnapshotScalars.size(), 0.0012 * spec.physics.density);
  for (std::size_t k = 0; k < kSnapshotScalars.size(); ++k)
    if (std::string(kSnapshotScalars[k]) == "shell_peak_density")
      f.last_scalars[k] = 1.718 * spec.physics.density;
  const Comparison& low = row(case_comparisons({"d3", "", false, false}, spec, f),
                              "shell peak density / ambient");
  EXPECT_FALSE(low.agrees());
  EXPECT_LT(low.z(), -150);
  // Identity broken (a speed column of another time): the check fails.
  f.speed_identity_error = 1e-3;
  EXPECT_FALSE(row(case_comparisons({"d3", "", false, false}, spec, f),
                   "v_rms^2 = 2E/N (identity)")
                   .agrees());
}

TEST(Verdicts, EnergyIsComparedRawAndCorrectionRowsNeedAnInteriorOmega) {
  const EnsembleSpec spec = spec_of(2, 0.1);
  EnsembleFits f = fits_at_theory(spec.physics);
  auto cmp = case_comparisons({"d2_r0.1", "", false, false}, spec, f);
  EXPECT_NEAR(row(cmp, "exponent of E_t").theory, -2.0 / 3, 1e-15);
  for (const auto& c : cmp) EXPECT_EQ(c.quantity.find("correction to scaling"), std::string::npos);
  for (auto& e : f.exponents) {
    e.corrected.note.clear();  // omega inside its grid
    e.corrected.b = e.theory;
    e.corrected.ci_lo = e.theory - 0.01;
    e.corrected.ci_hi = e.theory + 0.01;
  }
  cmp = case_comparisons({"d2_r0.1", "", true, false}, spec, f);
  EXPECT_EQ(row(cmp, "exponent of E_t, with a correction to scaling").role, Role::Sensitivity);
  // The collapse rows come with the case that carries them, not with an r.
  EXPECT_EQ(row(cmp, "alpha best collapsing P(R,t)").relation, Relation::Inside);
}

TEST(Verdicts, SummaryCountsOnlyTheCountedRows) {
  const EnsembleSpec spec = spec_of(2, 1.0);
  EnsembleFits f = fits_at_theory(spec.physics);
  f.exponents[0].fit.exponent += 0.05;  // N_t off: one disagreement
  auto cmp = case_comparisons({"d2_r1", "", false, false}, spec, f);
  std::size_t counted = 0;
  for (const auto& c : cmp) counted += c.counted();
  const std::string md = comparison_summary_markdown(cmp);
  EXPECT_NE(md.find("**" + std::to_string(counted) + " numbers compared"), std::string::npos)
      << md;
  EXPECT_NE(md.find(std::to_string(counted - 1) + " agree within 2 sigma, 1 disagree"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("exponent of N_t"), std::string::npos);
}

// Fits whose R_t, N_t, E_t and P_r exponents are those of a given alpha, sigma 0.003 each.
EnsembleFits fits_of_alpha(int d, double alpha) {
  EnsembleFits f;
  for (Quantity q : {Quantity::RadiusRms, Quantity::ActiveCount, Quantity::Energy,
                     Quantity::RadialMomentum}) {
    ExponentFit e;
    e.kind = q;
    e.fit.exponent = exponent_from_alpha(q, d, alpha);
    e.fit.standard_error = 0.003;
    f.exponents.push_back(e);
  }
  return f;
}

TEST(Snowplow, WeighsTheTwoPicturesByTheirZScores) {
  // 3D: 1/4 against 2/7 is 0.036 in R_t, 0.143 in P_r; with sigma 0.003 each reading tells them
  // apart by 12-48 sigma.
  const SnowplowVerdict m = weigh_snowplow(3, fits_of_alpha(3, 0.25));
  EXPECT_EQ(m.favoured, "momentum-conserving");
  EXPECT_EQ(m.used, 4u);
  EXPECT_NEAR(m.chi2_momentum, 0, 1e-18);
  EXPECT_EQ(m.strength, "very strong");
  const SnowplowVerdict p = weigh_snowplow(3, fits_of_alpha(3, 2.0 / 7));
  EXPECT_EQ(p.favoured, "pressure-driven");
  // P_r's z against the momentum-conserving 0 is (1/7) / 0.003.
  EXPECT_NEAR(p.readings[3].z_momentum, (1.0 / 7) / 0.003, 1e-9);
  // Neither: alpha 0.32 is far from both.
  EXPECT_EQ(weigh_snowplow(3, fits_of_alpha(3, 0.32)).favoured, "neither");
  // Midway the odds are even.
  const SnowplowVerdict mid = weigh_snowplow(3, fits_of_alpha(3, (0.25 + 2.0 / 7) / 2));
  EXPECT_EQ(mid.strength, "both excluded");  // 6 sigma from each in R_t alone
  // 2D: the same alpha, so no choice; no plateau: no readings.
  EXPECT_EQ(weigh_snowplow(2, fits_of_alpha(2, 1.0 / 3)).favoured, "both (the same alpha in 2D)");
  EnsembleFits none = fits_of_alpha(3, 0.25);
  for (auto& e : none.exponents) e.fit.exponent = std::nan("");
  EXPECT_EQ(weigh_snowplow(3, none).favoured, "no readings");
}

TEST(EndSlope, ReadsTheLastDecadesSlopeAndItsDriftPerDecade) {
  // A slope linear in ln t, 0.3 + 0.02 per decade, 20 samples a decade to 1.2e6 as the snowplow
  // runs have: over the last decade its mean is the value at the window's middle sample and its
  // drift 0.02 per decade, exactly but for the rounding of the sums.
  SlopeBand band;
  band.t = log_grid(1e3, 1.2e6, 20);
  for (double t : band.t) band.slope.push_back(0.3 + 0.02 * std::log10(t));
  band.lo = band.hi = band.slope;
  const EndSlope e = end_slope(band);
  ASSERT_TRUE(e.found);
  EXPECT_DOUBLE_EQ(e.window.t_hi, band.t.back());
  EXPECT_GE(std::log10(e.window.t_hi / e.window.t_lo), 1 - 1e-9);
  EXPECT_NEAR(e.drift_per_decade, 0.02, 1e-12);
  double mean = 0;
  int n = 0;
  for (std::size_t i = 0; i < band.t.size(); ++i)
    if (band.t[i] >= e.window.t_lo) mean += band.slope[i], ++n;
  EXPECT_NEAR(e.slope, mean / n, 1e-12);
  EXPECT_EQ(e.slope_error, 0);  // one realisation: no resampling
  // A run shorter than the decade asked for has no end slope.
  EXPECT_FALSE(end_slope(band, 4).found);
}

// An ensemble whose P_r slope is epsilon(decade) and whose R_t, N_t and E_t slopes are what a
// snowplow with that epsilon gives, R_t's shifted by `r_shift`: 16 realisations with 0.05% noise
// a sample, which gives P_r's last-decade slope an error of ~1e-4, as the 3D runs' 20 have.
EnsembleFits snowplow_fits(int d, double (*epsilon)(double decade), double r_shift = 0) {
  const std::vector<double> t = log_grid(10, 1.2e6, 20);
  EnsembleFits f;
  std::uint64_t key = 0;
  for (Quantity q :
       {Quantity::RadiusRms, Quantity::ActiveCount, Quantity::Energy, Quantity::RadialMomentum}) {
    const auto slope = [&](double u) {
      const double eps = epsilon(u / std::numbers::ln10);
      const double alpha = alpha_from_exponent(Quantity::RadialMomentum, d, eps);
      return exponent_from_alpha(q, d, alpha) + (q == Quantity::RadiusRms ? r_shift : 0);
    };
    ExponentFit e;
    e.kind = q;
    SlopeBandOptions o;
    o.key = ++key;
    e.slope = local_slope_band(t, series_with_slope(t, slope, 16, 7 + key, 0.0005), o);
    f.exponents.push_back(e);
  }
  return f;
}

TEST(Snowplow, HeadsWhereTheRadialMomentumsSlopeDriftsAndReadsTheShellsMomentum) {
  // As the 3D r = 0.1 runs end (epsilon 0.044 falling by 0.008 a decade): momentum-conserving.
  const auto falling = [](double dec) { return 0.044 - 0.008 * (dec - 5.6); };
  const SnowplowEnd m = snowplow_at_the_end(3, snowplow_fits(3, falling));
  EXPECT_EQ(m.heading, "momentum-conserving");
  // Within 3 of their own resampling sigmas, plus what the one-sided local slopes of the last
  // 0.1 decade take off a noiseless series (0.04403 and -0.00788 measured): 1e-4 and 2e-4.
  EXPECT_LT(std::fabs(m.epsilon.slope - 0.044), 3 * m.epsilon.slope_error + 1e-4);
  EXPECT_LT(std::fabs(m.epsilon.drift_per_decade + 0.008), 3 * m.epsilon.drift_error + 2e-4);
  // The wrong way: the same slope rising heads to the pressure-driven 1/7.
  const auto rising = [](double dec) { return 0.044 + 0.008 * (dec - 5.6); };
  EXPECT_EQ(snowplow_at_the_end(3, snowplow_fits(3, rising)).heading, "pressure-driven");
  // No drift: the picture within 3 sigma, neither when the slope sits between them.
  EXPECT_EQ(snowplow_at_the_end(3, snowplow_fits(3, [](double) { return 0.0; })).heading,
            "momentum-conserving");
  EXPECT_EQ(snowplow_at_the_end(3, snowplow_fits(3, [](double) { return 1.0 / 7; })).heading,
            "pressure-driven");
  EXPECT_EQ(snowplow_at_the_end(3, snowplow_fits(3, [](double) { return 0.07; })).heading,
            "neither");
  // Above both and falling (3D r = 0.5 at 2e4: 0.148 falling by 0.1 a decade): it reaches 1/7
  // first, and whether it stops there is not seen.
  const auto above = [](double dec) { return 0.2 - 0.05 * (dec - 5.6); };
  EXPECT_EQ(snowplow_at_the_end(3, snowplow_fits(3, above)).heading, "undecided");
  // Moving away from both, below 0 and falling: neither.
  const auto away = [](double dec) { return -0.03 - 0.01 * (dec - 5.6); };
  EXPECT_EQ(snowplow_at_the_end(3, snowplow_fits(3, away)).heading, "neither");
  EXPECT_EQ(snowplow_at_the_end(2, snowplow_fits(2, falling)).heading,
            "both (the same alpha in 2D)");
  // The shell's momentum N_t dR_t/dt of these snowplows grows as P_r does; R_t moved by 0.01
  // moves it by as much, far beyond its error.
  EXPECT_LT(std::fabs(m.shell - m.epsilon.slope), 3 * m.shell_sigma);
  EXPECT_NEAR(m.shell_z_momentum, m.shell / m.shell_sigma, 1e-12);
  const SnowplowEnd moved = snowplow_at_the_end(3, snowplow_fits(3, falling, 0.01));
  EXPECT_NEAR(moved.shell - m.shell, 0.01, 3 * m.shell_sigma);
  EXPECT_GT(moved.shell - m.shell, 5 * m.shell_sigma);
  EXPECT_EQ(moved.heading, "momentum-conserving");  // the heading reads P_r alone
  EnsembleFits none;
  EXPECT_EQ(snowplow_at_the_end(3, none).heading, "no readings");
}

// One r of `figures --limit` near the elastic limit: M realisations of E_t = E_0 g(t (1 - r^2)^phi
// / s), g(x) = 1 / (1 + x^0.7), on the run's own grid (20 a decade from 0.1 to t_max), each with
// a 2% log-normal amplitude and 1% noise a sample; s puts 2D r = 0.99's E_0/2 at the measured
// 1.41e4.
EnergyCurves near_elastic_curves(double r, double phi, double t_max, int M, std::uint64_t seed) {
  EnergyCurves c;
  c.control = 1 - r * r;
  c.label = "r = " + std::to_string(r);
  c.t = log_grid(0.1, t_max, 20);
  const double s = 1.41e4 * std::pow(1 - 0.99 * 0.99, phi);
  Rng rng(seed, std::uint64_t(1000 * r), Stream::Positions);
  for (int k = 0; k < M; ++k) {
    const double amp = std::exp(0.02 * rng.normal());
    std::vector<double> y;
    for (double t : c.t) {
      const double x = t * std::pow(c.control, phi) / s;
      y.push_back(c.e0 * std::min(1.0, amp / (1 + std::pow(x, 0.7))) *
                  std::exp(0.01 * rng.normal()));
    }
    c.realisations.push_back(std::move(y));
  }
  return c;
}

// The E_0/2 points of r = 0.9 and 0.95 (their phi1 `other`) and of 0.97, 0.98, 0.99 (phi1
// `phi`), run to t_max as the plan does.
std::vector<CrossoverPoint> half_energy_points(double phi, double other) {
  const std::pair<double, double> runs[] = {{0.9, 4e5}, {0.95, 1.6e6}, {0.97, 5e3},
                                            {0.98, 1e4}, {0.99, 3e4}};
  Phi1Options o;
  std::vector<CrossoverPoint> points;
  for (const auto& [r, t_max] : runs) {
    const EnergyCurves c = near_elastic_curves(r, r < 0.965 ? other : phi, t_max, 24, 11);
    FractionTime ft = time_to_fraction(c, 0.5, o);
    points.push_back({c.control, c.label, {ft.t, std::isfinite(ft.t), ""}, std::move(ft.draws)});
  }
  return points;
}

TEST(Verdicts, Phi1NearTheElasticLimitFromTheTimeToHalfTheEnergy) {
  // 2D curves of the crossover form with the paper's phi1 = 2.25 at r >= 0.97 (and 3.5 at r =
  // 0.9, 0.95, which the reading must leave out: with them it reads 3.64): the fit over
  // 0.97-0.99 recovers 2.25 and agrees. Tolerance 0.03, two of the reading's own bootstrap
  // sigma (0.016: the 2% amplitude over 24 realisations, ~0.6% in each t_half, over ln(0.0591 /
  // 0.0199) = 1.09 of control).
  const Comparison right = phi1_near_elastic_comparison(2, half_energy_points(2.25, 3.5));
  ASSERT_TRUE(right.measured_ok()) << right.note;
  EXPECT_NEAR(right.measured, 2.25, 0.03) << right.note;
  EXPECT_TRUE(right.agrees()) << right.measured << " +- " << right.sigma_stat;
  EXPECT_FALSE(right.counted());  // the declared phi1 is the collapse
  EXPECT_NE(right.note.find("r = 0.980000 and r = 0.990000"), std::string::npos) << right.note;
  // The scaling estimate's phi1 = 2 in the same runs: read as 2, and it disagrees with the
  // paper's 2.25.
  const Comparison wrong = phi1_near_elastic_comparison(2, half_energy_points(2.0, 3.5));
  EXPECT_NEAR(wrong.measured, 2.0, 0.03) << wrong.note;
  EXPECT_FALSE(wrong.agrees()) << wrong.measured << " +- " << wrong.sigma_stat;
  // Without three r >= 0.97 reaching E_0/2 there is no reading.
  std::vector<CrossoverPoint> two = half_energy_points(2.25, 3.5);
  two.back().crossover.found = false;
  two.back().crossover.time = std::nan("");
  EXPECT_FALSE(phi1_near_elastic_comparison(2, two).measured_ok());
}

}  // namespace
}  // namespace gs
