#pragma once
// The following camera of a movie, decided frame by frame from this frame and those before it,
// so that a movie needs no pass ahead to aim it: the centre is the mean of the front's centres
// over the last few frames; the visible size is the running maximum of what each frame needs
// about that centre. The size never shrinks, so the front always fits and the zoom never
// jitters; it eases outward as fast as the front grows.
#include <Eigen/Geometry>
#include <vector>

namespace gs {
class StateWriter;
class StateReader;
}  // namespace gs

namespace gs::render {

struct Shot {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  double half = 1;  // 2D: half the visible width; 3D: radius of the sphere to frame
};

class FollowCamera {
 public:
  // aspect: width / height of the picture; margin: the share left free around the front
  // (View::margin); window: the frames before this one that the centre is averaged over.
  FollowCamera(int dim, double aspect, double margin, int window);
  // front: the box of the particles to keep in view; radius: of the sphere about its centre
  // that holds them (what 3D frames).
  Shot next(const Eigen::AlignedBox3d& front, double radius);

  // What the frames so far taught it, for a movie's checkpoint: a camera loaded from it aims
  // the next frames as this one would.
  void save(StateWriter& out) const;
  // Refuses (as corrupt) a state of another window.
  void load(StateReader& in);

 private:
  int dim_;
  double aspect_, margin_;
  std::size_t window_;
  std::vector<Eigen::Vector3d> centres_;  // the last window_ + 1 fronts' centres
  double half_ = 0;
};

}  // namespace gs::render
