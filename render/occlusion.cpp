#include "render/occlusion.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace gs::render {
namespace {

// Screen extent along one axis of a circle of radius r centred at (a, depth) in the plane of
// that axis and the line of sight, seen from the origin: the two tangent lines' slopes.
std::pair<double, double> tangent_extent(double a, double depth, double r) {
  const double len = std::hypot(a, depth);
  const double centre = std::atan2(a, depth), half = std::asin(std::min(1.0, r / len));
  return {std::tan(centre - half), std::tan(centre + half)};
}

}  // namespace

SphereFootprint sphere_footprint(const Eigen::Vector3d& c, double r, double fx, double fy,
                                 int width, int height) {
  const double depth = -c.z();
  SphereFootprint f;
  const auto [xl, xh] = tangent_extent(c.x(), depth, r);
  const auto [yl, yh] = tangent_extent(c.y(), depth, r);
  // The antialiased rim reaches half a pixel beyond the silhouette (a little more off-axis, where
  // the projection stretches pixels); one pixel each side covers it.
  f.x0 = width / 2.0 + xl * fx - 1;
  f.x1 = width / 2.0 + xh * fx + 1;
  f.y0 = height / 2.0 - yh * fy - 1;
  f.y1 = height / 2.0 - yl * fy + 1;
  f.cx = width / 2.0 + c.x() / depth * fx;
  f.cy = height / 2.0 - c.y() / depth * fy;
  // The central cross-section parallel to the picture projects to a circle of this radius; rays
  // through it meet the sphere's front before they reach that plane, at depth <= the centre's.
  f.inner = r / depth * std::min(fx, fy);
  f.z_near = depth - r;
  f.z_inner = depth;
  return f;
}

void OcclusionBuffer::reset(int width, int height) {
  w_ = width, h_ = height;
  depth_.assign(static_cast<std::size_t>(w_) * h_, std::numeric_limits<float>::infinity());
}

bool OcclusionBuffer::test_and_insert(const SphereFootprint& f) {
  // Test the pixels that touch the circle around the footprint's box (it holds the ellipse).
  const double ox = (f.x0 + f.x1) / 2, oy = (f.y0 + f.y1) / 2;
  const double outer = std::max(f.x1 - f.x0, f.y1 - f.y0) / 2;
  const int y0 = std::max(0, static_cast<int>(std::floor(f.y0)));
  const int y1 = std::min(h_ - 1, static_cast<int>(std::floor(f.y1)));
  if (y0 > y1 || f.x1 < 0 || f.x0 >= w_) return true;  // off the picture: the frustum decides
  const auto zn = static_cast<float>(f.z_near);
  for (int py = y0; py <= y1; ++py) {
    const double dy = std::max(0.0, std::max(py - oy, oy - (py + 1)));
    if (dy > outer) continue;
    const double half = std::sqrt(outer * outer - dy * dy);
    const int x0 = std::max(0, static_cast<int>(std::floor(ox - half)));
    const int x1 = std::min(w_ - 1, static_cast<int>(std::floor(ox + half)));
    const float* row = &depth_[static_cast<std::size_t>(py) * w_];
    for (int px = x0; px <= x1; ++px)
      if (!(row[px] < zn)) return insert(f), true;
  }
  return false;
}

void OcclusionBuffer::insert(const SphereFootprint& f) {
  // Pixels wholly inside the inner disc are opaque surface no farther than z_inner.
  const auto zi = static_cast<float>(f.z_inner);
  const int y0 = std::max(0, static_cast<int>(std::ceil(f.cy - f.inner)));
  const int y1 = std::min(h_, static_cast<int>(std::floor(f.cy + f.inner)));  // exclusive
  for (int py = y0; py < y1; ++py) {
    const double dy = std::max(std::abs(py - f.cy), std::abs(py + 1 - f.cy));
    if (dy >= f.inner) continue;
    const double half = std::sqrt(f.inner * f.inner - dy * dy);
    const int x0 = std::max(0, static_cast<int>(std::ceil(f.cx - half)));
    const int x1 = std::min(w_, static_cast<int>(std::floor(f.cx + half)));  // exclusive
    float* row = &depth_[static_cast<std::size_t>(py) * w_];
    for (int px = x0; px < x1; ++px) row[px] = std::min(row[px], zi);
  }
}

}  // namespace gs::render
