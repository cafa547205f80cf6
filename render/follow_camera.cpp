#include "render/follow_camera.h"

#include <algorithm>

#include "sim/state_stream.h"

namespace gs::render {

FollowCamera::FollowCamera(int dim, double aspect, double margin, int window)
    : dim_(dim), aspect_(aspect), margin_(margin), window_(std::max(1, window)) {}

Shot FollowCamera::next(const Eigen::AlignedBox3d& front, double radius) {
  centres_.push_back(front.center());
  if (centres_.size() > window_ + 1) centres_.erase(centres_.begin());
  Shot shot;
  for (const auto& c : centres_) shot.centre += c;
  shot.centre /= double(centres_.size());
  // At least 12 diameters across the shorter side, so the first collisions are not a blur.
  const double min_half = dim_ == 3 ? 6 : 6 * std::max(1.0, aspect_);
  const Eigen::Vector3d c = shot.centre;
  const Eigen::Vector3d reach =
      (front.max() - c).cwiseMax(c - front.min()) + Eigen::Vector3d::Constant(0.5);
  // 2D: the stills' margin (View::margin of the front's larger extent on every side), so a
  // movie's frame leaves the same free border around the front as a still of it.
  const double sphere = radius + (front.center() - c).norm() + 0.5;
  const double free = margin_ * 2 * std::max(reach.x(), reach.y());
  const double need = dim_ == 3 ? sphere * (1 + margin_)
                                : std::max(reach.x() + free, (reach.y() + free) * aspect_);
  half_ = std::max({half_, need, min_half});
  shot.half = half_;
  return shot;
}

void FollowCamera::save(StateWriter& out) const {
  out.vector(centres_);
  out.value(half_);
}

void FollowCamera::load(StateReader& in) {
  in.vector(centres_);
  in.expect(centres_.size() <= window_ + 1);
  in.value(half_);
}

}  // namespace gs::render
