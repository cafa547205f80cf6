#pragma once
// Where the picture looks. 2D: an orthographic window; 3D: a perspective orbit camera around a
// target. Positions are made relative to `origin` in double before they become floats, so
// unwrapped coordinates far from 0 keep their precision on the GPU.
#include <cmath>
#include <optional>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "render/view.h"

namespace gs::render {

struct Camera {
  bool perspective = false;
  int width = 0, height = 0;
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();  // picture centre (2D) or orbit target (3D)
  // 2D: half the visible width and height in world units.
  double half_w = 1, half_h = 1;
  // 3D: view matrix (world minus origin -> eye space, eye looking down -z) and projection.
  Eigen::Matrix4d view = Eigen::Matrix4d::Identity(), proj = Eigen::Matrix4d::Identity();
  Eigen::Vector3d forward = -Eigen::Vector3d::UnitZ();  // unit line of sight
  double near = 0.1, far = 100;
  double distance = 0;  // 3D: from the eye to the origin
  double tan_half_x = 1, tan_half_y = 1;
  double slab = 0;
  bool clip = false;
  Eigen::Vector3d cut_origin = Eigen::Vector3d::Zero();  // the slab or clip plane's point

  double pixels_per_unit() const { return width / (2 * half_w); }
  // Pixels per world unit as a disc is drawn: 2D everywhere, 3D at the orbit centre's distance.
  double magnification() const {
    return perspective ? height / (2 * distance * tan_half_y) : pixels_per_unit();
  }
  // False if a disc or sphere of radius r at world point p cannot show in the picture.
  bool visible(const Eigen::Vector3d& p, double r) const {
    if (perspective) return visible_3d(p, r);
    // Inline: a 2D frame asks this of every particle.
    const Eigen::Vector3d d = p - origin;
    return std::abs(d.x()) <= half_w + r && std::abs(d.y()) <= half_h + r;
  }
  bool visible_3d(const Eigen::Vector3d& p, double r) const;
  // Where a world point lands in the picture (pixels, x right, y down); nullopt behind the eye.
  std::optional<Eigen::Vector2d> to_pixel(const Eigen::Vector3d& p) const;
};

// `fit` is the box to frame (fitted particles or the periodic box), r_max the largest radius.
Camera make_camera_2d(const Eigen::AlignedBox3d& fit, double r_max, const View& v);
// `centre` and `radius` bound what to frame (particle radii included).
Camera make_camera_3d(const Eigen::Vector3d& centre, double radius, const View& v);

}  // namespace gs::render
