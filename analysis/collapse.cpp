#include "analysis/collapse.h"

#include <algorithm>
#include <limits>
#include <string>

#include "sim/error.h"

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

}  // namespace gs
