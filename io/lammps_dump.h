#pragma once
// LAMMPS text dumps (`dump atom`, `dump custom`): per frame ITEM: TIMESTEP, NUMBER OF ATOMS,
// BOX BOUNDS and ATOMS sections (TIME and UNITS when the dump has them), several frames per file.
#include <memory>

#include "io/snapshot_file.h"

namespace gs {

// Columns in any order: positions as x, scaled xs, unwrapped xu or scaled unwrapped xsu (per
// axis, the unwrapped ones preferred, image flags ix iy iz applied to wrapped ones), velocities
// vx vy vz, radius or diameter; every other numeric column (id, type, c_pe, fx, ...) becomes an
// extra column. BOX BOUNDS with any pp/ff/ss flags; a triclinic box with non-zero tilt is
// refused. A missing section, a count that does not match the lines or a bad number is an error
// naming the file and line.
std::unique_ptr<FrameSource> open_lammps_dump(MappedFile file);

}  // namespace gs
