#include "analysis/power_law.h"

#include <algorithm>
#include <cmath>
#include <deque>
#include <numbers>
#include <string>

#include "analysis/quantile.h"
#include "sim/error.h"
#include "sim/format.h"
#include "sim/rng.h"

namespace gs {
namespace {

std::string window_text(const Window& w) {
  return "[" + format_double(w.t_lo) + ", " + format_double(w.t_hi) + "]";
}

// Indices [first, last) of the times inside the window, after checking it against the data.
std::pair<std::size_t, std::size_t> window_range(std::span<const double> t, const Window& w) {
  if (t.empty()) throw UserError("scaling window " + window_text(w) + ": no data");
  if (!(w.t_hi > w.t_lo))
    throw UserError("scaling window " + window_text(w) + " is empty (t_hi must exceed t_lo)");
  if (w.t_lo < t.front() || w.t_hi > t.back())
    throw UserError("scaling window " + window_text(w) + " lies outside the data [" +
                    format_double(t.front()) + ", " + format_double(t.back()) + "]");
  if (!(w.t_lo > 0)) throw UserError("scaling window " + window_text(w) + " must start at t > 0");
  const auto first = std::size_t(std::lower_bound(t.begin(), t.end(), w.t_lo) - t.begin());
  const auto last = std::size_t(std::upper_bound(t.begin(), t.end(), w.t_hi) - t.begin());
  if (last < first + 3)
    throw UserError("scaling window " + window_text(w) + " holds fewer than 3 samples");
  return {first, last};
}

void check_sorted(std::span<const double> t) {
  GS_CHECK_MSG(std::is_sorted(t.begin(), t.end()), "time grid must be increasing");
}

}  // namespace

Line fit_line(std::span<const double> x, std::span<const double> y) {
  GS_CHECK(x.size() == y.size());
  const std::size_t n = x.size();
  if (n < 3) throw UserError("a line fit needs at least 3 points, got " + std::to_string(n));
  double mx = 0, my = 0;
  for (std::size_t i = 0; i < n; ++i) {
    mx += x[i];
    my += y[i];
  }
  mx /= double(n);
  my /= double(n);
  double sxx = 0, sxy = 0;
  for (std::size_t i = 0; i < n; ++i) {
    sxx += (x[i] - mx) * (x[i] - mx);
    sxy += (x[i] - mx) * (y[i] - my);
  }
  if (!(sxx > 0)) throw UserError("a line fit needs distinct abscissae");
  Line l;
  l.points = n;
  l.slope = sxy / sxx;
  l.intercept = my - l.slope * mx;
  double ssr = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double r = y[i] - l.intercept - l.slope * x[i];
    ssr += r * r;
  }
  l.slope_error = std::sqrt(ssr / double(n - 2) / sxx);
  return l;
}

std::vector<double> local_slope(std::span<const double> t, std::span<const double> y,
                                double half_width_decades) {
  GS_CHECK(t.size() == y.size());
  check_sorted(t);
  const std::size_t n = t.size();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::vector<double> s(n, nan);
  // A little slack so that a log-spaced grid, whose neighbours sit at exactly half_width in
  // exact arithmetic, gets the same symmetric neighbourhood at every point despite round-off.
  const double h = half_width_decades * std::numbers::ln10 * (1 + 1e-9);
  for (std::size_t i = 0; i < n; ++i) {
    if (!(t[i] > 0)) continue;
    const double li = std::log(t[i]);
    std::size_t a = i, b = i + 1;  // [a, b)
    while (a > 0 && t[a - 1] > 0 && li - std::log(t[a - 1]) <= h) --a;
    while (b < n && std::log(t[b]) - li <= h) ++b;
    if (a == i && i > 0 && t[i - 1] > 0) --a;  // at least one neighbour on each side
    if (b == i + 1 && b < n) ++b;
    if (b - a < 2) continue;
    double sx = 0, sy = 0;
    bool ok = true;
    for (std::size_t j = a; j < b; ++j) {
      if (!(y[j] > 0) || !(t[j] > 0)) ok = false;
    }
    if (!ok) continue;
    for (std::size_t j = a; j < b; ++j) {
      sx += std::log(t[j]);
      sy += std::log(y[j]);
    }
    const double m = double(b - a), mx = sx / m, my = sy / m;
    double sxx = 0, sxy = 0;
    for (std::size_t j = a; j < b; ++j) {
      const double dx = std::log(t[j]) - mx;
      sxx += dx * dx;
      sxy += dx * (std::log(y[j]) - my);
    }
    if (sxx > 0) s[i] = sxy / sxx;
  }
  return s;
}

