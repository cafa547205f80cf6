#pragma once
// The snapshot files `run` writes: extended XYZ for ASE (the default) or for OVITO's 2D view, or
// HOOMD GSD; all particles, or only the active ones (the gas at rest left out: a fraction of the
// size and time, for pictures and fronts, not for packing, which needs the particles around).
#include <string>

#include "sim/snapshot.h"

namespace gs {

enum class SnapshotFormat { Xyz, OvitoXyz, Gsd };

struct SnapshotWriteOptions {
  SnapshotFormat format = SnapshotFormat::Xyz;
  bool active_only = false;
};

// "xyz", "ovito-xyz" or "gsd"; UserError naming the choices otherwise.
SnapshotFormat parse_snapshot_format(const std::string& name);
const char* to_string(SnapshotFormat f);
// "all" or "active" into options.active_only; UserError otherwise.
void parse_snapshot_particles(const std::string& name, SnapshotWriteOptions& options);
// ".xyz" or ".gsd"
const char* snapshot_extension(SnapshotFormat f);

// The particles of `s` with active set into `out` (its storage reused), every per-particle
// array kept in step.
void active_particles(const Snapshot& s, Snapshot& out);

// Writes `s` to `path` (which has the format's extension) atomically. With active_only, the
// filtered copy goes through `scratch`, so that a run reuses its storage.
void write_snapshot(const std::string& path, const Snapshot& s, const SnapshotWriteOptions& options,
                    Snapshot& scratch);
void write_snapshot(const std::string& path, const Snapshot& s,
                    const SnapshotWriteOptions& options);

}  // namespace gs
