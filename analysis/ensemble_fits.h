#pragma once
// The numbers an ensemble is for (Jabeen, Rajesh, Ray, EPL 2010):
//  - exponents of N_t ~ t^(alpha d), E_t ~ t^(alpha d + 2 alpha - 2), R_t ~ t^alpha and
//    v_t ~ t^(alpha - 1): a least-squares line of ln <y> against ln t over a scaling window (given,
//    or the longest range within the last 1.5 decades, and after the mean N_t reaches 20, where
//    the local slope of <y> stays within +-0.05; without one, the last decade), with a 95%
//    percentile interval from 1000 bootstrap resamples of the
//    realisations (M >= 2); each gives an estimate of alpha to compare with 1/(d+1) (r < 1) or
//    2/(d+2) (r = 1);
//  - t_c1: the time from which the local slope of <N_t> stays within 10% of alpha d
//    (analysis/crossover.h, slope rule); t_c2: the later time from which it leaves that band
//    for good, if the data reach it;
//  - collapse quality Q (analysis/collapse.h) of t^alpha P(R,t) against R t^-alpha and of
//    t^(alpha-1) P(v,t) against v t^(1-alpha) over the snapshot times;
//  - A(t) at the last sample, band packing (typical and upper) and the inner-edge speed ratio at
//    the last snapshot time.
#include <optional>
#include <string>
#include <vector>

#include "analysis/crossover.h"
#include "analysis/ensemble_sums.h"
#include "analysis/power_law.h"

namespace gs {

struct FitOptions {
  std::optional<Window> window;  // none: automatic per quantity
  int resamples = 1000;
};

// Throws UserError naming --window unless t_lo < t_hi and the window lies in the sampled range.
void check_window(const EnsembleSpec& spec, const Window& w);

struct ExponentFit {
  std::string column;    // timeseries column: active, energy, radius_rms, speed_rms
  std::string quantity;  // N_t, E_t, R_t, v_t
  double theory = 0;     // exponent predicted with the theory's alpha
  PowerLawFit fit;       // NaN exponent when no window was found
  // alpha implied by the exponent and its interval (half width of the bootstrap interval, or
  // the least-squares error for a single realisation).
  double alpha = 0, alpha_uncertainty = 0;
  std::string note;  // why there is no fit
};

struct EnsembleFits {
  double alpha_theory = 0;
  std::vector<ExponentFit> exponents;
  Crossover tc1, tc2;
  double collapse_radius = std::numeric_limits<double>::quiet_NaN();
  double collapse_speed = std::numeric_limits<double>::quiet_NaN();
  std::string collapse_note;
  double anisotropy = 0, anisotropy_sem = 0;            // at the last sample
  double packing_typical = 0, packing_typical_sem = 0;  // at the last snapshot time
  double packing_upper = 0, packing_upper_sem = 0;
  double inner_outer_ratio = 0, inner_outer_ratio_sem = 0;
};

EnsembleFits fit_ensemble(const EnsembleSums& sums, const FitOptions& options);

}  // namespace gs
