#include "render/contrast.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

namespace gs::render {

double edge_contrast(const std::vector<ShadedPoint>& points, int sectors) {
  const double nan = std::nan("");
  if (points.empty() || sectors < 1) return nan;
  double cx = 0, cy = 0;
  for (const auto& p : points) cx += p.x, cy += p.y;
  cx /= double(points.size()), cy /= double(points.size());
  struct Polar {
    double d, t;
  };
  std::vector<std::vector<Polar>> by_sector(static_cast<std::size_t>(sectors));
  for (const auto& p : points) {
    const double a = std::atan2(p.y - cy, p.x - cx) + std::numbers::pi;  // 0..2 pi
    const int k = std::min(sectors - 1, static_cast<int>(a / (2 * std::numbers::pi) * sectors));
    by_sector[k].push_back({std::hypot(p.x - cx, p.y - cy), p.t});
  }
  std::vector<double> diffs;
  for (const auto& sec : by_sector) {
    if (sec.size() < 2) continue;
    double lo = INFINITY, hi = -INFINITY;
    for (const auto& q : sec) lo = std::min(lo, q.d), hi = std::max(hi, q.d);
    const double quarter = (hi - lo) / 4;
    if (!(quarter > 0)) continue;
    double in_sum = 0, out_sum = 0;
    std::size_t in_n = 0, out_n = 0;
    for (const auto& q : sec) {
      if (q.d <= lo + quarter) in_sum += q.t, ++in_n;
      if (q.d >= hi - quarter) out_sum += q.t, ++out_n;
    }
    if (in_n && out_n) diffs.push_back(in_sum / double(in_n) - out_sum / double(out_n));
  }
  if (2 * diffs.size() < static_cast<std::size_t>(sectors)) return nan;
  const auto mid = diffs.begin() + static_cast<std::ptrdiff_t>(diffs.size() / 2);
  std::nth_element(diffs.begin(), mid, diffs.end());
  if (diffs.size() % 2) return *mid;
  return 0.5 * (*mid + *std::max_element(diffs.begin(), mid));
}

std::vector<ShadedPoint> shaded_pixels(const Image& img, const Colormap& cmap,
                                       const std::vector<Rect>& exclude, double tolerance) {
  std::array<Rgb8, 256> table;
  for (int k = 0; k < 256; ++k) table[k] = cmap.at8(k / 255.0);
  const double tol2 = tolerance * tolerance;
  std::vector<ShadedPoint> out;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      bool skip = false;
      for (const Rect& r : exclude) skip |= x >= r.x0 && x < r.x1 && y >= r.y0 && y < r.y1;
      if (skip) continue;
      const std::uint8_t* p = img.pixel(x, y);
      double best = INFINITY;
      int at = 0;
      for (int k = 0; k < 256; ++k) {
        double d2 = 0;
        for (int c = 0; c < 3; ++c) {
          const double d = double(p[c]) - table[k][c];
          d2 += d * d;
        }
        if (d2 < best) best = d2, at = k;
      }
      if (best <= tol2) out.push_back({x + 0.5, y + 0.5, at / 255.0});
    }
  return out;
}

}  // namespace gs::render
