#include "analysis/effective_exponent.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
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
    auto s = local_slope(t, mean_of(realisations, draw, n), o.half_width_decades);
    for (std::size_t i = 0; i < n; ++i)
      if (std::isfinite(s[i])) per_point[i].push_back(s[i]);
    b.draws.push_back(std::move(s));
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

namespace {

// Means of one slope series over the thirds of a window, from its prefix sums.
struct Thirds {
  std::size_t a, i1, i2, b;  // [a, i1), [i1, i2), [i2, b]
  double drift(const std::vector<double>& prefix) const {
    return mean(prefix, i2, b + 1) - mean(prefix, a, i1);
  }
  double curvature(const std::vector<double>& prefix) const {
    return mean(prefix, i1, i2) - 0.5 * (mean(prefix, a, i1) + mean(prefix, i2, b + 1));
  }
  static double mean(const std::vector<double>& prefix, std::size_t lo, std::size_t hi) {
    return (prefix[hi] - prefix[lo]) / double(hi - lo);
  }
};

// Prefix sums of a slope series over the usable samples (others count 0; windows never hold
// them).
std::vector<double> prefix_of(const std::vector<double>& s, const std::vector<bool>& usable) {
  std::vector<double> p(s.size() + 1, 0.0);
  for (std::size_t i = 0; i < s.size(); ++i) p[i + 1] = p[i] + (usable[i] ? s[i] : 0.0);
  return p;
}

// The z of m two-sided tests whose joint level is that of one test at z: P(|N| > z_m) = P(|N| > z)
// / m, solved by bisection (erfc is monotone).
double bonferroni_z(double z, std::size_t m) {
  const double tail = std::erfc(z / std::numbers::sqrt2) / double(m);
  double lo = z, hi = z + 10;
  for (int k = 0; k < 100; ++k) {
    const double mid = 0.5 * (lo + hi);
    (std::erfc(mid / std::numbers::sqrt2) > tail ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

double spread(std::span<const double> v) {
  if (v.size() < 2) return 0;
  double m = 0;
  for (double x : v) m += x;
  m /= double(v.size());
  double q = 0;
  for (double x : v) q += (x - m) * (x - m);
  return std::sqrt(q / double(v.size() - 1));
}

}  // namespace

Plateau find_plateau(const SlopeBand& band, const PlateauOptions& o) {
  const auto& t = band.t;
  const std::size_t n = t.size();
  std::vector<bool> usable(n);
  std::vector<double> x(n);
  for (std::size_t i = 0; i < n; ++i) {
    usable[i] = t[i] > 0 && t[i] >= o.t_min && t[i] <= o.t_max && std::isfinite(band.slope[i]) &&
                std::isfinite(band.lo[i]) && std::isfinite(band.hi[i]);
    x[i] = t[i] > 0 ? std::log(t[i]) : 0;
  }
  // seg[i]: the first sample of the run of usable samples that ends at i.
  std::vector<std::size_t> seg(n, 0);
  for (std::size_t i = 0; i < n; ++i) seg[i] = !usable[i] ? i + 1 : (i > 0 ? seg[i - 1] : 0);
  const auto mean_prefix = prefix_of(band.slope, usable);
  std::vector<std::vector<double>> draw_prefix;
  for (const auto& d : band.draws) draw_prefix.push_back(prefix_of(d, usable));
  const double need = o.min_decades * std::numbers::ln10 * (1 - 1e-9);

  struct Verdict {
    double drift, drift_error, curvature, curvature_error;
    bool piece_worst = false;  // a piece's mean (see below) fails by most: it and its error
    double piece = 0, piece_error = 0;
    double excess;
  };
  std::vector<double> dd(draw_prefix.size()), kk(draw_prefix.size());
  // z_m of the pieces' test below, for every m a window of usable samples can have.
  double x_lo = INFINITY, x_hi = -INFINITY;
  for (std::size_t i = 0; i < n; ++i)
    if (usable[i]) x_lo = std::min(x_lo, x[i]), x_hi = std::max(x_hi, x[i]);
  std::vector<double> z_of_pieces;
  for (std::size_t m = 0; x_lo < x_hi && m <= std::size_t((x_hi - x_lo) / need); ++m)
    z_of_pieces.push_back(m > 3 ? bonferroni_z(o.z, m) : o.z);
  auto judge = [&](const Thirds& w) {
    Verdict v{};
    v.drift = w.drift(mean_prefix);
    v.curvature = w.curvature(mean_prefix);
    for (std::size_t k = 0; k < draw_prefix.size(); ++k) {
      dd[k] = w.drift(draw_prefix[k]);
      kk[k] = w.curvature(draw_prefix[k]);
    }
    v.drift_error = spread(dd);
    v.curvature_error = spread(kk);
    v.excess = std::max(std::fabs(v.drift) - (o.z * v.drift_error + o.floor),
                        std::fabs(v.curvature) - (o.z * v.curvature_error + o.floor));
    // Thirds average a wave of about a third's length away: a window of four decades whose slope
    // swings by +-0.025 passed with equal thirds (3D R_t of r = 0.95). So the window is
    // also cut into pieces of min_decades or more, and each piece's mean must lie within
    // z_m sigma + floor of the window's, z_m the two-sided normal quantile at the level of z
    // shared by the m pieces (Bonferroni), so that the m of them together reject a flat slope's
    // window no more often than one test at z does.
    const auto m = std::max<std::size_t>(3, std::size_t((x[w.b] - x[w.a]) / need));
    if (m > 3) {
      const double zm = z_of_pieces[m];
      // Piece j holds the samples [lo, hi); the last ends with the window.
      for (std::size_t j = 0, lo = w.a, hi; j < m; ++j, lo = hi) {
        const double end = x[w.a] + (x[w.b] - x[w.a]) * double(j + 1) / double(m);
        hi = j + 1 == m ? w.b + 1
                        : std::size_t(std::lower_bound(x.begin() + long(lo),
                                                       x.begin() + long(w.b) + 1, end) -
                                      x.begin());
        if (hi <= lo) continue;  // no sample in the piece: the grid is coarser than it
        const auto deviation = [&](const std::vector<double>& prefix) {
          return Thirds::mean(prefix, lo, hi) - Thirds::mean(prefix, w.a, w.b + 1);
        };
        const double dev = deviation(mean_prefix);
        for (std::size_t k = 0; k < draw_prefix.size(); ++k) dd[k] = deviation(draw_prefix[k]);
        const double err = spread(dd);
        const double excess = std::fabs(dev) - (zm * err + o.floor);
        if (excess > v.excess) {
          v.excess = excess;
          v.piece_worst = true;
          v.piece = dev;
          v.piece_error = err;
        }
      }
    }
    return v;
  };

  std::size_t last_usable = 0;
  for (std::size_t i = 0; i < n; ++i)
    if (usable[i]) last_usable = i;
  Plateau p;
  bool any_window = false;
  Verdict closest{};
  Window closest_window;
  closest.excess = std::numeric_limits<double>::infinity();
  for (std::size_t b = n; b-- > 0;) {
    if (!usable[b]) continue;
    for (std::size_t a = seg[b]; a < b && x[b] - x[a] >= need; ++a) {
      const double c1 = x[a] + (x[b] - x[a]) / 3, c2 = x[a] + 2 * (x[b] - x[a]) / 3;
      const auto i1 = std::size_t(std::lower_bound(x.begin() + long(a), x.begin() + long(b), c1) -
                                  x.begin());
      const auto i2 = std::size_t(std::lower_bound(x.begin() + long(i1), x.begin() + long(b), c2) -
                                  x.begin());
      if (i1 <= a || i2 <= i1 || b < i2) continue;  // a third without a sample
      any_window = true;
      const Thirds w{a, i1, i2, b};
      const Verdict v = judge(w);
      if (v.excess <= 0 && x[last_usable] - x[b] > o.max_end_gap_decades * std::numbers::ln10) {
        p.note = "no plateau within the run: the latest window that passes the rule, [" +
                 short_text(t[a]) + ", " + short_text(t[b]) + "] (slope " +
                 short_text(Thirds::mean(mean_prefix, a, b + 1)) + "), ends " +
                 short_text((x[last_usable] - x[b]) / std::numbers::ln10) +
                 " decades before the last usable sample (t = " + short_text(t[last_usable]) +
                 ", slope " + short_text(band.slope[last_usable]) +
                 "): a transient the slope leaves, not the asymptotic regime";
        return p;
      }
      if (v.excess <= 0) {
        p.found = true;
        p.window = {t[a], t[b]};
        p.exponent = Thirds::mean(mean_prefix, a, b + 1);
        p.drift = v.drift;
        p.drift_error = v.drift_error;
        p.curvature = v.curvature;
        p.curvature_error = v.curvature_error;
        return p;
      }
      if (v.excess < closest.excess) {
        closest = v;
        closest_window = {t[a], t[b]};
      }
    }
  }
  // Say where the slope goes instead: its value at the first and last usable samples, and the
  // window that came closest.
  std::size_t first = n, last = n;
  for (std::size_t i = 0; i < n; ++i)
    if (usable[i]) {
      if (first == n) first = i;
      last = i;
    }
  if (first == n) {
    p.note = "no plateau within the run: no usable local slope";
  } else if (!any_window) {
    p.note = "no plateau within the run: the usable local slope spans less than " +
             short_text(o.min_decades) + " decades";
  } else {
    p.note = "no plateau within the run: the local slope goes from " +
             short_text(band.slope[first]) + " at t = " + short_text(t[first]) + " to " +
             short_text(band.slope[last]) + " at t = " + short_text(t[last]) + "; no window of " +
             short_text(o.min_decades) + " decades or more is flat within its error (closest: [" +
             short_text(closest_window.t_lo) + ", " + short_text(closest_window.t_hi) +
             "], drift " + short_text(closest.drift) + " +- " + short_text(closest.drift_error) +
             ", curvature " + short_text(closest.curvature) + " +- " +
             short_text(closest.curvature_error) +
             (closest.piece_worst ? ", a piece off the mean by " + short_text(closest.piece) +
                                            " +- " + short_text(closest.piece_error)
                                      : std::string()) +
             ")";
  }
  return p;
}

namespace {

struct SlopeModel {
  double b, k, omega, residual;
};

// s = b + k t^-omega by least squares over the samples `use`, for each omega of the grid.
SlopeModel fit_slope_model(const std::vector<double>& t, const std::vector<double>& s,
                           const std::vector<std::size_t>& use) {
  SlopeModel best{0, 0, 0, std::numeric_limits<double>::infinity()};
  for (int w = 2; w <= 40; ++w) {
    const double omega = 0.05 * w;
    double n = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
    for (std::size_t i : use) {
      const double x = std::pow(t[i], -omega);
      n += 1;
      sx += x;
      sy += s[i];
      sxx += x * x;
      sxy += x * s[i];
    }
    const double det = n * sxx - sx * sx;
    if (!(det > 0)) continue;
    const double k = (n * sxy - sx * sy) / det, b = (sy - k * sx) / n;
    double res = 0;
    for (std::size_t i : use) {
      const double e = s[i] - b - k * std::pow(t[i], -omega);
      res += e * e;
    }
    if (res < best.residual) best = {b, k, omega, res};
  }
  return best;
}

}  // namespace

CorrectedExponent corrected_exponent(const SlopeBand& band, double t_lo, double t_hi,
                                     double confidence) {
  CorrectedExponent out;
  std::vector<std::size_t> use;
  for (std::size_t i = 0; i < band.t.size(); ++i)
    if (band.t[i] >= t_lo && band.t[i] <= t_hi && std::isfinite(band.slope[i]) &&
        std::isfinite(band.lo[i]))
      use.push_back(i);
  if (use.size() < 6) {
    out.note = "fewer than 6 usable local slopes";
    return out;
  }
  const SlopeModel m = fit_slope_model(band.t, band.slope, use);
  if (!std::isfinite(m.residual)) {
    out.note = "no fit";
    return out;
  }
  out.found = true;
  out.b = m.b;
  out.k = m.k;
  out.omega = m.omega;
  out.window = {band.t[use.front()], band.t[use.back()]};
  if (m.omega <= 0.1 + 1e-9 || m.omega >= 2 - 1e-9)
    out.note = "omega at the edge of its grid [0.1, 2]";
  std::vector<double> bs;
  for (const auto& d : band.draws) {
    const SlopeModel md = fit_slope_model(band.t, d, use);
    if (std::isfinite(md.residual)) bs.push_back(md.b);
  }
  if (bs.size() >= 10) {
    out.ci_lo = quantile(bs, (1 - confidence) / 2);
    out.ci_hi = quantile(bs, (1 + confidence) / 2);
  }
  return out;
}

}  // namespace gs
