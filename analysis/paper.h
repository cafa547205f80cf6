#pragma once
// Every number of the paper (Jabeen, Rajesh, Ray, EPL 2010) that `grainshock figures` measures,
// in one place: what is measured, how it is defined, the paper's or theory's value, the
// tolerance and the rule by which the two agree. The command only runs ensembles and draws.
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "analysis/crossover.h"
#include "analysis/energy_scaling.h"
#include "analysis/ensemble_fits.h"
#include "analysis/json.h"
#include "analysis/realisation.h"

namespace gs {

// Fig. 1 of the paper, in its time unit 1/(v0 n^(1/d)): the active particles of r = 0.1 at four
// times overlaid (a) and of r = 1 at one time (b), in a box of 2.5e5 discs (n = 0.25: side 1000,
// the kick at its centre, (500, 500) in the caption).
inline constexpr double kFig1aPaperTimes[] = {5000, 10000, 20000, 50000};
inline constexpr double kFig1bPaperTime = 25000;
inline constexpr std::int64_t kFig1Particles = 250000;
// The times of the paper's scaling collapses (r = 0.1) in its time unit: Fig. 4 (2D), Fig. 5 (3D).
inline constexpr double kFig4PaperTimes[] = {25000, 37500, 50000};
inline constexpr double kFig5PaperTimes[] = {30000, 50000, 75000};
// The paper's cutoff velocity: "In our simulation, we set delta = 10^-4".
inline constexpr double kPaperCutoff = 1e-4;

// How a measured number is set against the paper's or the theory's.
enum class Relation {
  // |measured - theory| <= 2 sqrt(sigma_stat^2 + sigma_sys^2 + sigma_paper^2).
  Equal,
  // The theory's value lies in the measured 95% interval [ci_lo, ci_hi] (which need not be
  // symmetric: the best-collapsing alpha).
  Inside
};

// Where a comparison goes in the report.
enum class Role {
  Counted,      // a declared reading of a paper number: in the agree/disagree count
  Sensitivity,  // another reading of a counted number (the sensitivity table)
  Check,        // an identity or a relation the paper does not claim (v_rms^2 = 2E/N, the shock
                // jump): shown with its z, not counted
  Reported      // measured beside a theory the paper does not test (3D A(t), P_r): not counted
};

// One entry of the report's tables and of summary.json "comparisons".
struct Comparison {
  std::string case_name;  // the ensemble it was measured on (two 3D elastic cases differ in size)
  std::string quantity;
  // The fitted quantity whose exponent this row compares, if it is one.
  std::optional<Quantity> exponent;
  int d = 0;
  double r = std::numeric_limits<double>::quiet_NaN();
  double measured = std::numeric_limits<double>::quiet_NaN();
  // Standard deviation of the measurement over realisations (a 95% bootstrap interval's half
  // width / 1.96, or a standard error).
  double sigma_stat = std::numeric_limits<double>::quiet_NaN();
  // The systematic of the reading's choices (the plateau windows' spread); NaN: none assessed.
  double sigma_sys = std::numeric_limits<double>::quiet_NaN();
  double theory = std::numeric_limits<double>::quiet_NaN();
  // The paper's number's own uncertainty: its quoted range read as 95% (0.78-0.82: 0.01), or
  // the rounding of its last digit (uniform: half a unit / sqrt 3); 0 for a theory's exact value.
  double sigma_paper = 0;
  Relation relation = Relation::Equal;
  double ci_lo = std::numeric_limits<double>::quiet_NaN();
  double ci_hi = std::numeric_limits<double>::quiet_NaN();
  Role role = Role::Counted;
  std::string source;  // where the theory value comes from
  std::string note;    // window, interval, or why nothing was measured
  std::string figure;  // the figure that shows it (e.g. the local slope beside an exponent)
  bool measured_ok() const { return std::isfinite(measured); }
  bool counted() const { return role == Role::Counted; }
  // sqrt(sigma_stat^2 + sigma_sys^2 + sigma_paper^2), the missing terms counting 0.
  double sigma_total() const;
  // (measured - theory) / sigma_stat; NaN without a statistical error.
  double z() const;
  bool agrees() const;
};

// What the figures job knows of a case beyond its spec.
struct CaseContext {
  std::string name;          // the ensemble's folder name
  std::string slope_figure;  // the local slopes' figure of the case
  // The case of the paper's Figs. 4 and 5 (its smallest r): the collapse readings are made.
  bool collapse = false;
  // A 3D elastic case beside a larger one of the same physics: its exponents are sensitivity.
  bool superseded = false;
  // A case run for the band packing at the paper's delta alone: only its packing rows.
  bool packing_only = false;
};

// The comparisons of one ensemble (exponents, identities, A, band measures, shock jump, Q).
std::vector<Comparison> case_comparisons(const CaseContext& context, const EnsembleSpec& spec,
                                         const EnsembleFits& fits);

// A crossover time of one run with its bootstrap draws, for phi1 (control 1 - r^2) or phi2
// (control delta).
struct CrossoverPoint {
  double control = 0;
  std::string label;  // "r = 0.5", "delta = 1e-3"
  Crossover crossover;
  std::vector<double> draws;
};

// phi of t_c ~ control^-phi by least squares over the points found, with a 95% percentile
// interval from refitting the bootstrap draws (a draw without a crossover at some point is
// left out of the interval); fewer than three points: no fit, and the note says which points
// are missing and why.
struct CrossoverExponentFit {
  CrossoverExponent fit;
  double ci_lo = std::numeric_limits<double>::quiet_NaN();
  double ci_hi = std::numeric_limits<double>::quiet_NaN();
  std::size_t points = 0;
  std::string note;
};
CrossoverExponentFit fit_crossover_points(const std::vector<CrossoverPoint>& points);

// The effective exponent between neighbouring points, -d ln t_c / d ln control, for each pair of
// successive found points in the order given (for phi1: r ascending, towards the elastic limit
// in which phi1 is defined), with a 95% percentile interval over the pairs of bootstrap draws
// (NaN with fewer than 10 pairs). Like a time series' local slope it shows whether one exponent
// describes every point: a fit over r = 0.1 ... 0.85 mixes t_c1 of a few collision times
// (r = 0.1) with those of the elastic limit.
struct LocalCrossoverExponent {
  std::string from, to;  // the two points' labels
  double phi = std::numeric_limits<double>::quiet_NaN();
  double ci_lo = std::numeric_limits<double>::quiet_NaN();
  double ci_hi = std::numeric_limits<double>::quiet_NaN();
};
std::vector<LocalCrossoverExponent> local_crossover_exponents(
    const std::vector<CrossoverPoint>& points);

// theory_b: the fit of the t_c1 read with E_t's exponent fixed at the theory's, reported beside
// the intersection rule's (its systematic).
Comparison phi1_comparison(int d, const CrossoverExponentFit& fit, bool theory_b);
// phi1 from the pair of found points nearest the elastic limit (the last of `local`); not
// measured when there is none.
Comparison phi1_elastic_limit_comparison(int d, const std::vector<LocalCrossoverExponent>& local);
// phi1 from the energy curves (analysis/energy_scaling.h) of the pair nearest the elastic limit
// that gives one: the collapse of E_t / E_0 when `level` is NaN (the declared phi1, counted:
// it reads the divergence where the paper defines it and needs no plateau, which the 3D runs
// do not reach), else the time to E_0 x level (sensitivity). The intersection rule's phi1
// readings go to the sensitivity table beside them.
Comparison phi1_energy_comparison(int d, const std::vector<Phi1Reading>& readings, double level);
Comparison phi2_comparison(int d, double r, const CrossoverExponentFit& fit);
// phi1 nearest the elastic limit from the time <E_t> first falls to E_0/2 (`points`: that
// level's points, analysis/energy_scaling.h time_to_fraction) at r >= kNearElasticR only, the
// short runs of `figures --limit` that reach E_0/2 before any plateau: the least-squares fit
// over those r with its bootstrap interval, the neighbouring pairs' readings in the note, the
// scaling estimate's z beside the paper's. One sensitivity row (the declared phi1 is the
// collapse); not measured with fewer than three such r reaching E_0/2.
inline constexpr double kNearElasticR = 0.97;
Comparison phi1_near_elastic_comparison(int d, const std::vector<CrossoverPoint>& points);

// A phi1 reading nearest the elastic limit (phi with its 95% interval [ci_lo, ci_hi]) weighed
// between the two values on offer: the paper's (2.25, 3.0) and the scaling estimate (d + 2)/2
// (2, 2.5; analysis/energy_scaling.h). Each value's distance from the reading counts standard
// errors on its own side of the interval, sigma = (ci_hi - phi) / 1.96 above and
// (phi - ci_lo) / 1.96 below (percentile intervals may be lopsided); the odds are the
// likelihood ratio exp((z_other^2 - z_near^2) / 2) of the nearer value over the other under a
// normal sampling distribution, in the words of Kass and Raftery (J. Am. Stat. Assoc. 90, 773,
// 1995: below 3 not worth more than a bare mention, 3-20 positive, 20-150 strong, above that
// very strong); "neither" when both values lie more than 3 standard errors away. Sampling
// error only: a pair of r still short of the limit is a systematic error the odds do not see.
struct Phi1Weighing {
  double paper = 0, scaling = 0;
  double z_paper = std::numeric_limits<double>::quiet_NaN();
  double z_scaling = std::numeric_limits<double>::quiet_NaN();
  double odds = std::numeric_limits<double>::quiet_NaN();  // >= 1, for `favoured`
  std::string favoured;  // "paper", "scaling", "neither", or empty without an interval
  std::string strength;
};
Phi1Weighing weigh_phi1(int d, double phi, double ci_lo, double ci_hi);

// The comparisons as a JSON array (summary.json of the figures job).
Json comparisons_json(const std::vector<Comparison>& cmp);
// The tables of the report, one per role: the counted comparisons, the sensitivity readings, and
// the checks and reported numbers (with their z, not counted).
std::string comparisons_markdown(const std::vector<Comparison>& cmp);
std::string sensitivity_markdown(const std::vector<Comparison>& cmp);
std::string checks_markdown(const std::vector<Comparison>& cmp);
// The report's first section: how many counted numbers, how many agree, which do not and why,
// which could not be measured.
std::string comparison_summary_markdown(const std::vector<Comparison>& cmp);
// The report's definitions of every measured quantity and agreement rule.
std::string definitions_markdown();

}  // namespace gs
