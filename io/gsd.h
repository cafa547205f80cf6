#pragma once
// HOOMD-blue GSD files, from the published GSD file-layer and hoomd-schema specifications
// (gsd.readthedocs.io): a 256-byte header, an index of 32-byte entries (frame, N, location, M,
// name id, type), a list of chunk names, and the data chunks. A chunk a frame lacks is taken
// from frame 0, else its schema default, as HOOMD does.
#include <memory>
#include <string>
#include <string_view>

#include "io/snapshot_file.h"
#include "io/trajectory.h"

namespace gs {

// Whether the bytes begin with the GSD magic number.
bool is_gsd(std::string_view bytes);

// Reads configuration/step, dimensions and box (a tilted box is refused), particles/N,
// position (unwrapped by image when present), velocity, diameter, typeid, mass, charge, and
// the per-particle log/particles/* chunks (ours: active, first_collision; others become extra
// columns). Every size and offset is checked against the file before it is used.
std::unique_ptr<FrameSource> open_gsd(MappedFile file);

// One frame in the hoomd schema (positions, velocities and diameters as 32-bit floats, as the
// schema has them, so this is a picture of the state rather than an exact record), plus
// log/particles/active, log/particles/first_collision, configuration/step (the snapshot's step:
// collisions so far for ours) and log/Time (OVITO's global attribute Time; earlier versions
// wrote log/grainshock/time, which is still read). Positions are
// wrapped into the box centred on the origin with the image counts beside them, as HOOMD wants;
// image and diameter are left out when all are the schema's defaults (0 and 1).
void write_gsd(const std::string& path, const Snapshot& s);

// Several frames in one file, as HOOMD writes a trajectory (OVITO and gsd.hoomd open it as one
// sequence): each frame as write_gsd writes one, but with every chunk, since readers take a
// chunk a frame lacks from frame 0. 1D frames are refused (UserError).
std::unique_ptr<TrajectoryWriter> open_gsd_trajectory(const std::string& path);

}  // namespace gs
