#include "io/trajectory.h"

#include "io/gsd.h"
#include "io/xyz.h"
#include "sim/error.h"

namespace gs {

SnapshotFormat trajectory_format(const std::string& name) {
  auto ends = [&](std::string_view e) { return name.size() > e.size() && name.ends_with(e); };
  if (ends(".gsd")) return SnapshotFormat::Gsd;
  if (ends(".xyz") || ends(".extxyz")) return SnapshotFormat::Xyz;
  throw UsageError("--trajectory '" + name +
                  "' must end in .gsd or .xyz (the format it is written in)");
}

std::unique_ptr<TrajectoryWriter> open_trajectory(const std::string& path, SnapshotFormat format) {
  if (format == SnapshotFormat::Gsd) return open_gsd_trajectory(path);
  return open_xyz_trajectory(path,
                             format == SnapshotFormat::OvitoXyz ? XyzFlavour::Ovito : XyzFlavour::Ase);
}

}  // namespace gs
