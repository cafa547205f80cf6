#include "analysis/crossover.h"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "sim/error.h"
#include "sim/format.h"
#include "sim/rng.h"

namespace gs {
namespace {

struct Marked {
  std::vector<std::size_t> index;  // samples in range with a finite slope
  std::vector<double> slope;
  std::vector<double> above;  // s - target - tolerance |target|: > 0 above the band
};

Marked mark(std::span<const double> t, std::span<const double> y, const SlopeCrossoverOptions& o) {
  if (!std::isfinite(o.target) || o.target == 0)
    throw UserError("crossover target slope must be finite and non-zero");
  if (!(o.tolerance > 0)) throw UserError("crossover tolerance must be positive");
  const auto s = local_slope(t, y, o.half_width_decades);
  Marked m;
  for (std::size_t i = 0; i < t.size(); ++i) {
    if (t[i] < o.t_lo || t[i] > o.t_hi || !std::isfinite(s[i])) continue;
    m.index.push_back(i);
    m.slope.push_back(s[i]);
    m.above.push_back(s[i] - o.target - o.tolerance * std::fabs(o.target));
  }
  return m;
}

// A slope in a note: 0.845, not 0.84532873.
std::string three_digits(double x) {
  return format_number(std::round(x * 1000) / 1000);
}

// The time between samples a and b where `above` crosses zero, linear in ln t.
double interpolate(std::span<const double> t, std::size_t a, std::size_t b, double da, double db) {
  const double f = da / (da - db);
  return std::exp(std::log(t[a]) + f * (std::log(t[b]) - std::log(t[a])));
}

// Calls f(mean) for the mean of each of `resamples` draws of realisations with replacement
// (gs::Rng, Stream::Bootstrap, keyed by seed and key).
template <class F>
void for_each_resampled_mean(std::size_t n, std::span<const std::vector<double>> curves,
                             int resamples, std::uint64_t seed, std::uint64_t key, F f) {
  Rng rng(seed, key, Stream::Bootstrap);
  std::vector<std::size_t> draw(curves.size());
  for (int b = 0; b < resamples; ++b) {
    for (auto& x : draw) x = std::size_t(rng.below(curves.size()));
    std::vector<double> mean(n, 0.0);
    for (std::size_t k : draw)
      for (std::size_t i = 0; i < n; ++i) mean[i] += curves[k][i] / double(draw.size());
    f(std::as_const(mean));
  }
}

}  // namespace

Crossover crossover_enter(std::span<const double> t, std::span<const double> y,
                          const SlopeCrossoverOptions& o) {
  const Marked m = mark(t, y, o);
  Crossover c;
  const std::size_t n = m.index.size();
  if (n < 2) {
    c.note = "fewer than 2 usable samples in the examined range";
    return c;
  }
  if (m.above[n - 1] > 0) {
    c.note = "the local slope is above the band around " + format_double(o.target) +
             " at the end of the range (scaling regime not reached; it ends at " +
             three_digits(m.slope[n - 1]) + ")";
    return c;
  }
  std::size_t k = n - 1;  // first sample of the final run at or below the band's upper edge
  while (k > 0 && m.above[k - 1] <= 0) --k;
  if (k == 0) {
    c.note =
        "the local slope is at or below the band's upper edge from the first sample "
        "(crossover before the data)";
    return c;
  }
  c.time = interpolate(t, m.index[k - 1], m.index[k], m.above[k - 1], m.above[k]);
  c.found = true;
  return c;
}

Crossover crossover_leave(std::span<const double> t, std::span<const double> y,
                          const SlopeCrossoverOptions& o) {
  const Marked m = mark(t, y, o);
  Crossover c;
  const std::size_t n = m.index.size();
  if (n < 2) {
    c.note = "fewer than 2 usable samples in the examined range";
    return c;
  }
  if (m.above[n - 1] <= 0) {
    c.note = "the local slope is not above the band around " + format_double(o.target) +
             " at the end of the range (crossover not reached; it ends at " +
             three_digits(m.slope[n - 1]) + ")";
    return c;
  }
  std::size_t k = n - 1;  // first sample of the final run above the band
  while (k > 0 && m.above[k - 1] > 0) --k;
  if (k == 0) {
    c.note = "the local slope is above the band around " + format_double(o.target) +
             " throughout (the scaling regime never began)";
    return c;
  }
  // Interpolated to where s crosses the band's upper edge.
  c.time = interpolate(t, m.index[k - 1], m.index[k], m.above[k - 1], m.above[k]);
  c.found = true;
  return c;
}

CrossoverPair crossover_pair(std::span<const double> t, std::span<const double> y,
                             const SlopeCrossoverOptions& o) {
  CrossoverPair p;
  p.leave = crossover_leave(t, y, o);
  SlopeCrossoverOptions before = o;
  if (p.leave.found) before.t_hi = std::min(o.t_hi, p.leave.time);
  p.enter = crossover_enter(t, y, before);
  return p;
}

CrossoverDraws crossover_draws(std::span<const double> t,
                               std::span<const std::vector<double>> curves,
                               const SlopeCrossoverOptions& o, int resamples, std::uint64_t seed,
                               std::uint64_t key) {
  CrossoverDraws out;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  if (curves.size() < 2) return out;
  for_each_resampled_mean(t.size(), curves, resamples, seed, key, [&](const auto& mean) {
    const CrossoverPair c = crossover_pair(t, mean, o);
    out.enter.push_back(c.enter.found ? c.enter.time : nan);
    out.leave.push_back(c.leave.found ? c.leave.time : nan);
  });
  return out;
}

double crossover_intersection(const PowerLawFit& early, const PowerLawFit& late) {
  const double db = early.exponent - late.exponent;
  if (!(std::fabs(db) > 0)) return std::numeric_limits<double>::quiet_NaN();
  return std::exp((std::log(late.prefactor) - std::log(early.prefactor)) / db);
}

Crossover crossover_energy(const PowerLawFit& energy, double e0, double last_time,
                           const std::string& energy_note) {
  if (!(e0 > 0)) throw UserError("crossover: the initial energy must be positive");
  Crossover c;
  if (!std::isfinite(energy.exponent)) {
    c.note = "no power law of E_t to meet E_0 (" + energy_note + ")";
    return c;
  }
  if (!(energy.exponent < 0)) {
    c.note = "E_t's plateau exponent " + three_digits(energy.exponent) +
             " is not negative: no dissipating regime";
    return c;
  }
  if (energy.window.t_hi < last_time * std::pow(10.0, -0.1)) {
    c.note = "E_t's plateau [" + three_digits(energy.window.t_lo) + ", " +
             three_digits(energy.window.t_hi) + "] (slope " + three_digits(energy.exponent) +
             ") ends before the run (t = " + format_number(last_time) +
             "): the slope drifts on, the scaling regime is not reached";
    return c;
  }
  PowerLawFit elastic;
  elastic.exponent = 0;
  elastic.prefactor = e0;
  c.time = crossover_intersection(elastic, energy);
  c.found = std::isfinite(c.time) && c.time > 0;
  if (!c.found) c.note = "E_t's power law does not meet E_0";
  return c;
}

std::vector<double> crossover_energy_draws(std::span<const double> t,
                                           std::span<const std::vector<double>> curves,
                                           const Window& window, double e0, int resamples,
                                           std::uint64_t seed, std::uint64_t key,
                                           double fixed_exponent) {
  std::vector<double> out;
  if (curves.size() < 2) return out;
  for_each_resampled_mean(t.size(), curves, resamples, seed, key, [&](const auto& mean) {
    double time = std::numeric_limits<double>::quiet_NaN();
    try {
      const PowerLawFit fit = std::isfinite(fixed_exponent)
                                  ? fit_power_law_fixed(t, mean, window, fixed_exponent)
                                  : fit_power_law(t, mean, window);
      const Crossover c = crossover_energy(fit, e0, t.back(), "");
      if (c.found) time = c.time;
    } catch (const UserError&) {  // a draw with a non-positive mean in the window: no time
    }
    out.push_back(time);
  });
  return out;
}

CrossoverExponent fit_crossover_exponent(std::span<const double> control,
                                         std::span<const double> crossover_time) {
  if (control.size() != crossover_time.size())
    throw UserError("crossover fit: as many control values as crossover times needed");
  std::vector<double> x, y;
  for (std::size_t i = 0; i < control.size(); ++i) {
    if (!(control[i] > 0) || !(crossover_time[i] > 0))
      throw UserError("crossover fit: control " + format_double(control[i]) + " and time " +
                      format_double(crossover_time[i]) + " must be positive");
    x.push_back(std::log(control[i]));
    y.push_back(std::log(crossover_time[i]));
  }
  const Line l = fit_line(x, y);
  CrossoverExponent e;
  e.phi = -l.slope;
  e.standard_error = l.slope_error;
  e.prefactor = std::exp(l.intercept);
  e.points = l.points;
  return e;
}

}  // namespace gs
