#pragma once
// The numbers an ensemble is for (Jabeen, Rajesh, Ray, EPL 2010):
//  - effective exponents (analysis/effective_exponent.h): the local slope d ln <X> / d ln t with
//    a bootstrap band, for N_t ~ t^(alpha d), E_t ~ t^(alpha d + 2 alpha - 2), R_t (rms) and the
//    front radius ~ t^alpha, the radial momentum P_r ~ N_t R_t / t ~ t^(alpha (d+1) - 1), the
//    mean radial speed P_r / N_t ~ t^(alpha - 1) (the front speed; dR_front/dt of a front
//    quantised in shells of 2 diameters measured the shells' noise) and the collision count
//    (~ t^(2(d+1)/(d+2)) for r = 1, Antal, Krapivsky, Redner 2008); each fitted as a
//    least-squares line of ln <X> against ln t on the plateau of its local slope (found after
//    <N_t> reaches 20), with a 95% percentile interval from 1000 bootstrap resamples of the
//    realisations (M >= 2), or "no plateau within the run" and no fit;
//  - v_t is not fitted: v_rms^2 = 2 E_t / N_t holds exactly (every moving particle is active), so
//    its exponent repeats those of E_t and N_t; the identity is checked instead;
//  - t_c1 (r < 1): where the plateau fit of <E_t> meets E_0, the elastic regime's conserved
//    energy (analysis/crossover.h, intersection rule), also with E_t's exponent fixed at the
//    theory's on the same window (its systematic); beside it the slope rule's t_c1, the time
//    from which the local slope of <N_t> stays at or below the upper edge of a 10% band around
//    alpha d (up to t_c2); t_c2: the time from which that slope stays above the band, if the
//    data reach it; each with bootstrap draws for the intervals of phi1, phi2;
//  - collapse quality Q (analysis/collapse.h) of t^alpha P(R,t) against R t^-alpha and of
//    t^(alpha-1) P(v,t) against v t^(1-alpha) over the snapshot times, and the alpha that
//    collapses each best with its interval (best_collapse_alpha);
//  - A(t) at the last sample with its late local slope, and the band measures at the last
//    snapshot time.
#include <optional>
#include <string>
#include <vector>

#include "analysis/collapse.h"
#include "analysis/crossover.h"
#include "analysis/effective_exponent.h"
#include "analysis/ensemble_sums.h"
#include "analysis/power_law.h"

