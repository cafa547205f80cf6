#pragma once
// Effective exponents: the local slope d ln X / d ln t of an ensemble-mean time series with a
// bootstrap band over realisations, and the plateau of that slope on which a power law may be
// fitted. A fit over a fixed window of a series with corrections to scaling, X = t^a (1 + c t^-b),
// returns an average of the drifting slope rather than a; the local slope shows the drift, and
// the plateau rule says whether the run reached the asymptotic regime at all.
//
// Plateau rule (drift within its own error): a window [t_a, t_b] of usable samples spanning at
// least min_decades is cut into three equal thirds in ln t. With s-bar_1, s-bar_2, s-bar_3 the
// means of the local slope over the thirds,
//   drift     D = s-bar_3 - s-bar_1                    (the slope's change across the window),
//   curvature K = s-bar_2 - (s-bar_1 + s-bar_3) / 2    (a dip or bump a straight drift misses),
// and sigma_D, sigma_K their standard deviations over the bootstrap resamples of the
// realisations (the same resamples as the band, so the correlation of neighbouring slopes and of
// the thirds is in them). The window is a plateau when |D| <= z sigma_D + floor and
// |K| <= z sigma_K + floor (z = 2, ~95%; floor = 1e-3 only absorbs the rounding of exact
// series; it is not a tolerance), and, in a window of 4 piece_decades or more, when each of its
// m = floor(span / piece_decades) equal pieces has a mean slope within z_m sigma + floor of the
// window's (z_m: z shared by m tests, Bonferroni), so that a swing of the slope that the thirds
// average away is seen too. A slope that drifts, however slowly, is therefore rejected as
// soon as the data resolve the drift: more realisations make the rule stricter, not looser.
// With one realisation there is no error and only a drift below the floor passes.
// The plateau is the window ending latest (the asymptotic regime is the late one), extended as
// far back as the rule allows; its exponent is the mean local slope over it, and its drift D with
// sigma_D is reported with every fit. None: "no plateau within the run", and no fit is made.
#include <cstdint>
#include <limits>
#include <span>
#include <string>
#include <vector>

#include "analysis/power_law.h"

