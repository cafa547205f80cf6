#pragma once
// How well scaled distributions collapse onto one curve (the paper's Figs. 4 and 5:
// t^alpha P(R,t) against R t^-alpha, t^(alpha-1) P(v,t) against v t^(1-alpha)).
//
// Collapse quality Q: the curves are interpolated linearly on a common uniform grid spanning the
// range all of them cover; Q is the mean over the grid of the variance between curves, divided
// by the variance along the grid of their mean curve:
//   Q = < (1/K) sum_k (y_k(x) - ybar(x))^2 >_x / < (ybar(x) - <ybar>_x)^2 >_x.
// Q = 0 for a perfect collapse; curves that do not overlap at all give Q of order 1. Statistical
// noise of the histograms sets a floor ~ (noise variance) / (signal variance).
#include <cstdint>
#include <limits>
#include <span>
#include <string>
#include <vector>

#include "sim/histogram.h"

namespace gs {

struct Curve {
  std::vector<double> x;  // increasing
  std::vector<double> y;
};

// Bin centres and densities of a histogram.
Curve curve_of(const Histogram& h);

// UserError if fewer than two curves, a curve has fewer than two points or non-increasing x, the
// curves share no range, or the mean curve is flat (nothing to compare against).
double collapse_quality(std::span<const Curve> curves, int grid_points = 200);

// The alpha that collapses best, and its interval. A test of the theory's alpha that can fail:
// Q at that alpha is below any fixed tolerance for a range of alpha (Q(1/4) = 0.024 for 2D P(R)
// made with 1/3), so the verdict is whether the theory's alpha lies inside the interval of the
// best-collapsing alpha, not whether Q is small.
//   best: the alpha of the grid [lo, hi] (step `step`) with the smallest misfit of the mean
//   distributions: chi^2 per point of the scaled curves against their mean, with the bins'
//   standard errors (Q where a bin has none; Q's denominator changes with the common range and
//   so with alpha, which biases its minimum); an argmin on the edge of the grid is no minimum
//   ("at the edge of the scan"). q_best is Q at the best alpha.
//   Interval: percentile interval of the best alpha over `resamples` parametric resamples, each
//   bin of each snapshot drawn from a normal of its mean and standard error over realisations
//   (the per-realisation histograms are not kept; bins taken independent).
struct CollapseSnapshot {
  double t = 0;
  Histogram mean;
  std::vector<double> sem;  // per bin; empty: no noise (then the interval is the point)
};
enum class CollapseVariable { Radius, Speed };  // R t^-alpha or v t^(1-alpha)
struct CollapseScanOptions {
  double lo = 0.1, hi = 0.6, step = 0.0025;
  int resamples = 200;
  double confidence = 0.95;
  std::uint64_t seed = 1, key = 0;
};
struct CollapseAlpha {
  double best = std::numeric_limits<double>::quiet_NaN();
  double q_best = std::numeric_limits<double>::quiet_NaN();
  double ci_lo = std::numeric_limits<double>::quiet_NaN();
  double ci_hi = std::numeric_limits<double>::quiet_NaN();
  std::string note;  // why there is no best alpha
  bool contains(double alpha) const { return ci_lo <= alpha && alpha <= ci_hi; }
};
// UserError if fewer than two snapshots or an empty scan.
CollapseAlpha best_collapse_alpha(std::span<const CollapseSnapshot> snapshots,
                                  CollapseVariable variable, const CollapseScanOptions& options);

}  // namespace gs
