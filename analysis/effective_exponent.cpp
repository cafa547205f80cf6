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

namespace {

// How far a window fails the rule (<= 0: it passes), with the numbers the note quotes.
struct Verdict {
  double drift, drift_error, curvature, curvature_error;
  bool piece_worst = false;  // a piece's mean fails by most: it and its error
  double piece = 0, piece_error = 0;
  bool reference_worst = false;  // the distance from the last decade's slope fails by most
  double reference = 0, reference_error = 0;
  double excess;
};

// The plateau rule (effective_exponent.h) over one slope band: the usable samples, prefix sums
// of the slope and of every resampled slope, and the judgement of a window.
class PlateauSearch {
 public:
  PlateauSearch(const SlopeBand& band, const PlateauOptions& o) : band_(band), o_(o) {
    const auto& t = band.t;
    const std::size_t n = t.size();
    usable_.resize(n);
    x_.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      usable_[i] = t[i] > 0 && t[i] >= o.t_min && t[i] <= o.t_max &&
                   std::isfinite(band.slope[i]) && std::isfinite(band.lo[i]) &&
                   std::isfinite(band.hi[i]);
      x_[i] = t[i] > 0 ? std::log(t[i]) : 0;
      if (usable_[i]) first_ = std::min(first_, i), last_ = i, any_ = true;
    }
    seg_.assign(n, 0);
    for (std::size_t i = 0; i < n; ++i) seg_[i] = !usable_[i] ? i + 1 : (i > 0 ? seg_[i - 1] : 0);
    mean_prefix_ = prefix_of(band.slope, usable_);
    for (const auto& d : band.draws) draw_prefix_.push_back(prefix_of(d, usable_));
    dd_.resize(draw_prefix_.size());
    need_ = o.min_decades * std::numbers::ln10 * (1 - 1e-9);
    piece_ = o.piece_decades * std::numbers::ln10 * (1 - 1e-9);
    if (!any_) return;
    for (std::size_t m = 0; m <= std::size_t((x_[last_] - x_[first_]) / piece_); ++m)
      z_of_pieces_.push_back(m > 3 ? bonferroni_z(o.z, m) : o.z);
    if (o.reference_decades > 0) {
      ref_lo_ = last_;
      while (ref_lo_ > seg_[last_] &&
             x_[last_] - x_[ref_lo_ - 1] <= o.reference_decades * std::numbers::ln10 * (1 + 1e-9))
        --ref_lo_;
    }
  }

  bool any() const { return any_; }
  std::size_t first() const { return first_; }
  std::size_t last() const { return last_; }
  double x(std::size_t i) const { return x_[i]; }
  double t(std::size_t i) const { return band_.t[i]; }
  bool usable(std::size_t i) const { return usable_[i]; }
  std::size_t segment_start(std::size_t i) const { return seg_[i]; }
  bool long_enough(std::size_t a, std::size_t b) const { return x_[b] - x_[a] >= need_; }
  double mean_slope(std::size_t a, std::size_t b) const {
    return Thirds::mean(mean_prefix_, a, b + 1);
  }
  // The mean ln t over the samples [lo, hi).
  double mean_x(std::size_t lo, std::size_t hi) const {
    double sum = 0;
    for (std::size_t i = lo; i < hi; ++i) sum += x_[i];
    return sum / double(hi - lo);
  }
  double mean_slope_error(std::size_t a, std::size_t b) {
    return spread_of([&](const auto& p) { return Thirds::mean(p, a, b + 1); });
  }

  // The thirds of [a, b], or false when one of them holds no sample.
  bool thirds(std::size_t a, std::size_t b, Thirds& w) const {
    const double c1 = x_[a] + (x_[b] - x_[a]) / 3, c2 = x_[a] + 2 * (x_[b] - x_[a]) / 3;
    const auto i1 =
        std::size_t(std::lower_bound(x_.begin() + long(a), x_.begin() + long(b), c1) - x_.begin());
    const auto i2 = std::size_t(
        std::lower_bound(x_.begin() + long(i1), x_.begin() + long(b), c2) - x_.begin());
    w = {a, i1, i2, b};
    return i1 > a && i2 > i1 && b >= i2;
  }

  Verdict judge(const Thirds& w) {
    Verdict v{};
    v.drift = w.drift(mean_prefix_);
    v.curvature = w.curvature(mean_prefix_);
    v.drift_error = spread_of([&](const auto& p) { return w.drift(p); });
    v.curvature_error = spread_of([&](const auto& p) { return w.curvature(p); });
    v.excess = std::max(excess(v.drift, v.drift_error, o_.z), excess(v.curvature,
                                                                     v.curvature_error, o_.z));
    judge_pieces(w, v);
    judge_reference(w, v);
    return v;
  }

