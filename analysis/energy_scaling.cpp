#include "analysis/energy_scaling.h"

#include <algorithm>
#include <cmath>

#include "analysis/quantile.h"
#include "sim/error.h"
#include "sim/format.h"
#include "sim/rng.h"

namespace gs {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNan = std::numeric_limits<double>::quiet_NaN();

// ln y at ln t = u on the curve (t, y), linear in ln t and ln y; NaN outside the samples or where
// a neighbour is not positive.
double log_at(std::span<const double> t, std::span<const double> y, double u) {
  const double tu = std::exp(u);
  if (t.empty() || tu < t.front() || tu > t.back()) return kNan;
  auto it = std::lower_bound(t.begin(), t.end(), tu);
  std::size_t b = std::size_t(it - t.begin());
  if (b == 0) b = 1;
  const std::size_t a = b - 1;
  if (!(y[a] > 0) || !(y[b] > 0) || !(t[a] > 0)) return kNan;
  const double f = (u - std::log(t[a])) / (std::log(t[b]) - std::log(t[a]));
  return std::log(y[a]) + f * (std::log(y[b]) - std::log(y[a]));
}

void check_pair(const EnergyCurves& a, const EnergyCurves& b) {
  if (!(a.control > 0) || !(b.control > 0) || a.control == b.control)
    throw UserError("phi1: two different positive values of 1 - r^2 needed (" + a.label + ", " +
                    b.label + ")");
}

double phi_between(double ca, double cb, double ta, double tb) {
  return -(std::log(tb) - std::log(ta)) / (std::log(cb) - std::log(ca));
}

// The 95% percentile interval of the finite draws (NaN with fewer than 10).
void interval_of(std::vector<double> draws, Phi1Reading& out) {
  std::erase_if(draws, [](double x) { return !std::isfinite(x); });
  if (draws.size() < 10) return;
  std::sort(draws.begin(), draws.end());
  out.ci_lo = sorted_quantile(draws, 0.025);
  out.ci_hi = sorted_quantile(draws, 0.975);
}

// The mean of c's realisations drawn with replacement.
std::vector<double> resampled_mean(const EnergyCurves& c, Rng& rng) {
  std::vector<double> m(c.t.size(), 0.0);
  const std::size_t n = c.realisations.size();
  for (std::size_t k = 0; k < n; ++k) {
    const auto& y = c.realisations[std::size_t(rng.below(n))];
    for (std::size_t i = 0; i < m.size(); ++i) m[i] += y[i] / double(n);
  }
  return m;
}

// Calls f(mean_a, mean_b) for each of o.resamples draws, each curve's realisations resampled
// with replacement (gs::Rng, Stream::Bootstrap, keyed by the seed and `key`).
template <class F>
void for_each_draw(const EnergyCurves& a, const EnergyCurves& b, const Phi1Options& o,
                   std::uint64_t key, F f) {
  if (a.realisations.size() < 2 || b.realisations.size() < 2) return;
  Rng rng(o.seed, key, Stream::Bootstrap);
  for (int s = 0; s < o.resamples; ++s) {
    const auto ma = resampled_mean(a, rng);
    const auto mb = resampled_mean(b, rng);
    f(ma, mb);
  }
}

// The key of a level's draws: its own stream for each fraction of E_0.
std::uint64_t level_key(double level) {
  return 3301 + std::uint64_t(std::round(-100 * std::log(level)));
}

double best_collapse(const EnergyCurves& a, std::span<const double> ma, const EnergyCurves& b,
                     std::span<const double> mb, const Phi1Options& o) {
  const double step = 0.05;
  double best = kNan, best_m = kInf;
  for (double phi = o.phi_min; phi <= o.phi_max + 1e-12; phi += step) {
    const double m = collapse_misfit(a, ma, b, mb, phi, o.collapse_lo, o.collapse_hi);
    if (m < best_m) best_m = m, best = phi;
  }
  if (!std::isfinite(best_m)) return kNan;
  // The scan's minimum on its edge is no minimum: the range does not hold the collapse.
  if (best <= o.phi_min + 0.5 * step || best >= o.phi_max - 0.5 * step) return kNan;
  // Golden section inside the scan cell around the minimum.
  double lo = best - step, hi = best + step;
  const double g = 0.5 * (std::sqrt(5.0) - 1);
  auto m = [&](double p) { return collapse_misfit(a, ma, b, mb, p, o.collapse_lo, o.collapse_hi); };
  double x1 = hi - g * (hi - lo), x2 = lo + g * (hi - lo);
  double f1 = m(x1), f2 = m(x2);
  for (int k = 0; k < 40; ++k) {
    if (f1 < f2) {
      hi = x2, x2 = x1, f2 = f1, x1 = hi - g * (hi - lo), f1 = m(x1);
    } else {
      lo = x1, x1 = x2, f1 = f2, x2 = lo + g * (hi - lo), f2 = m(x2);
    }
  }
  return 0.5 * (lo + hi);
}

std::string fraction_text(double level) {
  return format_number(level);
}

}  // namespace

std::vector<double> EnergyCurves::mean() const {
  if (realisations.empty()) throw UserError("phi1: " + label + " has no realisations");
  std::vector<double> m(t.size(), 0.0);
  for (const auto& y : realisations) {
    if (y.size() != t.size())
      throw UserError("phi1: a realisation of " + label + " does not match its time grid");
    for (std::size_t i = 0; i < m.size(); ++i) m[i] += y[i] / double(realisations.size());
  }
  return m;
}

