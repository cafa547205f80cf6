#include "analysis/snowplow.h"

#include <algorithm>
#include <cmath>

namespace gs {
namespace {

// 99.7% quantiles of chi^2 with k = 1..4 degrees of freedom (the level of a 3 sigma deviation).
constexpr double kChi2Excluded[5] = {0, 8.807, 11.618, 14.156, 16.527};
constexpr double kZ95 = 1.959964;

double sigma_of(const ExponentFit& e) {
  const double stat = e.fit.confidence > 0 ? 0.5 * (e.fit.ci_hi - e.fit.ci_lo) / kZ95
                                           : e.fit.standard_error;
  const double sys = std::isfinite(e.window_systematic) ? e.window_systematic : 0;
  return std::sqrt(stat * stat + sys * sys);
}

std::string strength_of(double odds) {
  return odds < 3 ? "not worth more than a bare mention"
         : odds < 20  ? "positive"
         : odds < 150 ? "strong"
                      : "very strong";
}

}  // namespace

SnowplowVerdict weigh_snowplow(int d, const EnsembleFits& fits) {
  SnowplowVerdict v;
  v.d = d;
  double chi_m = 0, chi_p = 0;
  for (Quantity q : {Quantity::RadiusRms, Quantity::ActiveCount, Quantity::Energy,
                     Quantity::RadialMomentum}) {
    SnowplowReading r;
    r.quantity = q;
    if (const ExponentFit* e = find_exponent(fits, q); e && std::isfinite(e->fit.exponent)) {
      r.exponent = e->fit.exponent;
      r.sigma = sigma_of(*e);
      if (r.sigma > 0) {
        r.z_momentum = (r.exponent - exponent_from_alpha(q, d, momentum_conserving_alpha(d))) /
                       r.sigma;
        r.z_pressure = (r.exponent - exponent_from_alpha(q, d, pressure_driven_alpha(d))) /
                       r.sigma;
        chi_m += r.z_momentum * r.z_momentum;
        chi_p += r.z_pressure * r.z_pressure;
        ++v.used;
      }
    }
    v.readings.push_back(r);
  }
  if (v.used == 0) {
    v.favoured = "no readings";
    v.strength = "no plateau within the run";
    return v;
  }
  v.chi2_momentum = chi_m;
  v.chi2_pressure = chi_p;
  if (d == 2) {
    v.favoured = "both (the same alpha in 2D)";
    v.strength = chi_m > kChi2Excluded[v.used] ? "the data exclude it" : "";
    return v;
  }
  const double near = std::min(chi_m, chi_p), far = std::max(chi_m, chi_p);
  v.odds = std::exp(0.5 * (far - near));
  if (near > kChi2Excluded[v.used]) {
    v.favoured = "neither";
    v.strength = "both excluded";
    return v;
  }
  v.favoured = chi_m <= chi_p ? "momentum-conserving" : "pressure-driven";
  v.strength = strength_of(v.odds);
  return v;
}

SnowplowEnd snowplow_at_the_end(int d, const EnsembleFits& fits) {
  constexpr double kFloor = 1e-3;  // the plateau rule's: the rounding of an exact series
  SnowplowEnd v;
  v.d = d;
  const auto end_of = [&fits](Quantity q) {
    const ExponentFit* e = find_exponent(fits, q);
    return e ? end_slope(e->slope) : EndSlope{};
  };
  v.epsilon = end_of(Quantity::RadialMomentum);
  v.radius = end_of(Quantity::RadiusRms);
  v.count = end_of(Quantity::ActiveCount);
  v.energy = end_of(Quantity::Energy);
  const auto epsilon_of = [d](double alpha) {
    return exponent_from_alpha(Quantity::RadialMomentum, d, alpha);
  };
  const double mc = epsilon_of(momentum_conserving_alpha(d)),
               pd = epsilon_of(pressure_driven_alpha(d));
  if (v.radius.found && v.count.found) {
    v.shell = v.count.slope + v.radius.slope - 1;
    v.shell_sigma = std::hypot(v.count.slope_error, v.radius.slope_error, kFloor);
    v.shell_z_momentum = (v.shell - mc) / v.shell_sigma;
    v.shell_z_pressure = (v.shell - pd) / v.shell_sigma;
  }
  if (!v.epsilon.found) {
    v.heading = "no readings";
    return v;
  }
  if (std::fabs(mc - pd) < 1e-12) {
    v.heading = "both (the same alpha in 2D)";
    return v;
  }
  // The picture(s) the reading points to: towards (a significant drift) or near (none).
  const auto pick = [](bool mc_side, bool pd_side) {
    return mc_side && pd_side ? "undecided"
           : mc_side          ? "momentum-conserving"
           : pd_side          ? "pressure-driven"
                              : "neither";
  };
  const double eps = v.epsilon.slope, drift = v.epsilon.drift_per_decade;
  if (std::fabs(drift) > 2 * v.epsilon.drift_error + kFloor) {
    v.heading = pick((mc - eps) * drift > 0, (pd - eps) * drift > 0);
    return v;
  }
  const double reach = 3 * v.epsilon.slope_error + kFloor;
  v.heading = pick(std::fabs(eps - mc) <= reach, std::fabs(eps - pd) <= reach);
  return v;
}

}  // namespace gs
