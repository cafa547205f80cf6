#pragma once
// Conservative occlusion culling of spheres on the CPU. Spheres are offered nearest first; one
// whose whole screen footprint lies behind spheres already kept is dropped. A dense 3D gas seen
// whole shows only its outer layers, a few per cent of its particles, so this saves most of
// llvmpipe's per-primitive cost. Dropping is exact, never a guess: the picture does not change.
#include <Eigen/Core>
#include <vector>

namespace gs::render {

// A sphere as the picture sees it, in pixels (y down) and depths along the line of sight.
struct SphereFootprint {
  double x0, x1, y0, y1;  // bounding box of everything it can touch, antialiased rim included
  double cx, cy, inner;   // a disc inside its silhouette (its central cross-section's image)
  double z_near;          // depth of its nearest point
  double z_inner;         // its surface over the inner disc is no farther than this
};

// Footprint of a sphere at view-space centre c (eye at the origin looking down -z) with radius
// r, for focal lengths fx, fy in pixels and a width x height picture. Exact bounding box of the
// perspective ellipse (tangent lines in the xz and yz planes), plus a pixel.
SphereFootprint sphere_footprint(const Eigen::Vector3d& c, double r, double fx, double fy,
                                 int width, int height);

class OcclusionBuffer {
 public:
  // One depth per pixel of a width x height picture, all "nothing in front" (+inf).
  void reset(int width, int height);
  // False if every pixel of the footprint is already covered by something nearer than z_near;
  // otherwise records the pixels wholly inside the inner disc at z_inner and returns true.
  bool test_and_insert(const SphereFootprint& f);

 private:
  void insert(const SphereFootprint& f);
  int w_ = 0, h_ = 0;
  std::vector<float> depth_;
};

}  // namespace gs::render
