#pragma once
// Crossover times of the paper: t_c1, when the blast enters its inelastic scaling regime
// (diverging as (1 - r^2)^-phi1 in the elastic limit, phi1 ~ 2.25 in 2D, 3.0 in 3D), and t_c2,
// when the band has slowed to v_t ~ delta and collisions turn elastic (t_c2 ~ delta^-phi2,
// phi2 = 1/(1 - alpha)).
//
// t_c1, intersection rule (the one reported): where the two asymptotic laws of E_t meet, the
// elastic regime's E_t = E_0 (energy conserved) and the inelastic scaling law a t^-b fitted on
// the plateau of E_t's local slope: t_c1 = (a / E_0)^(1/b). It is the time from which the
// blast dissipates as the scaling regime does, and needs no early-time plateau, which small r
// do not have: their E_t is on its scaling slope from the first tens of collisions.
// The same with b fixed at the theory's asymptotic exponent and only a fitted on that window (the
// "theory b" reading): a plateau slope shallower than b (the slope still drifting towards it, as
// in 3D at r >= 0.7) extrapolates back to E_0 differently under the two, and the difference
// between the phi1 of each is the rule's systematic.
// t_c1, slope rule on N_t (the previous reading, kept in each ensemble's summary.json but no
// longer fitted for phi1): with s(t) the local log-slope
// of N_t (power_law.h) and the target its asymptotic value alpha d, the time from which s stays
// at or below the upper edge of the band target +- `tolerance` (relative) to the end of the
// examined range. Measured, it does not depend on r (t ~ 500-800 in 2D for r = 0.1 ... 0.9):
// the slope of N_t falls from ~0.9 to 2/3 over t ~ 1e2-1e3 for every r, E_t already being on
// its scaling slope for r <= 0.5, so the rule times the build-up of the band, not the end of
// the elastic regime. An undershoot below the band that follows (2D at r >= 0.7 and 3D) does
// not move it.
// t_c2, slope rule on N_t: the time after which s stays above that band (towards the elastic
// regime, whose exponents are the larger) up to the end of the examined range. A run may reach
// past t_c2 (the delta scan does), so t_c2 is sought first and the slope rule's t_c1 only
// before it (crossover_pair).
// The slope rule locates each time between the two samples where it switches, by linear
// interpolation of s in ln t. If X = t_c^a g(t / t_c) for a family of runs (one crossover
// shape, shifted), both rules give a fixed multiple of t_c, so phi1 and phi2 come out right
// whatever the tolerance.
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

// The intersection rule's t_c1: where E_0 (the energy given to the blast) meets `energy`, the
// power law fitted on the plateau of E_t's local slope. Not found when the fit has no exponent
// (`energy_note` says why), when its exponent is not negative (no dissipating regime), or when
// its window ends more than 0.1 decade (the local slope's smoothing half width) before
// `last_time`, the run's last sample: a plateau the slope leaves again is a transient, not the
// asymptotic regime (3D at r >= 0.7 in --quick: E_t's slope still falls at the end of the run).
Crossover crossover_energy(const PowerLawFit& energy, double e0, double last_time,
                           const std::string& energy_note);

// crossover_energy of the mean of realisations drawn with replacement, each fitted over
// `window` (its exponent fitted, or fixed at `fixed_exponent` when that is finite: the theory's
// b, fit_power_law_fixed), `resamples` times (gs::Rng, Stream::Bootstrap, keyed by seed and
// key): NaN where a draw meets none. For the bootstrap interval of phi1.
std::vector<double> crossover_energy_draws(
    std::span<const double> t, std::span<const std::vector<double>> realisations,
    const Window& window, double e0, int resamples, std::uint64_t seed, std::uint64_t key,
    double fixed_exponent = std::numeric_limits<double>::quiet_NaN());

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
