#pragma once
// Crossover times of the paper: t_c1, when N_t enters its scaling regime (diverging as
// (1 - r^2)^-phi1 in the elastic limit, phi1 ~ 2.25 in 2D, 3.0 in 3D), and t_c2, when the band
// has slowed to v_t ~ delta and collisions turn elastic (t_c2 ~ delta^-phi2, phi2 = 1/(1 - alpha)).
//
// Definition used (slope rule): with s(t) the local log-slope of N_t (power_law.h) and the target
// its asymptotic value alpha d,
//   t_c1 = the time from which s stays at or below the upper edge of the band target +-
//          `tolerance` (relative) up to the end of the examined range: the early, elastic-like
//          growth (s above the band) is over. An undershoot below the band that follows (2D at
//          r >= 0.7 and 3D: s dips to ~0.57 against 2/3 and recovers over a decade) does not move
//          it; counted as outside, it made t_c1 the end of the undershoot for some r and the entry
//          for others;
//   t_c2 = the time after which s stays above that band (towards the elastic regime, whose
//          exponents are the larger) up to the end of the examined range.
// A run may reach past t_c2 (the delta scan does), so t_c2 is sought first and t_c1 only before
// it (crossover_pair): searched to the end of such a run, the slope is out of the band there and
// no t_c1 would be found.
// Each is located between the two samples where the rule switches, by linear interpolation of
// s in ln t. If N_t = t_c^a g(t / t_c) for a family of runs (one crossover shape, shifted), the
// slope rule gives a fixed multiple of t_c, so exponents such as phi1 come out right whatever the
// tolerance; it needs no early-time fit, which for small r has no points. The intersection of
// early and late power-law fits is given as an alternative.
#include <cstdint>
#include <limits>
#include <span>
#include <string>
#include <vector>

#include "analysis/power_law.h"

namespace gs {

struct SlopeCrossoverOptions {
  double target = std::numeric_limits<double>::quiet_NaN();  // e.g. alpha d for N_t
  double tolerance = 0.1;  // relative: |s - target| <= tolerance |target| is "in the regime"
  double half_width_decades = 0.1;  // smoothing of the local slope
  double t_lo = 0;                  // examined range
  double t_hi = std::numeric_limits<double>::infinity();
};

struct Crossover {
  double time = std::numeric_limits<double>::quiet_NaN();
  bool found = false;
  std::string note;  // why not found
};

Crossover crossover_enter(std::span<const double> t, std::span<const double> y,
                          const SlopeCrossoverOptions& options);  // t_c1
Crossover crossover_leave(std::span<const double> t, std::span<const double> y,
                          const SlopeCrossoverOptions& options);  // t_c2

// t_c2 over the examined range, then t_c1 over the part of it before t_c2 (all of it when the
// slope does not leave the band).
struct CrossoverPair {
  Crossover enter, leave;  // t_c1, t_c2
};
CrossoverPair crossover_pair(std::span<const double> t, std::span<const double> y,
                             const SlopeCrossoverOptions& options);

// crossover_pair of the mean of realisations drawn with replacement, `resamples` times (gs::Rng,
// Stream::Bootstrap, keyed by seed and key): NaN where a draw finds none. For bootstrap
// intervals of phi1 and phi2.
struct CrossoverDraws {
  std::vector<double> enter, leave;
};
CrossoverDraws crossover_draws(std::span<const double> t,
                               std::span<const std::vector<double>> realisations,
                               const SlopeCrossoverOptions& options, int resamples,
                               std::uint64_t seed, std::uint64_t key);

// Where two power laws a1 t^b1 and a2 t^b2 meet: (a2 / a1)^(1 / (b1 - b2)). NaN if parallel.
double crossover_intersection(const PowerLawFit& early, const PowerLawFit& late);

// The exponent phi of t_c ~ control^-phi across runs (control = 1 - r^2 for phi1, delta for
// phi2): minus the least-squares slope of ln t_c against ln control, with its standard error
// (from the scatter of >= 3 points). UserError on fewer than 3 points or values <= 0.
struct CrossoverExponent {
  double phi = std::numeric_limits<double>::quiet_NaN();
  double standard_error = std::numeric_limits<double>::quiet_NaN();
  double prefactor = std::numeric_limits<double>::quiet_NaN();  // t_c = prefactor control^-phi
  std::size_t points = 0;
};
CrossoverExponent fit_crossover_exponent(std::span<const double> control,
                                         std::span<const double> crossover_time);

}  // namespace gs
