#include "io/snapshot_file.h"

#include <algorithm>
#include <cmath>

#include "io/gsd.h"
#include "io/gunzip.h"
#include "io/lammps_dump.h"
#include "io/text_scan.h"
#include "io/xyz.h"
#include "sim/error.h"
#include "sim/escaped.h"
#include "sim/format.h"

namespace gs {

SnapshotFile::SnapshotFile(std::unique_ptr<FrameSource> source, std::string path, ReadOptions o)
    : source_(std::move(source)), path_(std::move(path)), options_(o) {
  if (options_.dim < 0 || options_.dim > 3) throw UsageError("--dim must be 1, 2 or 3");
  if (!(options_.dt >= 0) || !std::isfinite(options_.dt))
    throw UsageError("--dt must be a positive time step");
}

Snapshot SnapshotFile::read(std::size_t k) const {
  const std::size_t n = source_->frames();
  if (k >= n)
    throw UserError("snapshot '" + path_ + "' has " + std::to_string(n) +
                    (n == 1 ? " frame" : " frames") + "; frame " + std::to_string(k) +
                    " is out of range (frames count from 0)");
  Snapshot s = source_->read(k, options_);
  finish_snapshot(s, options_, "snapshot '" + path_ + "' frame " + std::to_string(k));
  return s;
}

std::size_t SnapshotFile::frame_index(long long k) const {
  const auto n = static_cast<long long>(source_->frames());
  const long long at = k < 0 ? n + k : k;
  if (at < 0 || at >= n)
    throw UserError("--frame " + std::to_string(k) + ": snapshot '" + path_ + "' has " +
                     std::to_string(n) + (n == 1 ? " frame" : " frames") + " (0 to " +
                     std::to_string(n - 1) + ", or -" + std::to_string(n) +
                     " to -1 from the end)");
  return static_cast<std::size_t>(at);
}

void refuse_extent(const std::string& path, std::size_t frame, std::string_view column,
                   std::size_t particle, std::string_view what, double value) {
  throw UserError("snapshot '" + path + "' frame " + std::to_string(frame) + ", column '" +
                  std::string(column) + "': particle " + std::to_string(particle) + " has " +
                  std::string(what) + " " + format_number(value) + ", beyond " +
                  format_number(kMaxCoordinate) + " (a corrupt file or another length unit)");
}

void check_extent(const Snapshot& s, const std::string& path, std::size_t frame,
                  const std::array<std::string, 3>& position_columns,
                  const std::string& radius_column) {
  static constexpr const char* kAxis[3] = {"x =", "y =", "z ="};
  for (std::size_t i = 0; i < s.position.size(); ++i)
    for (int a = 0; a < 3; ++a)
      if (beyond_extent(s.position[i][a]))
        refuse_extent(path, frame, position_columns[a], i, kAxis[a], s.position[i][a]);
  if (!radius_column.empty())
    for (std::size_t i = 0; i < s.radius.size(); ++i)
      if (beyond_extent(s.radius[i])) refuse_extent(path, frame, radius_column, i, "radius", s.radius[i]);
}

void finish_snapshot(Snapshot& s, const ReadOptions& options, const std::string& where) {
  const std::size_t n = s.size();
  GS_CHECK(s.velocity.empty() || s.velocity.size() == n);
  GS_CHECK(s.radius.empty() || s.radius.size() == n);
  GS_CHECK(s.active.empty() || s.active.size() == n);
  GS_CHECK(s.first_collision.empty() || s.first_collision.size() == n);
  for (const auto& c : s.columns) GS_CHECK(c.values.size() == n);

  int dim = options.dim > 0 ? options.dim : s.info.dim;
  if (dim == 0) {
    // Stated nowhere: a layer of exactly zero z (and z-velocity) is a 2D system, as LAMMPS and
    // HOOMD write 2D runs; a box without a z edge is too.
    bool flat = n > 0 || (s.info.box[0] > 0 && s.info.box[1] > 0 && s.info.box[2] == 0);
    for (std::size_t i = 0; i < n && flat; ++i)
      flat = s.position[i].z() == 0 && (s.velocity.empty() || s.velocity[i].z() == 0);
    dim = flat ? 2 : 3;
  } else if (options.dim == 0) {
    for (std::size_t i = 0; i < n; ++i)
      for (int k = dim; k < 3; ++k)
        if (s.position[i][k] != 0 || (!s.velocity.empty() && s.velocity[i][k] != 0))
          throw UserError(where + ": the file states " + std::to_string(dim) + "D but particle " +
                          std::to_string(i) + " has a component beyond it that is not 0");
  }
  s.info.dim = dim;
  for (int k = dim; k < 3; ++k) {
    s.info.box[k] = 0;
    s.info.origin[k] = 0;
    for (auto& p : s.position) p[k] = 0;
    for (auto& v : s.velocity) v[k] = 0;
  }
  if (!s.info.has_time && s.info.step && options.dt > 0) {
    s.info.time = static_cast<double>(*s.info.step) * options.dt;
    s.info.has_time = true;
    s.notes.push_back("the file gives steps, no time: time = step x " + format_number(options.dt) +
                      " (--dt)");
  } else if (!s.info.has_time) {
    s.notes.push_back(s.info.step ? "the file gives steps, no time: frames are labelled by their "
                                    "step (--dt DT turns steps into time)"
                                  : "the file gives no time and no step: frames have no time label");
  }
  if (s.radius.empty()) s.radius.assign(n, 0.5);
  if (s.active.empty()) s.active.assign(n, 1);  // a file without the column shows every particle
}

namespace {

std::unique_ptr<FrameSource> open_source(MappedFile file) {
  const std::string_view b = file.bytes();
  if (is_gsd(b)) return open_gsd(std::move(file));
  std::size_t i = 0;
  while (i < b.size() && is_space(b[i])) ++i;
  if (b.substr(i).starts_with("ITEM:")) return open_lammps_dump(std::move(file));
  if (i == b.size()) throw UserError("snapshot '" + file.path() + "' is empty");
  if (std::any_of(b.begin(), b.begin() + std::min<std::size_t>(b.size(), 64),
                  [](char c) { return c == '\0'; }))
    throw UserError("snapshot '" + file.path() + "' is binary but not GSD (bad magic number)");
  std::size_t j = i;
  while (j < b.size() && b[j] != '\n') ++j;
  std::string_view first = b.substr(i, j - i);
  std::size_t t = 0;
  std::uint64_t count = 0;
  const std::string_view tok = next_token(first, t);
  if (!parse_integer(tok, count) || !is_blank(first.substr(t))) {
    throw_at_line(file.path(), std::count(b.begin(), b.begin() + i, '\n') + 1,
                  "'" + escaped(first, 60) +
                      "' is not a particle count alone on the line (extended XYZ) nor an ITEM: "
                      "line (LAMMPS dump), and the file is not GSD");
  }
  return open_xyz(std::move(file));
}

}  // namespace

SnapshotFile open_snapshots(MappedFile file, const ReadOptions& options) {
  std::string path = file.path();
  return SnapshotFile(open_source(std::move(file)), std::move(path), options);
}

SnapshotFile open_snapshots(const std::string& path, const ReadOptions& options) {
  MappedFile file = MappedFile::open(path);
  if (is_gzip(file.bytes()))
    file = MappedFile::from_bytes(path, gunzip(file.bytes(), path, gunzip_limit()));
  return open_snapshots(std::move(file), options);
}

Snapshot read_snapshot(const std::string& path, const ReadOptions& options, long long frame) {
  const SnapshotFile f = open_snapshots(path, options);
  return f.read(f.frame_index(frame));
}

}  // namespace gs
