#pragma once
// Extended XYZ snapshots (the format OVITO and ASE read): a count line, a comment line of
// key=value pairs (Lattice, Properties, Time, pbc, and our Dim, Density, Restitution, Cutoff,
// Speed, Seed), then one line per particle.
#include <string>

#include "sim/snapshot.h"

namespace gs {

// Reads ours and hand-written files: any property order, unknown properties skipped, velo,
// radius (default 0.5), active (default 1) and first_collision optional; Dim defaults to 3.
// A missing, truncated or malformed file throws UserError naming the file and the line.
Snapshot read_xyz(const std::string& path);

// Writes through a temporary file and rename, numbers in shortest round-trip form.
void write_xyz(const std::string& path, const Snapshot& s);

}  // namespace gs
