#include "analysis/collapse.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "analysis/quantile.h"
#include "sim/error.h"
#include "sim/observables.h"
#include "sim/rng.h"

namespace gs {

Curve curve_of(const Histogram& h) {
  Curve c;
  for (std::size_t i = 0; i < h.bins(); ++i) {
    c.x.push_back(h.centre(i));
    c.y.push_back(h.values[i]);
  }
  return c;
}

namespace {
double interpolate(const Curve& c, double x) {
  auto it = std::upper_bound(c.x.begin(), c.x.end(), x);
  std::size_t b = std::size_t(it - c.x.begin());
  b = std::clamp<std::size_t>(b, 1, c.x.size() - 1);
  const std::size_t a = b - 1;
  const double f = (x - c.x[a]) / (c.x[b] - c.x[a]);
  return c.y[a] + f * (c.y[b] - c.y[a]);
}
}  // namespace

double collapse_quality(std::span<const Curve> curves, int grid_points) {
  if (curves.size() < 2) throw UserError("collapse quality needs at least two curves");
  if (grid_points < 2) throw UserError("collapse quality needs at least two grid points");
  double lo = -std::numeric_limits<double>::infinity(),
         hi = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < curves.size(); ++k) {
    const Curve& c = curves[k];
    GS_CHECK(c.x.size() == c.y.size());
    if (c.x.size() < 2 || !std::is_sorted(c.x.begin(), c.x.end()) ||
        std::adjacent_find(c.x.begin(), c.x.end()) != c.x.end())
      throw UserError("collapse curve " + std::to_string(k) +
                      " needs at least two points with increasing x");
    lo = std::max(lo, c.x.front());
    hi = std::min(hi, c.x.back());
  }
  if (!(hi > lo)) throw UserError("scaled curves share no range of the scaling variable");
  const auto g = std::size_t(grid_points);
  const double K = double(curves.size());
  std::vector<double> mean(g), y(curves.size());
  double spread = 0;
  for (std::size_t i = 0; i < g; ++i) {
    const double x = lo + (hi - lo) * double(i) / double(g - 1);
    double s = 0;
    for (std::size_t k = 0; k < curves.size(); ++k) s += (y[k] = interpolate(curves[k], x));
    mean[i] = s / K;
    double v = 0;
    for (double yk : y) v += (yk - mean[i]) * (yk - mean[i]);
    spread += v / K;
  }
  double grand = 0;
  for (double m : mean) grand += m;
  grand /= double(g);
  double signal = 0;
  for (double m : mean) signal += (m - grand) * (m - grand);
  if (!(signal > 0)) throw UserError("scaled curves are flat on their common range");
  return spread / signal;
}

namespace {

Histogram scaled(const Histogram& h, double t, double alpha, CollapseVariable v) {
  return v == CollapseVariable::Radius ? scaled_radial_distribution(h, t, alpha)
                                       : scaled_speed_distribution(h, t, alpha);
}

// The misfit the scan minimises: with errors, chi^2 per grid point of the scaled curves against
// their mean, < (1/K) sum_k (y_k - ybar)^2 / s_k^2 >_x (the errors scaled as the densities);
// without, Q. Q's denominator, the variance of the mean curve over the common range, changes
// with alpha as that range does, which biases its minimum; chi^2 has no such term. Infinity
// where the scaled curves cannot be compared.
double quality_at(std::span<const Histogram> hs, std::span<const Histogram> errors,
                  std::span<const double> times, double alpha, CollapseVariable v) {
  std::vector<Curve> cs, es;
  for (std::size_t k = 0; k < hs.size(); ++k) {
    cs.push_back(curve_of(scaled(hs[k], times[k], alpha, v)));
    if (!errors.empty()) es.push_back(curve_of(scaled(errors[k], times[k], alpha, v)));
  }
  try {
    if (errors.empty()) return collapse_quality(cs);
  } catch (const UserError&) {
    return std::numeric_limits<double>::infinity();
  }
  double lo = -std::numeric_limits<double>::infinity(), hi = -lo;
  for (const auto& c : cs) {
    lo = std::max(lo, c.x.front());
    hi = std::min(hi, c.x.back());
  }
  if (!(hi > lo)) return std::numeric_limits<double>::infinity();
  constexpr int kGrid = 200;
  double chi2 = 0;
  std::vector<double> y(cs.size()), e(cs.size());
  for (int i = 0; i < kGrid; ++i) {
    const double x = lo + (hi - lo) * i / (kGrid - 1);
    double m = 0;
    for (std::size_t k = 0; k < cs.size(); ++k) {
      y[k] = interpolate(cs[k], x);
      e[k] = interpolate(es[k], x);
      m += y[k];
    }
    m /= double(cs.size());
    for (std::size_t k = 0; k < cs.size(); ++k)
      chi2 += (y[k] - m) * (y[k] - m) / (e[k] * e[k]) / double(cs.size());
  }
  return chi2 / kGrid;
}

// Index of the grid alpha with the smallest Q; the grid's size when none is finite.
std::size_t argmin_alpha(std::span<const Histogram> hs, std::span<const Histogram> errors,
                         std::span<const double> times, std::span<const double> grid,
                         CollapseVariable v, double* q_min) {
  std::size_t best = grid.size();
  double q = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < grid.size(); ++i) {
    const double qi = quality_at(hs, errors, times, grid[i], v);
    if (qi < q) {
      q = qi;
      best = i;
    }
  }
  if (q_min) *q_min = q;
  return best;
}

}  // namespace

