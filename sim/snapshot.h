#pragma once
// The state of a run at one instant, as every consumer downstream of the engine sees it
// (analysis, renderer, snapshot files). Positions are unwrapped across the periodic boundary,
// so a band that straddles the box edge stays in one piece; 1D and 2D snapshots have zeros in the
// unused components. Files of other programs fill what they have (see io/snapshot_file.h).
#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace gs {

// What a snapshot knows of the run that made it; written into the file header and the PNG
// text chunks. Hand-written snapshots may lack all but the dimension.
struct SnapshotInfo {
  int dim = 3;
  // The rectangular periodic box: edge lengths along x, y, z and its lower corner. Edges beyond
  // `dim` are 0; all zero when the file gave no box. Triclinic boxes are refused by the readers.
  Eigen::Vector3d box = Eigen::Vector3d::Zero();
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  double time = 0;                   // simulation time (diameter / v0 for our runs)
  // False when the file gives no time (LAMMPS dumps without ITEM: TIME, HOOMD's GSD, XYZ without
  // Time): `time` is then 0, and pictures are labelled by the step (ReadOptions::dt turns it
  // into a time).
  bool has_time = true;
  std::optional<std::int64_t> step;  // time step of LAMMPS and HOOMD files; collisions for ours
  std::optional<double> density, restitution, cutoff, speed;
  std::optional<std::uint64_t> seed;
  // A snapshot of the unbounded medium: `box` is only the region the engine addresses, almost all
  // of it never made, so there is no box to frame. Set by the engine, written and read as the XYZ
  // key Medium=unbounded and the GSD chunk log/Unbounded.
  bool unbounded = false;
  // A snapshot of a kick (a gas at rest, disturbed once: --initial kick) made by the engine. Its
  // colours are v/v_rms whether or not its resting particles were written (a file of the active
  // ones alone has none at rest to tell it by). Written and read as the XYZ key Initial=kick and
  // the GSD chunk log/Kick; false for others' files.
  bool kick = false;

  // A periodic cube of this side in the first `dim` axes (set `dim` first).
  void set_cubic_box(double side) {
    for (int k = 0; k < 3; ++k) box[k] = k < dim ? side : 0;
  }
  bool has_box() const { return box.head(dim).minCoeff() > 0; }
  // The edge shared by the first `dim` axes, or 0 when the box is unknown or not a cube.
  double cube_side() const { return has_box() && box.head(dim).maxCoeff() == box[0] ? box[0] : 0; }
};

// A numeric per-particle column of a file that the snapshot has no field for (LAMMPS `c_pe`,
// ASE `forces`, GSD `charge`, ...), so that pictures can be coloured by it. Vector columns are
// split into `name_x`, `name_y`, `name_z` (three or two components) or `name_0`, `name_1`, ...
struct Column {
  std::string name;
  std::vector<double> values;
};

struct Snapshot {
  SnapshotInfo info;
  std::vector<Eigen::Vector3d> position;  // unwrapped
  std::vector<Eigen::Vector3d> velocity;  // empty if the file had none
  std::vector<double> radius;             // 0.5 for the engine's unit-diameter spheres
  std::vector<std::uint8_t> active;       // 1 once a particle has collided; all 1 if unknown
  std::vector<double> first_collision;    // time of first collision (-1: never); may be empty
  std::vector<Column> columns;            // further numeric columns of the file
  // Particle types of a file that names them (LAMMPS `type`, GSD `typeid` with `types`, XYZ
  // species): an index into type_names each; both empty when the file has none.
  std::vector<std::uint32_t> type;
  std::vector<std::string> type_names;
  // What a reader assumed where the file says nothing (masses of momenta, time from steps,
  // positions folded into the cell), one sentence each, for the log of the command that reads it.
  std::vector<std::string> notes;

  std::size_t size() const { return position.size(); }
  // Whether particle i has collided; every particle of a file that does not say.
  bool is_active(std::size_t i) const { return active.empty() || active[i] != 0; }
  // Every particle has a velocity; so has a snapshot of none (the active particles before the
  // first collision), whose speeds are simply an empty set.
  bool has_velocity() const { return !velocity.empty() || position.empty(); }
  // The extra column of that name (exact match), or nullptr.
  const Column* column(std::string_view name) const {
    for (const auto& c : columns)
      if (c.name == name) return &c;
    return nullptr;
  }
};

}  // namespace gs
