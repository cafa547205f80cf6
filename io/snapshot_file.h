#pragma once
// One reader for every snapshot file render, movie and the analysis take: extended XYZ (ours,
// ASE's, OVITO's), LAMMPS text dumps and HOOMD GSD, told apart by their content, not their name,
// each also gzip-compressed (io/gunzip.h).
// Opening indexes the frames in one scan; read(k) parses frame k alone, so a movie streams a
// long trajectory one frame at a time.
//
//   SnapshotFile f = open_snapshots("dump.lammpstrj");
//   for (std::size_t k = 0; k < f.frame_count(); ++k) draw(f.read(k));
//
// Every frame comes back complete: radius (0.5 where the file has none), active (all 1 where
// the file has none), velocity only when the file has one, extra numeric columns by name, the
// box when the file has one, and the dimension: as the file states it (our Dim key, GSD's
// dimensions, 2-component positions, pbc "T T F" with a zero third lattice vector), else 2 when
// every z and z-velocity is exactly 0, else 3; ReadOptions::dim overrides (dropping the
// components beyond it). Bad input throws UserError naming the file and the line or frame.
#include <array>
#include <cmath>
#include <memory>
#include <string>
#include <string_view>

#include "io/mapped_file.h"
#include "sim/snapshot.h"

namespace gs {

struct ReadOptions {
  int dim = 0;  // 1, 2 or 3 overrides what the file says or suggests; 0 infers
  // > 0: frames that give a step but no time (LAMMPS dumps without ITEM: TIME, HOOMD GSD) get
  // time = step x dt; frames that give a time keep it.
  double dt = 0;
  // LAMMPS dumps and others' GSD files: false draws what OVITO draws, the positions in the cell
  // (x or xs as written, xu folded into the cell, image flags kept as columns ix iy iz or
  // image_x ...); true unwraps them (xu, or x plus image flags times the box). Our own files
  // hold unwrapped positions (a band across the boundary in one piece) and keep them either way.
  bool unwrap = false;
};

// The note of `unwrap` on a frame that has nothing to unwrap by (a dump of x y z without ix iy
// iz or xu, a GSD file without particles/image, any extended XYZ file), so that the flag never
// does nothing without a word.
inline constexpr char kNothingToUnwrap[] =
    "--unwrap: the file has no image flags to unwrap by; positions are drawn as written";

// A file format's view of a file: its frames, each read on demand.
class FrameSource {
 public:
  virtual ~FrameSource() = default;
  virtual std::size_t frames() const = 0;
  // Frame k < frames(). info.dim is what the file states, or 0 when it states nothing.
  virtual Snapshot read(std::size_t k, const ReadOptions& options) const = 0;
  virtual const char* format() const = 0;  // "extended XYZ", "LAMMPS dump", "GSD"
};

class SnapshotFile {
 public:
  explicit SnapshotFile(std::unique_ptr<FrameSource> source, std::string path, ReadOptions o);
  std::size_t frame_count() const { return source_->frames(); }
  // Frame k (0 = first); UserError naming the file and the number of frames if k is too large.
  Snapshot read(std::size_t k) const;
  // The frame a --frame K names, counted as ASE counts: from 0, or from the end when negative
  // (-1 the last); UserError naming the flag, the file and its frames if there is none.
  std::size_t frame_index(long long k) const;
  const std::string& path() const { return path_; }
  const char* format() const { return source_->format(); }

 private:
  std::unique_ptr<FrameSource> source_;
  std::string path_;
  ReadOptions options_;
};

SnapshotFile open_snapshots(const std::string& path, const ReadOptions& options = {});
// The same over bytes in memory (tests and fuzzers); `name` stands for the path in messages.
SnapshotFile open_snapshots(MappedFile file, const ReadOptions& options = {});
// Frame `frame` of a file (negative: from the end, as frame_index): the shorthand for pictures
// of one snapshot.
Snapshot read_snapshot(const std::string& path, const ReadOptions& options = {},
                       long long frame = 0);

// The largest |coordinate| and radius a frame may hold, in the file's length unit. Pictures place
// particles in float relative to the camera and their shaders square distances and radii (times a
// view scale of up to ~1e4 pixels per unit), which overflows float's 3.4e38 near 1e17; and a
// frame spanning more than 2^24 radii cannot be drawn in float at all. 1e12 leaves room for both
// and is far beyond any system in these units (our largest grid spans 32766 diameters, a
// million-atom LAMMPS box in angstrom about 1e3): a value above it is a corrupt file or a wrong
// unit, and was drawn as an empty picture.
inline constexpr double kMaxCoordinate = 1e12;

inline bool beyond_extent(double x) { return !(std::fabs(x) <= kMaxCoordinate); }
// The UserError for a value beyond it, naming the file, the frame, the column and the particle;
// `what` says which value ("x =", "radius").
[[noreturn]] void refuse_extent(const std::string& path, std::size_t frame,
                                std::string_view column, std::size_t particle,
                                std::string_view what, double value);
// refuse_extent unless every position of `s` is within +-kMaxCoordinate and every radius below
// it: `position_columns[a]` is the file's name for axis a, `radius_column` for the radii (empty
// when the file gives none). Every reader calls it on the frame it has read.
void check_extent(const Snapshot& s, const std::string& path, std::size_t frame,
                  const std::array<std::string, 3>& position_columns,
                  const std::string& radius_column);

// What every reader does last: applies the dimension (stated, overridden or inferred), zeroes
// what lies beyond it, fills the defaults and checks the sizes. Exposed for the tests.
void finish_snapshot(Snapshot& s, const ReadOptions& options, const std::string& where);

}  // namespace gs