CollapseAlpha best_collapse_alpha(std::span<const CollapseSnapshot> snaps, CollapseVariable v,
                                  const CollapseScanOptions& o) {
  if (snaps.size() < 2) throw UserError("the collapse scan needs at least two snapshot times");
  if (!(o.hi > o.lo) || !(o.step > 0)) throw UserError("the collapse scan needs lo < hi, step > 0");
  std::vector<double> grid;
  for (int i = 0;; ++i) {
    const double a = o.lo + o.step * i;
    if (a > o.hi + 1e-12) break;
    grid.push_back(a);
  }
  std::vector<Histogram> hs, errors;
  std::vector<double> times;
  bool with_errors = true;
  for (const auto& s : snaps) {
    hs.push_back(s.mean);
    times.push_back(s.t);
    Histogram e = s.mean;
    with_errors = with_errors && s.sem.size() == e.values.size();
    for (std::size_t b = 0; b < e.values.size() && b < s.sem.size(); ++b) {
      e.values[b] = s.sem[b];
      with_errors = with_errors && s.sem[b] > 0;
    }
    errors.push_back(std::move(e));
  }
  if (!with_errors) errors.clear();
  CollapseAlpha out;
  const std::size_t i = argmin_alpha(hs, errors, times, grid, v, nullptr);
  if (i < grid.size()) out.q_best = quality_at(hs, {}, times, grid[i], v);
  auto on_edge = [&](std::size_t k) { return k == 0 || k + 1 >= grid.size(); };
  if (i >= grid.size()) {
    out.note = "no alpha of the scan gives comparable scaled curves";
    return out;
  }
  if (on_edge(i)) {
    out.note = "the best collapse lies at the edge of the scan [" + std::to_string(o.lo) + ", " +
               std::to_string(o.hi) + "]: no minimum";
    return out;
  }
  out.best = grid[i];
  Rng rng(o.seed, o.key, Stream::Bootstrap);
  std::vector<double> draws;
  for (int r = 0; r < o.resamples; ++r) {
    std::vector<Histogram> hr = hs;
    for (std::size_t k = 0; k < hr.size(); ++k)
      for (std::size_t b = 0; b < hr[k].values.size() && b < snaps[k].sem.size(); ++b)
        hr[k].values[b] += snaps[k].sem[b] * rng.normal();
    const std::size_t j = argmin_alpha(hr, errors, times, grid, v, nullptr);
    draws.push_back(j < grid.size() ? grid[j] : std::numeric_limits<double>::quiet_NaN());
  }
  std::erase_if(draws, [](double x) { return !std::isfinite(x); });
  if (draws.empty()) {
    out.ci_lo = out.ci_hi = out.best;
    return out;
  }
  std::sort(draws.begin(), draws.end());
  out.ci_lo = std::min(out.best, sorted_quantile(draws, (1 - o.confidence) / 2));
  out.ci_hi = std::max(out.best, sorted_quantile(draws, (1 + o.confidence) / 2));
  if (out.ci_lo <= grid.front() || out.ci_hi >= grid.back())
    out.note = "the interval reaches the edge of the scan: alpha is not pinned";
  return out;
}

}  // namespace gs
