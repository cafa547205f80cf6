#pragma once
// Effective exponents: the local slope d ln X / d ln t of an ensemble-mean time series with a
// bootstrap band over realisations, and the plateau of that slope on which a power law may be
// fitted. A fit over a fixed window of a series with corrections to scaling, X = t^a (1 + c t^-b),
// returns an average of the drifting slope rather than a; the local slope shows the drift, and
// the plateau rule says whether the run reached the asymptotic regime at all.
//
// Plateau rule: each sample i has an acceptance interval s_i +- h_i, where s_i is the local slope
// of the mean curve and h_i = tolerance + half the width of its 95% bootstrap band. A window
// of samples is a plateau when one exponent lies in every interval of the window (the intervals
// intersect) and it spans at least min_decades of time. The plateau is the latest such window
// (the asymptotic regime is the late one), extended as far back as the rule allows; none: "no
// plateau within the run", and no fit is made.
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
};
SlopeBand local_slope_band(std::span<const double> t,
                           std::span<const std::vector<double>> realisations,
                           const SlopeBandOptions& options = {});

struct PlateauOptions {
  double tolerance = 0.02;  // added to the band's half width: a sample's acceptance interval
  double min_decades = 0.5;
  double t_min = 0;  // only samples in [t_min, t_max]
  double t_max = std::numeric_limits<double>::infinity();
};

struct Plateau {
  bool found = false;
  Window window;
  double exponent = std::numeric_limits<double>::quiet_NaN();  // mid-point of the intersection
  std::string note;  // where the slope goes when there is no plateau
};
Plateau find_plateau(const SlopeBand& band, const PlateauOptions& options = {});

}  // namespace gs