namespace gs {

struct SlopeBandOptions {
  double half_width_decades = 0.1;  // smoothing of the local slope (power_law.h local_slope)
  int resamples = 200;
  double confidence = 0.95;
  std::uint64_t seed = 1;  // master seed of the ensemble
  std::uint64_t key = 0;   // distinguishes the quantities of one ensemble
};

// Local slope of the mean of `realisations` on the grid t and its percentile band from
// resampling realisations with replacement; with one realisation lo = hi = slope. NaN where the
// slope is undefined (a non-positive value nearby).
struct SlopeBand {
  std::vector<double> t, slope, lo, hi;
  // The resampled local slopes (one per resample, each on the grid t); empty for one realisation.
  std::vector<std::vector<double>> draws;
};
SlopeBand local_slope_band(std::span<const double> t,
                           std::span<const std::vector<double>> realisations,
                           const SlopeBandOptions& options = {});

struct PlateauOptions {
  double z = 2;          // drift and curvature allowed: z standard deviations over resamples
  double floor = 1e-3;   // added to z sigma: the rounding of an exact series, not a tolerance
  double min_decades = 0.5;
  // The pieces' test cuts a window into pieces of at least this many decades (from 4 of them).
  double piece_decades = 0.5;
  // An absolute bound on |D|, |K| and the distance from the last decade's slope, whatever their
  // errors: a drift of 0.55 +- 0.28 passes "within 2 sigma" but is no plateau. Infinity: none.
  double max_drift = std::numeric_limits<double>::infinity();
  // > 0: the window's mean slope must also lie within z sigma + floor (and max_drift) of the
  // mean slope over the last this-many decades of usable samples, so that a flat stretch at a
  // dip's bottom, a hump's top or on the way up a rising slope is not taken for the asymptote.
  double reference_decades = 0;
  double t_min = 0;  // only samples in [t_min, t_max]
  double t_max = std::numeric_limits<double>::infinity();
  // The latest plateau must end within this many decades of the last usable sample; one that
  // ends earlier is a transient the slope leaves (every later window failed the rule), not the
  // asymptotic regime, and is reported as no plateau (3D N_t's [32, 562] of --quick, the elastic
  // build-up, while the slope drifts on for 1.7 decades). Infinity: any window.
  double max_end_gap_decades = std::numeric_limits<double>::infinity();
};

// The plateau of an asymptotic exponent: at least a decade long, drift and curvature within
// 0.005 as well as within their errors, consistent with the last decade's slope, and ending at
// most 0.3 decade (three smoothing half widths of the local slope, so at least one independent
// slope value) before the last usable sample. 0.005 is a quarter of the 0.02 by which the 2D
// E_t and R_t readings sit off 1/3 and of the gap between 1/4 and 2/7 in 3D (0.036): a slope
// that moves by more across its window cannot tell those apart.
inline PlateauOptions asymptotic_plateau() {
  PlateauOptions p;
  p.min_decades = 1;
  p.max_drift = 0.005;
  p.reference_decades = 1;
  p.max_end_gap_decades = 0.3;
  return p;
}

struct Plateau {
  bool found = false;
  Window window;
  double exponent = std::numeric_limits<double>::quiet_NaN();  // mean local slope over window
  double drift = std::numeric_limits<double>::quiet_NaN();     // D, see the rule above
  double drift_error = std::numeric_limits<double>::quiet_NaN();  // sigma_D
  double curvature = std::numeric_limits<double>::quiet_NaN();    // K
  double curvature_error = std::numeric_limits<double>::quiet_NaN();
  // The systematic of the window's choice: the standard deviation of the mean local slope over
  // every window that passes the rule and ends within max_end_gap_decades (0.3 decade when that
  // is unbounded) of the last usable sample; 0 when one window passes.
  double window_spread = std::numeric_limits<double>::quiet_NaN();
  std::size_t passing_windows = 0;
  std::string note;  // where the slope goes when there is no plateau
};
Plateau find_plateau(const SlopeBand& band, const PlateauOptions& options = {});

// Where the local slope stands at a run's end and which way it moves, what a run without a
// plateau still says: its mean over the last `decades` of usable samples, and the plateau rule's
// drift D over that window (the last third's mean minus the first's) over the decades between
// the thirds' centres, a change per decade (exact for a slope linear in ln t), with their
// resampling errors (0 for one realisation). Not found when the usable samples at the end span less
// than `decades`.
struct EndSlope {
  bool found = false;
  Window window;
  double slope = std::numeric_limits<double>::quiet_NaN();
  double slope_error = std::numeric_limits<double>::quiet_NaN();
  double drift_per_decade = std::numeric_limits<double>::quiet_NaN();
  double drift_error = std::numeric_limits<double>::quiet_NaN();
};
EndSlope end_slope(const SlopeBand& band, double decades = 1);

// The exponent with a correction to scaling, X = t^b (1 + c t^-omega) to first order: the local
// slope fitted as s(t) = b + k t^-omega over the usable samples of [t_lo, t_hi], b and k by
// least squares for each omega of the grid 0.1, 0.15, ..., 2, the omega of least squared
// residual kept (an omega at the grid's edge is reported as such). Interval: the same fit of
// every resampled slope (percentiles). Shows whether a plateau exponent short of the theory is
// a finite-time correction (b moves towards the theory) or not (b stays).
struct CorrectedExponent {
  bool found = false;
  double b = std::numeric_limits<double>::quiet_NaN();
  double k = std::numeric_limits<double>::quiet_NaN();
  double omega = std::numeric_limits<double>::quiet_NaN();
  double ci_lo = std::numeric_limits<double>::quiet_NaN();
  double ci_hi = std::numeric_limits<double>::quiet_NaN();
  Window window;
  std::string note;
};
CorrectedExponent corrected_exponent(const SlopeBand& band, double t_lo, double t_hi,
                                     double confidence = 0.95);

}  // namespace gs
