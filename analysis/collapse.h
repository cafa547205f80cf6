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
#include <span>
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

}  // namespace gs
