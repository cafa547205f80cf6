#pragma once
// One file holding every snapshot time of a run (`run --trajectory FILE.gsd|.xyz`), which
// OVITO, ASE and gsd.hoomd open as one sequence and `render --frame` and `movie` read back:
// extended XYZ frames one after the other (io/xyz.h), or a GSD file of several frames
// (io/gsd.h). Written through a temporary: the file appears whole at finish(), and a writer
// destroyed before leaves nothing.
#include <memory>
#include <string>

#include "io/snapshot_writer.h"
#include "sim/snapshot.h"

namespace gs {

class TrajectoryWriter {
 public:
  virtual ~TrajectoryWriter() = default;
  virtual void add(const Snapshot& s) = 0;
  virtual void finish() = 0;
};

// The format of a trajectory's name: .gsd is GSD, .xyz or .extxyz extended XYZ (ASE's kind);
// UserError naming the name otherwise.
SnapshotFormat trajectory_format(const std::string& name);
std::unique_ptr<TrajectoryWriter> open_trajectory(const std::string& path, SnapshotFormat format);

}  // namespace gs
