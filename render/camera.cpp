#include "render/camera.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace gs::render {

bool Camera::visible_3d(const Eigen::Vector3d& p, double r) const {
  const Eigen::Vector3d d = p - origin;
  const double cut = (p - cut_origin).dot(forward);
  if (slab > 0 && std::abs(cut) > slab / 2) return false;
  if (clip && cut < 0) return false;
  const Eigen::Vector4d e = view * Eigen::Vector4d(d.x(), d.y(), d.z(), 1);
  const double depth = -e.z();
  if (depth - r > far || depth + r < near || e.head<3>().norm() <= r) return false;
  // Inward normals of the four side planes through the eye: (-+1, 0, -t) / sqrt(1 + t^2).
  const double nx = 1 / std::sqrt(1 + tan_half_x * tan_half_x);
  const double ny = 1 / std::sqrt(1 + tan_half_y * tan_half_y);
  if ((-std::abs(e.x()) + depth * tan_half_x) * nx < -r) return false;
  if ((-std::abs(e.y()) + depth * tan_half_y) * ny < -r) return false;
  return true;
}

std::optional<Eigen::Vector2d> Camera::to_pixel(const Eigen::Vector3d& p) const {
  const Eigen::Vector3d d = p - origin;
  if (!perspective)
    return Eigen::Vector2d(width / 2.0 + d.x() * pixels_per_unit(),
                           height / 2.0 - d.y() * pixels_per_unit());
  const Eigen::Vector4d e = view * Eigen::Vector4d(d.x(), d.y(), d.z(), 1);
  const double depth = -e.z();
  if (depth < near) return std::nullopt;
  return Eigen::Vector2d(width / 2.0 + width / (2 * tan_half_x) * e.x() / depth,
                         height / 2.0 - height / (2 * tan_half_y) * e.y() / depth);
}

Camera make_camera_2d(const Eigen::AlignedBox3d& fit, double r_max, const View& v) {
  Camera c;
  c.width = v.width, c.height = v.height;
  const double aspect = double(v.width) / v.height;
  const Eigen::Vector3d size = fit.isEmpty() ? Eigen::Vector3d(1, 1, 0) : fit.sizes().eval();
  const double pad = v.margin * std::max(size.x(), size.y()) + r_max;
  c.half_w = std::max(size.x() / 2 + pad, (size.y() / 2 + pad) * aspect) / v.zoom;
  c.half_w = std::max(c.half_w, 1e-6);
  c.half_h = c.half_w / aspect;
  c.origin = v.centre ? *v.centre : fit.isEmpty() ? Eigen::Vector3d::Zero() : fit.center().eval();
  c.origin.z() = 0;
  return c;
}

Camera make_camera_3d(const Eigen::Vector3d& centre, double radius, const View& v) {
  Camera c;
  c.perspective = true;
  c.width = v.width, c.height = v.height;
  c.slab = v.slab;
  c.clip = v.clip;
  const double aspect = double(v.width) / v.height;
  const double deg = std::numbers::pi / 180;
  c.tan_half_y = std::tan(v.fov * deg / 2);
  c.tan_half_x = c.tan_half_y * aspect;
  c.origin = v.centre ? *v.centre : centre;
  c.cut_origin = v.cut_centre ? *v.cut_centre : c.origin;
  radius = std::max(radius + (c.origin - centre).norm(), 1e-6);
  const double half = std::atan(std::min(c.tan_half_x, c.tan_half_y));
  double dist = v.distance > 0 ? v.distance : radius * (1 + v.margin) / std::sin(half) / v.zoom;
  c.distance = dist;
  const double az = v.azimuth * deg, el = v.elevation * deg;
  // World z is up; azimuth turns about it, elevation lifts the eye above the xy plane.
  const Eigen::Vector3d eye = dist * Eigen::Vector3d(std::cos(el) * std::cos(az),
                                                     std::cos(el) * std::sin(az), std::sin(el));
  c.forward = -eye.normalized();
  Eigen::Vector3d up = Eigen::Vector3d::UnitZ();
  if (std::abs(c.forward.dot(up)) > 0.999) up = Eigen::Vector3d::UnitY();
  const Eigen::Vector3d right = c.forward.cross(up).normalized();
  const Eigen::Vector3d cam_up = right.cross(c.forward);
  c.view.setIdentity();
  c.view.block<1, 3>(0, 0) = right.transpose();
  c.view.block<1, 3>(1, 0) = cam_up.transpose();
  c.view.block<1, 3>(2, 0) = -c.forward.transpose();
  c.view.block<3, 1>(0, 3) = -(c.view.block<3, 3>(0, 0) * eye);
  const double reach = v.slab > 0 ? std::min(radius, v.slab / 2 + 1) : v.clip ? 1.0 : radius;
  const double shift = v.slab > 0 || v.clip ? (c.cut_origin - c.origin).dot(c.forward) : 0.0;
  c.near = std::max(dist + shift - reach - 1, dist * 1e-3);
  c.far = dist + radius + 1;
  c.proj.setZero();
  c.proj(0, 0) = 1 / c.tan_half_x;
  c.proj(1, 1) = 1 / c.tan_half_y;
  c.proj(2, 2) = -(c.far + c.near) / (c.far - c.near);
  c.proj(2, 3) = -2 * c.far * c.near / (c.far - c.near);
  c.proj(3, 2) = -1;
  // Pixels per world unit at the target's distance, for scale bars.
  c.half_w = dist * c.tan_half_x;
  c.half_h = dist * c.tan_half_y;
  return c;
}

}  // namespace gs::render
