#pragma once
// Particle types from per-particle labels (LAMMPS type numbers, XYZ species), so that pictures
// can be coloured by type as OVITO does by default for a file without velocities.
#include <string_view>
#include <vector>

#include "sim/snapshot.h"

namespace gs {

// Fills s.type and s.type_names from one label per particle: the names sorted (as numbers when
// every label is an integer, so LAMMPS type 10 follows 2), each particle the index of its label.
void assign_types(Snapshot& s, const std::vector<std::string_view>& labels);
// The same from numbers (a LAMMPS type column); leaves s untouched unless every one is an integer.
void assign_types(Snapshot& s, const std::vector<double>& numbers);

}  // namespace gs
