// Speed of the snapshot files: reading 2.5e5 particles from extended XYZ, a LAMMPS
// dump and GSD to the first drawn pixel (text at >= 150 MB/s on 2 cores), and writing the
// snapshot of a 2e6-sphere run (< 1 s, or a smaller file: GSD, or only the active particles).
#include <unistd.h>

#include <charconv>
#include <cmath>
#include <filesystem>
#include <random>

#include "bench/bench.h"
#include "io/atomic_file.h"
#include "io/gsd.h"
#include "io/snapshot_file.h"
#include "io/snapshot_writer.h"
#include "io/xyz.h"
#include "render/field.h"
#include "render/renderer.h"
#include "sim/error.h"

namespace gs::bench {
namespace {

namespace fs = std::filesystem;

// A kicked gas as the engine leaves it: uniform positions in a box of packing ~0.2, a band of
// moving particles (10%) with first-collision times, the rest at rest.
Snapshot gas(int dim, std::size_t n) {
  Snapshot s;
  s.info.dim = dim;
  const double side = std::pow(static_cast<double>(n) / 0.25, 1.0 / dim);
  s.info.set_cubic_box(side);
  s.info.time = 5000;
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0, side), v(-1, 1);
  s.position.assign(n, Eigen::Vector3d::Zero());
  s.velocity.assign(n, Eigen::Vector3d::Zero());
  s.radius.assign(n, 0.5);
  s.active.assign(n, 0);
  s.first_collision.assign(n, -1);
  for (std::size_t i = 0; i < n; ++i) {
    for (int k = 0; k < dim; ++k) s.position[i][k] = u(rng);
    if (i % 10 == 0) {
      for (int k = 0; k < dim; ++k) s.velocity[i][k] = v(rng);
      s.active[i] = 1;
      s.first_collision[i] = 4000 + 1000 * std::abs(v(rng));
    }
  }
  return s;
}

fs::path scratch(const std::string& name) {
  return fs::temp_directory_path() /
         ("grainshock_bench_" + std::to_string(::getpid()) + "_" + name);
}

// `dump custom ... id type x y z vx vy vz` as LAMMPS prints it (%g: 6 significant digits).
void write_dump(const fs::path& path, const Snapshot& s) {
  std::string out = "ITEM: TIMESTEP\n1000\nITEM: NUMBER OF ATOMS\n" + std::to_string(s.size()) +
                    "\nITEM: BOX BOUNDS pp pp pp\n";
  char buf[64];
  for (int k = 0; k < 3; ++k) {
    const double hi = k < s.info.dim ? s.info.box[k] : 0.5, lo = k < s.info.dim ? 0 : -0.5;
    out += std::to_string(lo) + " " + std::to_string(hi) + "\n";
  }
  out += "ITEM: ATOMS id type x y z vx vy vz\n";
  for (std::size_t i = 0; i < s.size(); ++i) {
    out += std::to_string(i + 1) + " 1";
    for (int k = 0; k < 3; ++k) {
      const auto r =
          std::to_chars(buf, buf + sizeof buf, s.position[i][k], std::chars_format::general, 6);
      out += ' ';
      out.append(buf, r.ptr);
    }
    for (int k = 0; k < 3; ++k) {
      const auto r =
          std::to_chars(buf, buf + sizeof buf, s.velocity[i][k], std::chars_format::general, 6);
      out += ' ';
      out.append(buf, r.ptr);
    }
    out += '\n';
  }
  write_file_atomic(path, out);
}

// The best of three reads of the first frame to a ready Snapshot.
// The best of three: the file read to a Snapshot, then drawn at 1920x1080 as `render` draws it
// (the renderer's GL context made once before, as in a movie: its set-up is not the reader's).
std::vector<Figure> read_case(const fs::path& path, const std::string& target) {
  const double bytes = static_cast<double>(fs::file_size(path));
  render::Renderer renderer;
  render::View view;
  view.width = 1920;
  view.height = 1080;
  double best_read = 1e300, best_total = 1e300, best_cpu = 1e300;
  std::size_t n = 0;
  for (int rep = 0; rep < 3; ++rep) {
    const double t0 = wall_seconds(), c0 = cpu_seconds();
    const Snapshot s = read_snapshot(path.string());
    const double t1 = wall_seconds(), c1 = cpu_seconds();
    render::Style style;
    style.field = render::default_field(s);
    const render::Image img = renderer.render(s, style, view);
    GS_CHECK(img.width == view.width);
    best_read = std::min(best_read, t1 - t0);
    best_cpu = std::min(best_cpu, c1 - c0);
    best_total = std::min(best_total, wall_seconds() - t0);
    n = s.size();
  }
  fs::remove(path);
  return {{"read_seconds", best_read, "s", ""},
          {"read_megabytes_per_second", bytes / best_read / 1e6, "MB/s", target},
          // Less moved by other work on the machine: a text frame is read by two threads, so
          // two idle cores give about twice this.
          {"read_megabytes_per_cpu_second", bytes / best_cpu / 1e6, "MB/s", ""},
          {"first_pixel_seconds", best_total, "s", "read + draw"},
          {"file_megabytes", bytes / 1e6, "MB", ""},
          {"particles", static_cast<double>(n), "", "2.5e5"}};
}

// As `run` writes a snapshot (io/snapshot_writer.h), the filtering of active_only included.
std::vector<Figure> write_case(const Snapshot& s, bool gsd, bool active_only) {
  SnapshotWriteOptions options;
  options.format = gsd ? SnapshotFormat::Gsd : SnapshotFormat::Xyz;
  options.active_only = active_only;
  const fs::path path = scratch(std::string("w") + snapshot_extension(options.format));
  Snapshot kept;
  const double t0 = wall_seconds();
  write_snapshot(path.string(), s, options, kept);
  const double seconds = wall_seconds() - t0;
  const std::size_t written = active_only ? kept.size() : s.size();
  const double bytes = static_cast<double>(fs::file_size(path));
  fs::remove(path);
  return {{"seconds", seconds, "s", "< 1 s, or a smaller file"},
          {"file_megabytes", bytes / 1e6, "MB", "< 148 MB (today's text)"},
          {"particles_written", static_cast<double>(written), "", ""}};
}

}  // namespace

