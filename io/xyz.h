#pragma once
// Extended XYZ snapshots (the format OVITO and ASE read): per frame a count line, a comment line
// of key=value pairs (Lattice, Properties, Time, pbc, and our Dim, Density, Restitution, Cutoff,
// Speed, Seed), then one line per particle; frames follow each other in one file.
#include <memory>
#include <string>

#include "io/snapshot_file.h"
#include "io/trajectory.h"

namespace gs {

// Reads ours and those of ASE and OVITO: any property order; pos:R:3 or pos:R:2; velo, vel or
// momenta (over masses, 1 when absent); radius (default 0.5), active (default 1) and
// first_collision optional; further numeric properties become extra columns. Lattice may be
// rectangular in any vector order (triclinic is refused); Origin or cell_origin move its corner.
// Opening checks every frame's count against the lines that follow it.
std::unique_ptr<FrameSource> open_xyz(MappedFile file);

// Which reader a 2D or 1D file is for. OVITO's XYZ importer makes a cell 2D only when it has a
// cell (all three Lattice vectors non-zero) and no column maps to Position.Z, i.e. pos:R:2
// (read in its XYZImporter.cpp, 2026), which ASE cannot read (its positions have three), so one
// file cannot be both: Ase (the default) writes pos:R:3 and momenta, which ASE's get_velocities()
// divides by the masses (1 for species X), and which OVITO shows as a layer one diameter thick in
// the cell; Ovito writes pos:R:d and velo. 3D files are the same for both but for momenta/velo.
enum class XyzFlavour { Ase, Ovito };

// Writes through a temporary file and rename, numbers in shortest round-trip form: Lattice
// (edges beyond the dimension 1, pbc F there), Origin when not 0, radius, active,
// first_collision and every extra column.
void write_xyz(const std::string& path, const Snapshot& s, XyzFlavour flavour = XyzFlavour::Ase);
// Frames as write_xyz writes them, one after the other in one file (ASE's read(f, ':') and
// OVITO open them as one sequence).
std::unique_ptr<TrajectoryWriter> open_xyz_trajectory(const std::string& path,
                                                      XyzFlavour flavour = XyzFlavour::Ase);

}  // namespace gs