 private:
  // How far |value| lies beyond z sigma + floor, or beyond the absolute bound.
  double excess(double value, double error, double z) const {
    return std::max(std::fabs(value) - (z * error + o_.floor), std::fabs(value) - o_.max_drift);
  }

  template <class F>
  double spread_of(F f) {
    for (std::size_t k = 0; k < draw_prefix_.size(); ++k) dd_[k] = f(draw_prefix_[k]);
    return spread(dd_);
  }

  // Thirds average a wave of about a third's length away: a window of four decades whose slope
  // swings by +-0.025 passed with equal thirds (3D R_t of r = 0.95). So the window is also cut
  // into pieces of piece_decades or more, and each piece's mean must lie within z_m sigma +
  // floor of the window's, z_m the two-sided normal quantile at the level of z shared by the m
  // pieces (Bonferroni), so that the m of them together reject a flat slope's window no more
  // often than one test at z does.
  void judge_pieces(const Thirds& w, Verdict& v) {
    const auto m = std::max<std::size_t>(3, std::size_t((x_[w.b] - x_[w.a]) / piece_));
    if (m <= 3) return;
    const double zm = z_of_pieces_[m];
    // Piece j holds the samples [lo, hi); the last ends with the window.
    for (std::size_t j = 0, lo = w.a, hi; j < m; ++j, lo = hi) {
      const double end = x_[w.a] + (x_[w.b] - x_[w.a]) * double(j + 1) / double(m);
      hi = j + 1 == m ? w.b + 1
                      : std::size_t(std::lower_bound(x_.begin() + long(lo),
                                                     x_.begin() + long(w.b) + 1, end) -
                                    x_.begin());
      if (hi <= lo) continue;  // no sample in the piece: the grid is coarser than it
      const auto deviation = [&](const std::vector<double>& prefix) {
        return Thirds::mean(prefix, lo, hi) - Thirds::mean(prefix, w.a, w.b + 1);
      };
      const double dev = deviation(mean_prefix_);
      const double err = spread_of(deviation);
      const double e = std::fabs(dev) - (zm * err + o_.floor);
      if (e > v.excess) v = with_worst(v, e, true, dev, err);
    }
  }

  void judge_reference(const Thirds& w, Verdict& v) {
    if (o_.reference_decades <= 0 || ref_lo_ >= last_) return;
    const auto deviation = [&](const std::vector<double>& prefix) {
      return Thirds::mean(prefix, w.a, w.b + 1) - Thirds::mean(prefix, ref_lo_, last_ + 1);
    };
    const double dev = deviation(mean_prefix_);
    const double err = spread_of(deviation);
    const double e = excess(dev, err, o_.z);
    if (e > v.excess) v = with_worst(v, e, false, dev, err);
  }

  static Verdict with_worst(Verdict v, double excess, bool piece, double dev, double err) {
    v.excess = excess;
    v.piece_worst = piece;
    v.reference_worst = !piece;
    (piece ? v.piece : v.reference) = dev;
    (piece ? v.piece_error : v.reference_error) = err;
    return v;
  }

  const SlopeBand& band_;
  const PlateauOptions& o_;
  std::vector<bool> usable_;
  std::vector<double> x_;
  std::vector<std::size_t> seg_;  // seg_[i]: the first sample of the usable run that ends at i
  std::vector<double> mean_prefix_;
  std::vector<std::vector<double>> draw_prefix_;
  std::vector<double> dd_;
  std::vector<double> z_of_pieces_;
  double need_ = 0, piece_ = 0;
  std::size_t first_ = std::numeric_limits<std::size_t>::max(), last_ = 0, ref_lo_ = 0;
  bool any_ = false;
};

std::string closest_text(const Verdict& v, const Window& w) {
  std::string s = "closest: [" + short_text(w.t_lo) + ", " + short_text(w.t_hi) + "], drift " +
                   short_text(v.drift) + " +- " + short_text(v.drift_error) + ", curvature " +
                   short_text(v.curvature) + " +- " + short_text(v.curvature_error);
  if (v.piece_worst)
    s += ", a piece off the mean by " + short_text(v.piece) + " +- " + short_text(v.piece_error);
  if (v.reference_worst)
    s += ", off the last decade's slope by " + short_text(v.reference) + " +- " +
         short_text(v.reference_error);
  return s + ")";
}

