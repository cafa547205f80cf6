#pragma once
// Extended XYZ snapshots (the format OVITO and ASE read): per frame a count line, a comment line
// of key=value pairs (Lattice, Properties, Time, pbc, and our Dim, Density, Restitution, Cutoff,
// Speed, Seed), then one line per particle; frames follow each other in one file.
#include <memory>
#include <string>

#include "sim/snapshot_file.h"

namespace gs {

// Reads ours and those of ASE and OVITO: any property order; pos:R:3 or pos:R:2; velo, vel or
// momenta (over masses, 1 when absent); radius (default 0.5), active (default 1) and
// first_collision optional; further numeric properties become extra columns. Lattice may be
// rectangular in any vector order (triclinic is refused); Origin or cell_origin move its corner.
// Opening checks every frame's count against the lines that follow it.
std::unique_ptr<FrameSource> open_xyz(MappedFile file);

// Writes through a temporary file and rename, numbers in shortest round-trip form.
void write_xyz(const std::string& path, const Snapshot& s);

}  // namespace gs