namespace gs {

struct FitOptions {
  // Given by the user: every fitted quantity must have a plateau of its local slope inside it
  // (UserError naming where the slope plateaus otherwise), and the fit covers all of it.
  std::optional<Window> window;
  int resamples = 1000;      // of the fits
  int band_resamples = 200;  // of the local-slope bands and the crossover draws
  PlateauOptions plateau = asymptotic_plateau();  // t_min is set from <N_t> >= 20
};

// Throws UserError naming --window unless t_lo < t_hi and the window lies in the sampled range.
void check_window(const EnsembleSpec& spec, const Window& w);

// The fitted quantities.
enum class Quantity { ActiveCount, Energy, RadiusRms, FrontRadius, RadialMomentum, RadialSpeed,
                      Collisions, KickedDisplacement, KickedSpeed, KickedCollisions };
// N_t, E_t, R_t, R_front, P_r, P_r/N_t, C_t, and the kicked particle's displacement, speed and
// collision count: x_kick, v_kick, C_kick.
const char* quantity_name(Quantity q);
bool is_kicked(Quantity q);

// The exponents of the kicked particle ("impurity") in the elastic blast by Kumar, Dhar and
// Krapivsky, "Impurity dynamics in a zero-temperature gas", arXiv:2505.02225 (2025), with
// R ~ t^(2/(d+2)): displacement lambda (R/lambda)^((4+3d^2)/(8+3d^2)), collisions
// (R/lambda)^((8+2d^2)/(8+3d^2)), speed t^(-d(8-2d+3d^2)/((2+d)(8+3d^2))); in 2D 2/5, 2/5 and
// -2/5 as their abstract states. NaN for the other quantities.
double impurity_exponent(Quantity q, int d);

struct ExponentFit {
  std::string column;  // a kCurveColumns name, or "radial_speed" (P_r / N_t per realisation)
  Quantity kind = Quantity::ActiveCount;
  std::string quantity;  // quantity_name(kind)
  double theory = std::numeric_limits<double>::quiet_NaN();  // NaN: no prediction
  std::string theory_source;
  SlopeBand slope;
  Plateau plateau;
  PowerLawFit fit;  // NaN exponent when there is no plateau
  // The local slope over its last two decades (after <N_t> >= 20) fitted with a correction to
  // scaling, s = b + k t^-omega (effective_exponent.h).
  CorrectedExponent corrected;
  // alpha implied by the exponent and its interval (half width of the bootstrap interval, or the
  // least-squares error for a single realisation); NaN for the collision count.
  double alpha = std::numeric_limits<double>::quiet_NaN();
  double alpha_uncertainty = std::numeric_limits<double>::quiet_NaN();
  // The exponent's systematic of the window's choice: the spread of the mean local slope over
  // the plateau rule's passing windows (Plateau::window_spread); NaN without a plateau.
  double window_systematic = std::numeric_limits<double>::quiet_NaN();
  std::string note;  // why there is no fit
};

// The exponent of the quantity for a given alpha: N ~ t^(alpha d), E ~ t^(alpha (d + 2) - 2),
// R ~ t^alpha (R_t, R_front), P_r ~ t^(alpha (d + 1) - 1), P_r / N_t ~ t^(alpha - 1); NaN for the
// collision count, and alpha_from_exponent its inverse.
double exponent_from_alpha(Quantity q, int d, double alpha);
double alpha_from_exponent(Quantity q, int d, double x);

struct EnsembleFits {
  double alpha_theory = 0;
  std::vector<ExponentFit> exponents;
  // Largest |v_rms^2 N_t / (2 E_t) - 1| over realisations and samples with N_t >= 20.
  double speed_identity_error = std::numeric_limits<double>::quiet_NaN();
  // tc1: intersection rule; tc1_theory_b: the same with E_t's exponent fixed at the theory's;
  // tc1_slope: slope rule on N_t.
  Crossover tc1, tc1_theory_b, tc1_slope, tc2;
  // The same of resampled ensembles (NaN where a draw does not find one), for intervals.
  std::vector<double> tc1_draws, tc1_theory_b_draws, tc1_slope_draws, tc2_draws;
  double collapse_radius = std::numeric_limits<double>::quiet_NaN();
  double collapse_speed = std::numeric_limits<double>::quiet_NaN();
  std::string collapse_note;
  CollapseAlpha collapse_alpha_radius, collapse_alpha_speed;
  double anisotropy = 0, anisotropy_sem = 0;  // at the last sample
  // d ln A / d ln t over the last half decade: weighted least squares of ln A against ln t with
  // the standard errors of the mean taken independent between samples; its standard error.
  double anisotropy_slope = std::numeric_limits<double>::quiet_NaN();
  double anisotropy_slope_error = std::numeric_limits<double>::quiet_NaN();
  Window anisotropy_window;
  // A of the same particles with their directions redrawn (sim/observables.h), the finite-N
  // floor A -> 0 is judged against, and <N_t>, at the last sample.
  double anisotropy_floor = std::numeric_limits<double>::quiet_NaN();
  double anisotropy_floor_sem = std::numeric_limits<double>::quiet_NaN();
  double active_last = std::numeric_limits<double>::quiet_NaN();
  // Means and standard errors over realisations of the snapshot scalars at the last snapshot
  // time, by kSnapshotScalars name.
  std::vector<double> last_scalars, last_scalars_sem;
  double last_scalar(const char* name) const;
  double last_scalar_sem(const char* name) const;
  double packing_typical = 0, packing_typical_sem = 0;  // at the last snapshot time
  double packing_upper = 0, packing_upper_sem = 0;
  double inner_outer_ratio = 0, inner_outer_ratio_sem = 0;
};

EnsembleFits fit_ensemble(const EnsembleSums& sums, const FitOptions& options);

// The exponent fit of `quantity`, or nullptr.
const ExponentFit* find_exponent(const EnsembleFits& f, Quantity quantity);

}  // namespace gs
