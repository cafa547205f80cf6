#include "analysis/effective_exponent.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <deque>
#include <numbers>

#include "analysis/quantile.h"
#include "sim/error.h"
#include "sim/format.h"
#include "sim/rng.h"

namespace gs {
namespace {

std::vector<double> mean_of(std::span<const std::vector<double>> curves,
                            std::span<const std::size_t> draw, std::size_t n) {
  std::vector<double> m(n, 0.0);
  for (std::size_t k : draw)
    for (std::size_t i = 0; i < n; ++i) m[i] += curves[k][i];
  for (auto& x : m) x /= double(draw.size());
  return m;
}

std::string short_text(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4g", x);
  return buf;
}

double quantile(std::vector<double>& v, double q) {
  std::sort(v.begin(), v.end());
  return sorted_quantile(v, q);
}

}  // namespace

SlopeBand local_slope_band(std::span<const double> t,
                           std::span<const std::vector<double>> realisations,
                           const SlopeBandOptions& o) {
  const std::size_t m = realisations.size(), n = t.size();
  if (m == 0) throw UserError("local slope: no realisation");
  for (const auto& c : realisations)
    if (c.size() != n) throw UserError("local slope: a realisation's length differs from the grid");
  std::vector<std::size_t> all(m);
  for (std::size_t k = 0; k < m; ++k) all[k] = k;
  SlopeBand b;
  b.t.assign(t.begin(), t.end());
  b.slope = local_slope(t, mean_of(realisations, all, n), o.half_width_decades);
  b.lo = b.slope;
  b.hi = b.slope;
  if (m < 2) return b;
  Rng rng(o.seed, o.key, Stream::Bootstrap);
  std::vector<std::vector<double>> per_point(n);
  std::vector<std::size_t> draw(m);
  for (int r = 0; r < o.resamples; ++r) {
    for (auto& d : draw) d = std::size_t(rng.below(m));
    const auto s = local_slope(t, mean_of(realisations, draw, n), o.half_width_decades);
    for (std::size_t i = 0; i < n; ++i)
      if (std::isfinite(s[i])) per_point[i].push_back(s[i]);
  }
  for (std::size_t i = 0; i < n; ++i) {
    // A point whose slope some resamples cannot define (a zero nearby) has no band.
    if (!std::isfinite(b.slope[i]) || per_point[i].size() < std::size_t(o.resamples)) {
      b.lo[i] = b.hi[i] = std::numeric_limits<double>::quiet_NaN();
      continue;
    }
    b.lo[i] = quantile(per_point[i], (1 - o.confidence) / 2);
    b.hi[i] = quantile(per_point[i], (1 + o.confidence) / 2);
  }
  return b;
}

Plateau find_plateau(const SlopeBand& band, const PlateauOptions& o) {
  const auto& t = band.t;
  const std::size_t n = t.size();
  std::vector<double> lower(n), upper(n);
  std::vector<bool> usable(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double h = o.tolerance + 0.5 * (band.hi[i] - band.lo[i]);
    usable[i] = t[i] > 0 && t[i] >= o.t_min && t[i] <= o.t_max && std::isfinite(band.slope[i]) &&
                std::isfinite(h);
    lower[i] = band.slope[i] - h;
    upper[i] = band.slope[i] + h;
  }
  // Two pointers: for each end b the earliest start a(b) whose intervals still intersect (a(b)
  // never decreases), with monotone deques for the running max of `lower` and min of `upper`.
  const double need = o.min_decades * std::numbers::ln10 * (1 - 1e-9);
  std::deque<std::size_t> lo, hi;
  std::size_t a = 0, best_a = 0, best_b = 0;
  bool found = false;
  for (std::size_t b = 0; b < n; ++b) {
    if (!usable[b]) {
      lo.clear();
      hi.clear();
      a = b + 1;
      continue;
    }
    while (!lo.empty() && lower[lo.back()] <= lower[b]) lo.pop_back();
    lo.push_back(b);
    while (!hi.empty() && upper[hi.back()] >= upper[b]) hi.pop_back();
    hi.push_back(b);
    while (lower[lo.front()] > upper[hi.front()]) {
      ++a;
      while (lo.front() < a) lo.pop_front();
      while (hi.front() < a) hi.pop_front();
    }
    if (std::log(t[b]) - std::log(t[a]) >= need) {
      found = true;
      best_a = a;
      best_b = b;
    }
  }
  Plateau p;
  if (!found) {
    // Say where the slope goes instead: its value at the first and last usable samples.
    std::size_t first = n, last = n;
    for (std::size_t i = 0; i < n; ++i)
      if (usable[i]) {
        if (first == n) first = i;
        last = i;
      }
    if (first == n) {
      p.note = "no plateau within the run: no usable local slope";
    } else {
      p.note = "no plateau within the run: the local slope goes from " +
               short_text(band.slope[first]) + " at t = " + short_text(t[first]) + " to " +
               short_text(band.slope[last]) + " at t = " + short_text(t[last]) +
               " and stays within +-(" + short_text(o.tolerance) + " + its band) over no " +
               short_text(o.min_decades) + " decades";
    }
    return p;
  }
  double mx = -std::numeric_limits<double>::infinity(), mn = -mx;
  for (std::size_t i = best_a; i <= best_b; ++i) {
    mx = std::max(mx, lower[i]);
    mn = std::min(mn, upper[i]);
  }
  p.found = true;
  p.window = {t[best_a], t[best_b]};
  p.exponent = 0.5 * (mx + mn);
  return p;
}

}  // namespace gs
