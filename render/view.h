#pragma once
// The picture's size and camera. 2D: fitted to the active particles, the whole box, or an
// explicit centre and zoom. 3D: a perspective orbit camera with an optional slab cut.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <optional>

namespace gs::render {

enum class Framing { Fit, Box };

struct View {
  int width = 1920, height = 1080;
  Framing framing = Framing::Fit;
  double margin = 0.08;  // fraction of the fitted extent left free on each side
  // Box framing: frame this region instead of the snapshot's box (a fixed movie camera over a
  // box that moves frames the union of its boxes).
  std::optional<Eigen::AlignedBox3d> region;
  // Explicit framing: the world point at the picture's centre, and a magnification relative to
  // the fitted (or box) framing.
  std::optional<Eigen::Vector3d> centre;
  double zoom = 1;
  // 2D, with a centre, > 0: show this half width about the centre (the following camera's shot)
  // instead of the fit and zoom. Such a shot is kept clear of the colour bar, legend and inset
  // as fitted stills are: the box of half_width by half_width * height / width is fitted into
  // the part of the picture they leave free, its centre in the middle of that part.
  double half_width = 0;
  // 3D camera, angles in degrees; distance 0 means fitted.
  double azimuth = 30, elevation = 20, distance = 0, fov = 30;
  // 3D: keep only particles whose centres lie within slab/2 of the plane through the centre
  // facing the camera (0: no cut), exposing the shell's cross-section.
  double slab = 0;
  // 3D: drop particles whose centres lie nearer than that plane (a half-space cut).
  bool clip = false;
  // 3D: the point the slab or clip plane goes through (default: the picture's centre), so a
  // fixed camera's cut can follow the front.
  std::optional<Eigen::Vector3d> cut_centre;
};

}  // namespace gs::render