void add_io_cases(std::vector<Case>& cases) {
  cases.push_back({"io/read_xyz_2.5e5",
                   "extended XYZ of a 2D kick, 2.5e5 discs, to the first drawn pixel", false, [] {
                     const auto p = scratch("r.xyz");
                     write_xyz(p.string(), gas(2, 250000));
                     return read_case(p, ">= 150 MB/s");
                   }});
  cases.push_back({"io/read_lammps_2.5e5",
                   "LAMMPS dump custom of the same gas, to the first drawn pixel", false, [] {
                     const auto p = scratch("r.dump");
                     write_dump(p, gas(2, 250000));
                     return read_case(p, ">= 150 MB/s");
                   }});
  cases.push_back({"io/read_gsd_2.5e5", "GSD of the same gas, to the first drawn pixel", false, [] {
                     const auto p = scratch("r.gsd");
                     write_gsd(p.string(), gas(2, 250000));
                     return read_case(p, "");
                   }});
  cases.push_back({"io/write_xyz_2e6", "extended XYZ of a 3D kick, 2e6 spheres, 10% moving", false,
                   [] { return write_case(gas(3, 2000000), false, false); }});
  cases.push_back({"io/write_xyz_2e6_active", "the same, --snapshot-particles active", false,
                   [] { return write_case(gas(3, 2000000), false, true); }});
  cases.push_back({"io/write_gsd_2e6", "the same as GSD", false,
                   [] { return write_case(gas(3, 2000000), true, false); }});
}

}  // namespace gs::bench
