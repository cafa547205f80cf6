// Files of a run as others read them and as we read them back: a
// run's --png frame drawn again by `render` from its snapshot, byte for byte; --trajectory as
// one sequence for render --frame, movie, gsd.hoomd and ASE (where /usr/bin/python3 has them);
// frames labelled by step without a time, and --dt.
#include <gtest/gtest.h>

#include <map>

#include "tests/apps/cli_test_util.h"
#include "render/png.h"
#include "io/snapshot_file.h"

namespace gs {
namespace {

namespace fs = std::filesystem;
using test::grainshock;
using test::read_file;
using test::scratch_dir;

constexpr const char* kPython = "/usr/bin/python3";

bool python_has(const std::string& module) {
  return std::system(
             (std::string(kPython) + " -c 'import " + module + "' > /dev/null 2>&1").c_str()) == 0;
}

// Runs `script` with /usr/bin/python3 in `dir`; its stdout, or "FAILED" and its stderr.
std::string python(const fs::path& dir, const std::string& script) {
  std::ofstream(dir / "script.py") << script;
  const std::string cmd =
      "cd " + dir.string() + " && " + kPython + " script.py > out.txt 2> err.txt";
  const bool ok = std::system(cmd.c_str()) == 0;
  return (ok ? "" : "FAILED ") + read_file(dir / (ok ? "out.txt" : "err.txt"));
}

std::map<std::string, std::string> text_of(const fs::path& png) {
  std::map<std::string, std::string> text;
  for (const auto& [k, v] : render::read_png_text(png.string())) text[k] = v;
  return text;
}

// A small kick with two snapshot times, its pictures and a trajectory of each format.
fs::path small_run(int dim, const std::string& extra) {
  const fs::path dir = scratch_dir("run" + std::to_string(dim));
  const auto r = grainshock("run --medium box --dim " + std::to_string(dim) + " --particles " +
                            (dim == 2 ? "3000" : "4000") +
                            " --restitution 0.5 --t-max 20 --snapshot-times 10,20 --png "
                            "--width 480 --height 270 --quiet " +
                            extra + " --out " + dir.string());
  EXPECT_EQ(r.exit_code, 0) << r.err;
  return dir;
}

// Item 4(d): `render` of a run's own snapshot draws what the run drew (inset, 3D slab 6), to
// the byte, given only the size; --no-inset draws something else (the test can fail).
TEST(CliInterop, RenderOfARunsSnapshotIsTheRunsFrame) {
  for (int dim : {2, 3}) {
    SCOPED_TRACE("dim " + std::to_string(dim));
    const fs::path dir = small_run(dim, "");
    const fs::path frame = dir / "frames" / "tsim_20.png";
    ASSERT_TRUE(fs::exists(frame));
    const fs::path again = dir / "again.png", bare = dir / "bare.png";
    auto r = grainshock("render " + (dir / "snapshots" / "tsim_20.xyz").string() +
                        " --width 480 --height 270 --out " + again.string());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(read_file(again), read_file(frame)) << "render differs from the run's frame";
    r = grainshock("render " + (dir / "snapshots" / "tsim_20.xyz").string() +
                   " --width 480 --height 270 --no-inset --out " + bare.string());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(read_file(bare), read_file(frame));
  }
}

// Item 7: --trajectory holds both snapshot times as one sequence, with the step (collisions
// so far) and the time where OVITO and gsd.hoomd look for them, and reads back through
// render --frame and movie.
TEST(CliInterop, TrajectoryIsOneSequence) {
  const fs::path dir = small_run(2, "--trajectory traj.gsd");
  const fs::path xyz_dir = small_run(3, "--trajectory traj.xyz");
  for (const fs::path& file : {dir / "traj.gsd", xyz_dir / "traj.xyz"}) {
    SCOPED_TRACE(file.string());
    const SnapshotFile f = open_snapshots(file.string());
    ASSERT_EQ(f.frame_count(), 2u);
    const Snapshot a = f.read(0), b = f.read(1);
    EXPECT_EQ(a.info.time, 10);
    EXPECT_EQ(b.info.time, 20);
    ASSERT_TRUE(a.info.step && b.info.step);
    EXPECT_GT(*a.info.step, 0);
    EXPECT_GT(*b.info.step, *a.info.step);
    // The same frame as the snapshot file of that time (GSD: within float32, in HOOMD's box
    // centred on 0).
    const Snapshot s = read_snapshot((file.parent_path() / "snapshots" / "tsim_20.xyz").string());
    ASSERT_EQ(s.size(), b.size());
    double worst = 0;
    for (std::size_t i = 0; i < s.size(); ++i)
      worst = std::max(worst, ((s.position[i] - s.info.origin) - (b.position[i] - b.info.origin))
                                  .cwiseAbs()
                                  .maxCoeff());
    EXPECT_LE(worst, file.extension() == ".gsd" ? 1e-4 : 0.0);
    EXPECT_EQ(b.active, s.active);

    const fs::path png = file.parent_path() / "frame1.png";
    auto r = grainshock("render " + file.string() + " --frame 1 --width 320 --height 180 --out " +
                        png.string());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(text_of(png)["Time"], "20.0");
    const fs::path movie = file.parent_path() / "movie";
    r = grainshock("movie " + file.string() + " --width 320 --height 180 --quiet --out " +
                   movie.string());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_TRUE(fs::exists(movie / "movie.mp4"));
  }
  if (python_has("gsd.hoomd")) {
    const std::string out =
        python(dir,
               "import gsd.hoomd\n"
               "f = gsd.hoomd.open('traj.gsd', 'rb')\n"
               "print(len(f), ' '.join(str(s.configuration.step) for s in f),\n"
               "      ' '.join(repr(float(s.log['Time'][0])) for s in f))\n");
    std::istringstream in(out);
    std::size_t frames = 0;
    long long step0 = -1, step1 = -1;
    double t0 = 0, t1 = 0;
    in >> frames >> step0 >> step1 >> t0 >> t1;
    EXPECT_EQ(frames, 2u) << out;
    EXPECT_GT(step0, 0) << out;
    EXPECT_GT(step1, step0) << out;
    EXPECT_EQ(t0, 10) << out;
    EXPECT_EQ(t1, 20) << out;
  } else {
    std::cout << "[ SKIPPED  ] gsd.hoomd part: " << kPython << " has no gsd (python3-gsd)\n";
  }
  if (python_has("ase.io")) {
    const std::string out = python(xyz_dir,
                                   "import ase.io\n"
                                   "fs = ase.io.read('traj.xyz', ':')\n"
                                   "print(len(fs), ' '.join(repr(float(a.info['Time'])) for a in "
                                   "fs), len(fs[1]))\n");
    std::istringstream in(out);
    std::size_t frames = 0, n = 0;
    double t0 = 0, t1 = 0;
    in >> frames >> t0 >> t1 >> n;
    EXPECT_EQ(frames, 2u) << out;
    EXPECT_EQ(t0, 10) << out;
    EXPECT_EQ(t1, 20) << out;
    EXPECT_EQ(n, 4000u) << out;
  } else {
    std::cout << "[ SKIPPED  ] ASE part: " << kPython << " has no ase (python3-ase)\n";
  }
}

// Item 3: a LAMMPS dump without ITEM: TIME is labelled by its step, and the log says so;
// --dt makes its time step x DT. Item 4(a): image flags are left as columns by default (the
// positions in the cell, as OVITO draws them) and applied with --unwrap.
TEST(CliInterop, StepsWithoutTimeAndPositionsInTheCell) {
  const fs::path dir = scratch_dir("dump");
  fs::create_directories(dir);
  const fs::path dump = dir / "melt.lammpstrj";
  std::ofstream(dump) << "ITEM: TIMESTEP\n500\nITEM: NUMBER OF ATOMS\n2\n"
                         "ITEM: BOX BOUNDS pp pp pp\n0 10\n0 10\n-0.5 0.5\n"
                         "ITEM: ATOMS id x y z vx vy vz ix iy iz\n"
                         "1 2 3 0 0.1 0 0 1 0 0\n2 7 5 0 0 0.2 0 0 -1 0\n";
  const fs::path png = dir / "step.png";
  auto r = grainshock("render " + dump.string() + " --width 200 --height 150 --out " +
                      png.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("labelled by their step"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("positions in the cell"), std::string::npos) << r.err;
  auto text = text_of(png);
  EXPECT_EQ(text.count("Time"), 0u);
  EXPECT_EQ(text["Step"], "500");
  r = grainshock("render " + dump.string() + " --dt 0.005 --width 200 --height 150 --out " +
                 png.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("time = step x 0.005"), std::string::npos) << r.err;
  EXPECT_EQ(text_of(png)["Time"], "2.5");

  const Snapshot in_cell = read_snapshot(dump.string());
  EXPECT_EQ(in_cell.position[0], Eigen::Vector3d(2, 3, 0));
  ASSERT_NE(in_cell.column("ix"), nullptr);
  ReadOptions unwrap;
  unwrap.unwrap = true;
  const Snapshot unwrapped = read_snapshot(dump.string(), unwrap);
  EXPECT_EQ(unwrapped.position[0], Eigen::Vector3d(12, 3, 0));
  EXPECT_EQ(unwrapped.position[1], Eigen::Vector3d(7, -5, 0));
}

}  // namespace
}  // namespace gs
