#include "io/snapshot_writer.h"

#include "io/gsd.h"
#include "io/xyz.h"
#include "sim/error.h"

namespace gs {

SnapshotFormat parse_snapshot_format(const std::string& name) {
  if (name == "xyz") return SnapshotFormat::Xyz;
  if (name == "ovito-xyz") return SnapshotFormat::OvitoXyz;
  if (name == "gsd") return SnapshotFormat::Gsd;
  throw UsageError("unknown --snapshot-format '" + name + "' (use xyz, ovito-xyz or gsd)");
}

const char* to_string(SnapshotFormat f) {
  switch (f) {
    case SnapshotFormat::Xyz:
      return "xyz";
    case SnapshotFormat::OvitoXyz:
      return "ovito-xyz";
    case SnapshotFormat::Gsd:
      return "gsd";
  }
  return "xyz";
}

void parse_snapshot_particles(const std::string& name, SnapshotWriteOptions& options) {
  if (name != "all" && name != "active")
    throw UsageError("unknown --snapshot-particles '" + name + "' (use all or active)");
  options.active_only = name == "active";
}

const char* snapshot_extension(SnapshotFormat f) {
  return f == SnapshotFormat::Gsd ? ".gsd" : ".xyz";
}

void active_particles(const Snapshot& s, Snapshot& out) {
  out.info = s.info;
  out.position.clear();
  out.velocity.clear();
  out.radius.clear();
  out.active.clear();
  out.first_collision.clear();
  out.columns.resize(s.columns.size());
  for (std::size_t c = 0; c < s.columns.size(); ++c) {
    out.columns[c].name = s.columns[c].name;
    out.columns[c].values.clear();
  }
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (!s.active[i]) continue;
    out.position.push_back(s.position[i]);
    if (s.has_velocity()) out.velocity.push_back(s.velocity[i]);
    out.radius.push_back(s.radius[i]);
    out.active.push_back(1);
    if (!s.first_collision.empty()) out.first_collision.push_back(s.first_collision[i]);
    for (std::size_t c = 0; c < s.columns.size(); ++c)
      out.columns[c].values.push_back(s.columns[c].values[i]);
  }
}

void write_snapshot(const std::string& path, const Snapshot& s, const SnapshotWriteOptions& options,
                    Snapshot& scratch) {
  if (options.active_only) active_particles(s, scratch);
  const Snapshot& out = options.active_only ? scratch : s;
  if (options.format == SnapshotFormat::Gsd) {
    if (out.info.dim < 2) throw UserError("GSD holds 2D and 3D systems only; use xyz in 1D");
    write_gsd(path, out);
  } else {
    write_xyz(path, out,
              options.format == SnapshotFormat::OvitoXyz ? XyzFlavour::Ovito : XyzFlavour::Ase);
  }
}

void write_snapshot(const std::string& path, const Snapshot& s,
                    const SnapshotWriteOptions& options) {
  Snapshot scratch;
  write_snapshot(path, s, options, scratch);
}

}  // namespace gs