Window auto_window(std::span<const double> t, std::span<const double> y,
                   const AutoWindowOptions& o) {
  const auto s = local_slope(t, y, o.half_width_decades);
  const std::size_t n = t.size();
  // Two pointers over runs of finite slopes in [t_min, t_max], with monotone deques holding the
  // running minimum and maximum of the slope in [a, b].
  std::size_t best_a = 0, best_b = 0;
  double best_len = -1;
  std::deque<std::size_t> lo, hi;
  std::size_t a = 0;
  for (std::size_t b = 0; b < n; ++b) {
    const bool usable = std::isfinite(s[b]) && t[b] >= o.t_min && t[b] <= o.t_max && t[b] > 0;
    if (!usable) {
      lo.clear();
      hi.clear();
      a = b + 1;
      continue;
    }
    while (!lo.empty() && s[lo.back()] >= s[b]) lo.pop_back();
    lo.push_back(b);
    while (!hi.empty() && s[hi.back()] <= s[b]) hi.pop_back();
    hi.push_back(b);
    while (s[hi.front()] - s[lo.front()] > 2 * o.tolerance) {
      ++a;
      while (lo.front() < a) lo.pop_front();
      while (hi.front() < a) hi.pop_front();
    }
    const double len = std::log(t[b]) - std::log(t[a]);
    if (len > best_len) {
      best_len = len;
      best_a = a;
      best_b = b;
    }
  }
  if (best_len < o.min_decades * std::numbers::ln10)
    throw UserError("no scaling window: the local slope never stays within +-" +
                    format_double(o.tolerance) + " over " + format_double(o.min_decades) +
                    " decades of time (longest: " +
                    format_double(std::max(0.0, best_len) / std::numbers::ln10) + ")");
  return {t[best_a], t[best_b]};
}

namespace {

// ln t and ln y over [first, last); UserError naming the window at a y <= 0.
void log_points(std::span<const double> t, std::span<const double> y, std::size_t first,
                std::size_t last, const Window& w, std::vector<double>& x, std::vector<double>& z) {
  for (std::size_t i = first; i < last; ++i) {
    if (!(y[i] > 0))
      throw UserError("scaling window " + window_text(w) + ": value " + format_double(y[i]) +
                      " at t = " + format_double(t[i]) + " is not positive (log-log fit)");
    x.push_back(std::log(t[i]));
    z.push_back(std::log(y[i]));
  }
}

PowerLawFit fit_range(std::span<const double> t, std::span<const double> y, std::size_t first,
                      std::size_t last, const Window& w) {
  std::vector<double> x, z;
  log_points(t, y, first, last, w, x, z);
  const Line l = fit_line(x, z);
  PowerLawFit f;
  f.exponent = l.slope;
  f.prefactor = std::exp(l.intercept);
  f.standard_error = l.slope_error;
  f.points = l.points;
  f.window = w;
  return f;
}

}  // namespace

PowerLawFit fit_power_law(std::span<const double> t, std::span<const double> y, const Window& w) {
  GS_CHECK(t.size() == y.size());
  check_sorted(t);
  const auto [first, last] = window_range(t, w);
  return fit_range(t, y, first, last, w);
}

PowerLawFit fit_power_law_fixed(std::span<const double> t, std::span<const double> y,
                                const Window& w, double exponent) {
  GS_CHECK(t.size() == y.size());
  GS_CHECK(std::isfinite(exponent));
  check_sorted(t);
  const auto [first, last] = window_range(t, w);
  std::vector<double> x, z;
  log_points(t, y, first, last, w, x, z);
  double sum = 0;
  for (std::size_t i = 0; i < x.size(); ++i) sum += z[i] - exponent * x[i];
  PowerLawFit f;
  f.exponent = exponent;
  f.prefactor = std::exp(sum / double(x.size()));
  f.points = x.size();
  f.window = w;
  return f;
}

PowerLawFit fit_power_law_bootstrap(std::span<const double> t,
                                    std::span<const std::vector<double>> realisations,
                                    const Window& w, const BootstrapOptions& o) {
  check_sorted(t);
  const std::size_t m = realisations.size();
  if (m < 2) throw UserError("bootstrap needs at least 2 realisations, got " + std::to_string(m));
  if (o.resamples < 10) throw UserError("bootstrap needs at least 10 resamples");
  if (!(o.confidence > 0 && o.confidence < 1))
    throw UserError("bootstrap confidence must be in (0, 1)");
  for (std::size_t k = 0; k < m; ++k)
    if (realisations[k].size() != t.size())
      throw UserError("realisation " + std::to_string(k) + " has " +
                      std::to_string(realisations[k].size()) + " samples, the time grid " +
                      std::to_string(t.size()));
  const auto [first, last] = window_range(t, w);

  // Sums in a fixed order (realisation index, then draw order) keep the result reproducible.
  auto mean_curve = [&](auto&& index_of) {
    std::vector<double> mean(t.size(), 0.0);
    for (std::size_t k = 0; k < m; ++k) {
      const auto& c = realisations[index_of(k)];
      for (std::size_t i = first; i < last; ++i) mean[i] += c[i];
    }
    for (std::size_t i = first; i < last; ++i) mean[i] /= double(m);
    return mean;
  };
  const auto full = mean_curve([](std::size_t k) { return k; });
  PowerLawFit fit = fit_range(t, full, first, last, w);

  Rng rng(o.seed, o.key, Stream::Bootstrap);
  std::vector<double> exponents;
  exponents.reserve(std::size_t(o.resamples));
  std::vector<std::size_t> draw(m);
  for (int b = 0; b < o.resamples; ++b) {
    for (auto& d : draw) d = std::size_t(rng.below(m));
    const auto mean = mean_curve([&](std::size_t k) { return draw[k]; });
    exponents.push_back(fit_range(t, mean, first, last, w).exponent);
  }
  std::sort(exponents.begin(), exponents.end());
  auto quantile = [&](double q) { return sorted_quantile(exponents, q); };
  fit.ci_lo = quantile((1 - o.confidence) / 2);
  fit.ci_hi = quantile((1 + o.confidence) / 2);
  fit.confidence = o.confidence;
  fit.resamples = o.resamples;
  return fit;
}

}  // namespace gs