double time_to_level(std::span<const double> t, std::span<const double> y, double level) {
  if (!(level > 0)) throw UserError("phi1: an energy level must be positive");
  if (t.size() != y.size()) throw UserError("phi1: times and values differ in length");
  if (t.empty() || !(y[0] > level)) return kNan;
  for (std::size_t i = 1; i < t.size(); ++i) {
    if (y[i] > level) continue;
    if (!(y[i] > 0) || !(t[i - 1] > 0))  // not interpolable in logs: take the sample
      return t[i];
    const double f = (std::log(level) - std::log(y[i - 1])) / (std::log(y[i]) - std::log(y[i - 1]));
    return std::exp(std::log(t[i - 1]) + f * (std::log(t[i]) - std::log(t[i - 1])));
  }
  return kNan;
}

double collapse_misfit(const EnergyCurves& a, std::span<const double> ma, const EnergyCurves& b,
                       std::span<const double> mb, double phi, double lo, double hi) {
  double sum = 0;
  std::size_t n = 0;
  auto one_way = [&](const EnergyCurves& p, std::span<const double> mp, const EnergyCurves& q,
                     std::span<const double> mq) {
    const double shift = phi * (std::log(p.control) - std::log(q.control));
    for (std::size_t i = 0; i < p.t.size(); ++i) {
      const double f = mp[i] / p.e0;
      if (!(f >= lo && f <= hi) || !(p.t[i] > 0)) continue;
      const double yq = log_at(q.t, mq, std::log(p.t[i]) + shift);  // same x on q
      if (!std::isfinite(yq)) continue;
      const double d = std::log(f) - (yq - std::log(q.e0));
      sum += d * d;
      ++n;
    }
  };
  one_way(a, ma, b, mb);
  one_way(b, mb, a, ma);
  return n >= 4 ? sum / double(n) : kInf;
}

FractionTime time_to_fraction(const EnergyCurves& c, double level, const Phi1Options& o) {
  FractionTime out;
  if (c.realisations.empty()) return out;
  out.t = time_to_level(c.t, c.mean(), level * c.e0);
  if (c.realisations.size() < 2) return out;
  // Streams apart from the pairs' (keys 3300 and up): 4300 and up.
  Rng rng(o.seed, 1000 + level_key(level), Stream::Bootstrap);
  for (int s = 0; s < o.resamples; ++s)
    out.draws.push_back(time_to_level(c.t, resampled_mean(c, rng), level * c.e0));
  return out;
}

Phi1Reading phi1_from_level(const EnergyCurves& a, const EnergyCurves& b, double level,
                            const Phi1Options& o) {
  check_pair(a, b);
  Phi1Reading out;
  out.from = a.label;
  out.to = b.label;
  out.level = level;
  const auto ma = a.mean(), mb = b.mean();
  const double ta = time_to_level(a.t, ma, level * a.e0);
  const double tb = time_to_level(b.t, mb, level * b.e0);
  if (!std::isfinite(ta) || !std::isfinite(tb)) {
    out.note = (std::isfinite(ta) ? b.label : a.label) + " does not reach E_0 x " +
               fraction_text(level) + " within its run";
    return out;
  }
  out.phi = phi_between(a.control, b.control, ta, tb);
  std::vector<double> draws;
  for_each_draw(a, b, o, level_key(level), [&](const auto& da, const auto& db) {
    const double x = time_to_level(a.t, da, level * a.e0);
    const double y = time_to_level(b.t, db, level * b.e0);
    draws.push_back(std::isfinite(x) && std::isfinite(y) ? phi_between(a.control, b.control, x, y)
                                                         : kNan);
  });
  interval_of(std::move(draws), out);
  return out;
}

Phi1Reading phi1_from_collapse(const EnergyCurves& a, const EnergyCurves& b, const Phi1Options& o) {
  check_pair(a, b);
  if (!(o.collapse_lo > 0 && o.collapse_lo < o.collapse_hi))
    throw UserError("phi1: the collapse's energy range must satisfy 0 < lo < hi");
  Phi1Reading out;
  out.from = a.label;
  out.to = b.label;
  const auto ma = a.mean(), mb = b.mean();
  out.phi = best_collapse(a, ma, b, mb, o);
  if (!std::isfinite(out.phi)) {
    out.note = "no minimum of the misfit inside phi1 in [" + format_number(o.phi_min) + ", " +
               format_number(o.phi_max) + "] (the curves do not overlap between E_0 x " +
               fraction_text(o.collapse_hi) + " and E_0 x " + fraction_text(o.collapse_lo) +
               ", or do not collapse)";
    return out;
  }
  std::vector<double> draws;
  for_each_draw(a, b, o, 3300, [&](const auto& da, const auto& db) {
    draws.push_back(best_collapse(a, da, b, db, o));
  });
  interval_of(std::move(draws), out);
  return out;
}

const Phi1Reading* nearest_limit_reading(const std::vector<Phi1Reading>& readings, double level) {
  const Phi1Reading* last = nullptr;
  for (const auto& p : readings)
    if ((std::isnan(level) ? std::isnan(p.level) : p.level == level) && std::isfinite(p.phi))
      last = &p;
  return last;
}

std::vector<Phi1Reading> phi1_readings(const std::vector<EnergyCurves>& curves,
                                       const Phi1Options& o) {
  std::vector<Phi1Reading> out;
  for (std::size_t k = 1; k < curves.size(); ++k) {
    out.push_back(phi1_from_collapse(curves[k - 1], curves[k], o));
    for (double level : o.levels)
      out.push_back(phi1_from_level(curves[k - 1], curves[k], level, o));
  }
  return out;
}

}  // namespace gs