std::string no_plateau_note(const PlateauSearch& s, const PlateauOptions& o, bool any_window,
                            const Verdict& closest, const Window& closest_window) {
  if (!s.any()) return "no plateau within the run: no usable local slope";
  if (!any_window)
    return "no plateau within the run: the usable local slope spans less than " +
           short_text(o.min_decades) + " decades";
  const std::size_t f = s.first(), l = s.last();
  return "no plateau within the run: the local slope goes from " +
         short_text(s.mean_slope(f, f)) + " at t = " + short_text(s.t(f)) + " to " +
         short_text(s.mean_slope(l, l)) + " at t = " + short_text(s.t(l)) + "; no window of " +
         short_text(o.min_decades) + " decades or more passes the rule (" +
         closest_text(closest, closest_window);
}

std::string transient_note(const PlateauSearch& s, std::size_t a, std::size_t b) {
  const std::size_t l = s.last();
  return "no plateau within the run: the latest window that passes the rule, [" +
         short_text(s.t(a)) + ", " + short_text(s.t(b)) + "] (slope " +
         short_text(s.mean_slope(a, b)) + "), ends " +
         short_text((s.x(l) - s.x(b)) / std::numbers::ln10) +
         " decades before the last usable sample (t = " + short_text(s.t(l)) + ", slope " +
         short_text(s.mean_slope(l, l)) + "): a transient the slope leaves, not the asymptotic "
         "regime";
}

}  // namespace

Plateau find_plateau(const SlopeBand& band, const PlateauOptions& o) {
  PlateauSearch s(band, o);
  Plateau p;
  bool any_window = false;
  Verdict closest{};
  Window closest_window;
  closest.excess = std::numeric_limits<double>::infinity();
  // Every passing window whose end lies this close to the last usable sample gives the spread.
  const double gap = std::isfinite(o.max_end_gap_decades) ? o.max_end_gap_decades : 0.3;
  std::vector<double> readings;
  for (std::size_t b = band.t.size(); b-- > 0;) {
    if (!s.usable(b)) continue;
    const bool late = s.any() && s.x(s.last()) - s.x(b) <= gap * std::numbers::ln10 * (1 + 1e-9);
    if (p.found && !late) break;
    for (std::size_t a = s.segment_start(b); a < b && s.long_enough(a, b); ++a) {
      Thirds w{};
      if (!s.thirds(a, b, w)) continue;
      any_window = true;
      const Verdict v = s.judge(w);
      if (v.excess > 0) {
        if (!p.found && v.excess < closest.excess) closest = v, closest_window = {s.t(a), s.t(b)};
        continue;
      }
      if (p.found) {
        readings.push_back(s.mean_slope(a, b));
        continue;
      }
      if (s.x(s.last()) - s.x(b) > o.max_end_gap_decades * std::numbers::ln10) {
        p.note = transient_note(s, a, b);
        return p;
      }
      p.found = true;
      p.window = {s.t(a), s.t(b)};
      p.exponent = s.mean_slope(a, b);
      p.drift = v.drift;
      p.drift_error = v.drift_error;
      p.curvature = v.curvature;
      p.curvature_error = v.curvature_error;
      readings.push_back(p.exponent);
    }
  }
  if (!p.found) {
    p.note = no_plateau_note(s, o, any_window, closest, closest_window);
    return p;
  }
  p.passing_windows = readings.size();
  p.window_spread = spread(readings);
  return p;
}

EndSlope end_slope(const SlopeBand& band, double decades) {
  PlateauOptions o;
  o.min_decades = decades;
  PlateauSearch s(band, o);
  EndSlope e;
  if (!s.any()) return e;
  const std::size_t b = s.last();
  std::size_t a = b;
  while (a > s.segment_start(b) && !s.long_enough(a, b)) --a;
  Thirds w{};
  if (!s.long_enough(a, b) || !s.thirds(a, b, w)) return e;
  const Verdict v = s.judge(w);
  // The thirds' centres, about two thirds of the window apart (exactly so on a fine grid).
  const double apart = (s.mean_x(w.i2, b + 1) - s.mean_x(a, w.i1)) / std::numbers::ln10;
  e.found = true;
  e.window = {s.t(a), s.t(b)};
  e.slope = s.mean_slope(a, b);
  e.slope_error = s.mean_slope_error(a, b);
  e.drift_per_decade = v.drift / apart;
  e.drift_error = v.drift_error / apart;
  return e;
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
