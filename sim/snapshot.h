#pragma once
// The state of a run at one instant, as every consumer downstream of the engine sees it
// (analysis, renderer, extended-XYZ files). Positions are unwrapped across the periodic boundary,
// so a band that straddles the box edge stays in one piece; 1D and 2D snapshots have zeros in the
// unused components.
#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace gs {

// What a snapshot knows of the run that made it; written into the XYZ comment line and the PNG
// text chunks. Hand-written snapshots may lack all but the box and dimension.
struct SnapshotInfo {
  int dim = 3;
  double box = 0;   // side L of the periodic cubic box
  double time = 0;  // simulation time (diameter / v0)
  std::optional<double> density, restitution, cutoff, speed;
  std::optional<std::uint64_t> seed;
};

struct Snapshot {
  SnapshotInfo info;
  std::vector<Eigen::Vector3d> position;  // unwrapped
  std::vector<Eigen::Vector3d> velocity;  // empty if the file had none
  std::vector<double> radius;             // 0.5 for the engine's unit-diameter spheres
  std::vector<std::uint8_t> active;       // 1 once a particle has collided
  std::vector<double> first_collision;    // time of first collision (-1: never); may be empty

  std::size_t size() const { return position.size(); }
  bool has_velocity() const { return !velocity.empty(); }
};

}  // namespace gs
