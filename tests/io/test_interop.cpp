// Our snapshot files as the programs of others read them, and theirs as we read them, with the
// real programs where installed (/usr/bin/python3 with python3-ase and python3-gsd; the python3
// first on PATH may be a build without them): a kicked gas from the engine, written as `run`
// writes it (io/snapshot_writer.h), read by ASE 3.22 and gsd 2.7 and compared value by value
// with what we wrote; files that ASE and gsd write, read by us. OVITO is not installed: its XYZ
// importer's rules are checked on our headers instead.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "io/snapshot_file.h"
#include "io/snapshot_writer.h"
#include "sim/engine.h"

namespace gs {
namespace {

namespace fs = std::filesystem;

constexpr const char* kPython = "/usr/bin/python3";

bool python_has(const std::string& module) {
  return std::system(
             (std::string(kPython) + " -c 'import " + module + "' > /dev/null 2>&1").c_str()) == 0;
}

fs::path scratch(const std::string& name) {
  const fs::path d = fs::path(GRAINSHOCK_TEST_OUTPUT_DIR) / "interop" / name;
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

// Runs `script` with /usr/bin/python3 in `dir`; returns its stdout, or "FAILED" + stderr.
std::string python(const fs::path& dir, const std::string& script) {
  std::ofstream(dir / "script.py") << script;
  const std::string cmd =
      "cd " + dir.string() + " && " + kPython + " script.py > out.txt 2> err.txt";
  const bool ok = std::system(cmd.c_str()) == 0;
  std::ifstream out(dir / (ok ? "out.txt" : "err.txt"));
  std::stringstream text;
  text << out.rdbuf();
  return (ok ? "" : "FAILED ") + text.str();
}

// A kicked gas a while after the kick: a band of moving particles, the rest at rest.
Snapshot kicked_gas(int dim) {
  PhysicsConfig c;
  c.dim = dim;
  c.particles = dim == 2 ? 3000 : 4000;
  c.restitution = 0.5;
  auto sim = make_simulation(c);
  sim->run_until(dim == 2 ? 60 : 20);
  Snapshot s = sim->snapshot();
  EXPECT_GT(std::count(s.active.begin(), s.active.end(), 1), 20);
  return s;
}

std::vector<double> numbers(std::istream& in, std::size_t count) {
  std::vector<double> v(count);
  for (auto& x : v) in >> x;
  return v;
}

// ASE reads what `run` writes by default: get_velocities() gives our velocities exactly (our
// numbers are printed in shortest round-trip form, and momenta with no masses column are
// divided by the mass 1 of species X), the cell is our box (in 2D with one diameter along z,
// pbc "T T F"), positions likewise.
TEST(Interop, AseReadsOurSnapshots) {
  if (!python_has("ase.io")) GTEST_SKIP() << kPython << " has no ase (python3-ase)";
  for (int dim : {2, 3}) {
    SCOPED_TRACE("dim " + std::to_string(dim));
    const Snapshot s = kicked_gas(dim);
    const fs::path dir = scratch("ase_" + std::to_string(dim));
    write_snapshot((dir / "t.xyz").string(), s, SnapshotWriteOptions{});
    const std::string out =
        python(dir,
               "import ase.io\n"
               "a = ase.io.read('t.xyz')\n"
               "print(len(a), ' '.join('1' if p else '0' for p in a.pbc))\n"
               "for row in a.cell[:]: print(' '.join(repr(float(x)) for x in row))\n"
               "for p, v in zip(a.positions, a.get_velocities()):\n"
               "    print(' '.join(repr(float(x)) for x in list(p) + list(v)))\n");
    ASSERT_EQ(out.rfind("FAILED", 0), std::string::npos) << out;
    std::istringstream in(out);
    std::size_t n = 0;
    int pbc[3];
    in >> n >> pbc[0] >> pbc[1] >> pbc[2];
    ASSERT_EQ(n, s.size());
    EXPECT_EQ(pbc[0] + pbc[1], 2);
    EXPECT_EQ(pbc[2], dim == 3 ? 1 : 0);
    const auto cell = numbers(in, 9);
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b)
        EXPECT_EQ(cell[3 * a + b], a != b ? 0 : a < dim ? s.info.box[a] : 1) << a << " " << b;
    for (std::size_t i = 0; i < n; ++i) {
      const auto row = numbers(in, 6);
      for (int a = 0; a < 3; ++a) {
        ASSERT_EQ(row[a], s.position[i][a]) << "particle " << i;
        ASSERT_EQ(row[3 + a], s.velocity[i][a]) << "particle " << i;
      }
    }
  }
}

// gsd.hoomd reads our GSD: dimensions, box, N, and positions (wrapped + image x box, shifted by
// the box corner) and velocities within float32 rounding. The schema stores float32: a wrapped
// coordinate |x| <= L/2 is within L/2 * 2^-24 of ours, and the unwrapping adds at most as much
// again, so L * 2^-23 bounds both; velocities (|v| <= v0 = 1) within 2^-24.
TEST(Interop, GsdModuleReadsOurSnapshots) {
  if (!python_has("gsd.hoomd")) GTEST_SKIP() << kPython << " has no gsd (python3-gsd)";
  for (int dim : {2, 3}) {
    SCOPED_TRACE("dim " + std::to_string(dim));
    const Snapshot s = kicked_gas(dim);
    const fs::path dir = scratch("gsd_" + std::to_string(dim));
    SnapshotWriteOptions w;
    w.format = SnapshotFormat::Gsd;
    write_snapshot((dir / "t.gsd").string(), s, w);
    const std::string out =
        python(dir,
               "import gsd.hoomd\n"
               "f = gsd.hoomd.open('t.gsd', 'rb')\n"
               "s = f[0]\n"
               "print(len(f), s.configuration.dimensions, s.particles.N)\n"
               "print(' '.join(repr(float(x)) for x in s.configuration.box))\n"
               "L = s.configuration.box[:3]\n"
               "u = s.particles.position.astype(float) + s.particles.image * L\n"
               "for p, v, a in zip(u, s.particles.velocity, s.log['particles/active']):\n"
               "    print(' '.join(repr(float(x)) for x in list(p) + list(v)), int(a))\n");
    ASSERT_EQ(out.rfind("FAILED", 0), std::string::npos) << out;
    std::istringstream in(out);
    std::size_t frames = 0, n = 0;
    int dims = 0;
    in >> frames >> dims >> n;
    EXPECT_EQ(frames, 1u);
    EXPECT_EQ(dims, dim);
    ASSERT_EQ(n, s.size());
    const auto box = numbers(in, 6);
    const double L = s.info.box[0], pos_tol = L * std::ldexp(1.0, -23),
                 vel_tol = std::ldexp(1.0, -24);
    for (int a = 0; a < dim; ++a) EXPECT_NEAR(box[a], s.info.box[a], pos_tol);
    for (int a = 3; a < 6; ++a) EXPECT_EQ(box[a], 0);  // no tilt
    for (std::size_t i = 0; i < n; ++i) {
      const auto row = numbers(in, 7);
      for (int a = 0; a < dim; ++a) {
        // HOOMD's box is centred on 0, ours has its corner at the origin.
        ASSERT_NEAR(row[a] + L / 2, s.position[i][a], pos_tol) << "particle " << i;
        ASSERT_NEAR(row[3 + a], s.velocity[i][a], vel_tol) << "particle " << i;
      }
      ASSERT_EQ(row[6], s.active[i]) << "particle " << i;
    }
  }
}

// The comment line of a frame of ours, as OVITO's XYZ importer would split it.
std::string header_of(const fs::path& file) {
  std::ifstream in(file);
  std::string count, header;
  std::getline(in, count);
  std::getline(in, header);
  return header;
}

std::vector<double> lattice_of(const std::string& header) {
  const auto at = header.find("Lattice=\"");
  if (at == std::string::npos) return {};
  std::istringstream in(header.substr(at + 9, header.find('"', at + 9) - at - 9));
  return numbers(in, 9);
}

// OVITO's XYZ importer (XYZImporter.cpp, FrameLoader::loadFile, OVITO 3.x) takes the Lattice
// as the cell only when all three vectors are non-zero, and otherwise makes an ad-hoc bounding
// box; pbc comes from the pbc key. Its dimensionality follows the position columns: our
// `ovito-xyz` writes pos:R:2 (and velo:R:2, OVITO's velocity name) for a 2D run, the default
// writes pos:R:3 for ASE. Both must give the box of the run with three non-zero vectors and
// pbc "T T F"; and we read both back the same.
TEST(Interop, OurTwoDimensionalFilesFollowOvitosImporterRules) {
  const Snapshot s = kicked_gas(2);
  const fs::path dir = scratch("ovito");
  SnapshotWriteOptions ovito;
  ovito.format = SnapshotFormat::OvitoXyz;
  write_snapshot((dir / "ase.xyz").string(), s, SnapshotWriteOptions{});
  write_snapshot((dir / "ovito.xyz").string(), s, ovito);
  for (const char* name : {"ase.xyz", "ovito.xyz"}) {
    SCOPED_TRACE(name);
    const std::string header = header_of(dir / name);
    const auto lattice = lattice_of(header);
    ASSERT_EQ(lattice.size(), 9u) << header;
    for (int v = 0; v < 3; ++v) {
      const double len = std::hypot(lattice[3 * v], lattice[3 * v + 1], lattice[3 * v + 2]);
      EXPECT_GT(len, 0) << "cell vector " << v << " is zero: OVITO would ignore the cell";
      EXPECT_EQ(len, v < 2 ? s.info.box[v] : 1.0) << v;
    }
    EXPECT_NE(header.find("pbc=\"T T F\""), std::string::npos) << header;
    const Snapshot back = read_snapshot((dir / name).string());
    EXPECT_EQ(back.info.dim, 2);
    EXPECT_EQ(back.position, s.position);
    EXPECT_EQ(back.velocity, s.velocity);
  }
  const std::string ovito_header = header_of(dir / "ovito.xyz");
  EXPECT_NE(ovito_header.find(":pos:R:2:velo:R:2:"), std::string::npos) << ovito_header;
  const std::string ase_header = header_of(dir / "ase.xyz");
  EXPECT_NE(ase_header.find(":pos:R:3:momenta:R:3:"), std::string::npos) << ase_header;
}

// ASE writes a 2D trajectory of three frames by its defaults (momenta, masses, pbc "T T F", a
// rectangular cell with a zero third vector, an info key per frame): every frame is read, as
// 2D, with velocity = momenta / masses and the cell's aspect ratio. The values are binary
// fractions, so ASE's %.8f printing keeps them exact.
TEST(Interop, WeReadWhatAseWrites) {
  if (!python_has("ase.io")) GTEST_SKIP() << kPython << " has no ase (python3-ase)";
  const fs::path dir = scratch("ase_writes");
  const std::string out =
      python(dir,
             "import ase, ase.io, numpy as np\n"
             "frames = []\n"
             "for k in range(3):\n"
             "    a = ase.Atoms('HeArHe', positions=[[1, 2, 0], [3.5, 0.25, 0], [7, 5, 0]],\n"
             "                  cell=[12, 6, 0], pbc=[True, True, False])\n"
             "    a.set_masses([2, 4, 2])\n"
             "    a.set_velocities([[0.5 * k, -1, 0], [0.25, 0.125, 0], [0, 2, 0]])\n"
             "    a.info['Time'] = 10.0 * k\n"
             "    frames.append(a)\n"
             "ase.io.write('traj.extxyz', frames, format='extxyz')\n");
  ASSERT_EQ(out.rfind("FAILED", 0), std::string::npos) << out;
  const SnapshotFile f = open_snapshots((dir / "traj.extxyz").string());
  ASSERT_EQ(f.frame_count(), 3u);
  for (std::size_t k = 0; k < 3; ++k) {
    const Snapshot s = f.read(k);
    EXPECT_EQ(s.info.dim, 2);
    EXPECT_EQ(s.info.time, 10.0 * k);
    EXPECT_EQ(s.info.box, Eigen::Vector3d(12, 6, 0));
    ASSERT_EQ(s.size(), 3u);
    EXPECT_EQ(s.position[1], Eigen::Vector3d(3.5, 0.25, 0));
    ASSERT_TRUE(s.has_velocity());
    EXPECT_EQ(s.velocity[0], Eigen::Vector3d(0.5 * k, -1, 0));
    EXPECT_EQ(s.velocity[1], Eigen::Vector3d(0.25, 0.125, 0));
    EXPECT_EQ(s.velocity[2], Eigen::Vector3d(0, 2, 0));
  }
}

// ASE writes a mixture of H and Au, all at speed 1, with momenta and no masses (ASE takes each
// mass from the element): once with species, once with a Z column and species X (ASE lets Z
// win). Our velocities are ASE's get_velocities() to the last bits, so both elements come out
// at speed 1 (without the element masses Au was drawn at 197 and H at 1).
TEST(Interop, MomentaOfAseMixturesGiveAsesVelocities) {
  if (!python_has("ase.io")) GTEST_SKIP() << kPython << " has no ase (python3-ase)";
  const fs::path dir = scratch("ase_mixture");
  const std::string out = python(
      dir,
      "import ase, ase.io, numpy as np\n"
      "rng = np.random.default_rng(7)\n"
      "n = 200\n"
      "a = ase.Atoms(symbols=['H', 'Au'] * (n // 2), positions=rng.uniform(0, 20, (n, 3)),\n"
      "              cell=[20, 20, 20], pbc=True)\n"
      "d = rng.normal(size=(n, 3))\n"
      "a.set_velocities(d / np.linalg.norm(d, axis=1)[:, None])\n"
      "ase.io.write('species.extxyz', a, format='extxyz')\n"
      "ase.io.write('z.extxyz', a, format='extxyz',\n"
      "             columns=['symbols', 'positions', 'numbers', 'momenta'])\n"
      "lines = open('z.extxyz').read().split('\\n')\n"
      "lines = lines[:2] + ['X ' + l.split(None, 1)[1] if l else l for l in lines[2:]]\n"
      "open('z.extxyz', 'w').write('\\n'.join(lines))\n"
      "for f in ['species.extxyz', 'z.extxyz']:\n"
      "    for v in ase.io.read(f).get_velocities():\n"
      "        print(' '.join(repr(float(x)) for x in v))\n");
  ASSERT_EQ(out.rfind("FAILED", 0), std::string::npos) << out;
  std::istringstream in(out);
  for (const char* name : {"species.extxyz", "z.extxyz"}) {
    SCOPED_TRACE(name);
    const Snapshot s = read_snapshot((dir / name).string());
    ASSERT_EQ(s.size(), 200u);
    double worst = 0;
    double lo[2] = {INFINITY, INFINITY}, hi[2] = {0, 0};  // speeds of H (even i) and Au (odd)
    for (std::size_t i = 0; i < s.size(); ++i) {
      const auto v = numbers(in, 3);
      for (int a = 0; a < 3; ++a) worst = std::max(worst, std::abs(s.velocity[i][a] - v[a]));
      lo[i % 2] = std::min(lo[i % 2], s.velocity[i].norm());
      hi[i % 2] = std::max(hi[i % 2], s.velocity[i].norm());
      // ASE prints momenta with 8 decimals: Au's speed is 1 within 1e-8 / 197.
      ASSERT_NEAR(s.velocity[i].norm(), 1, 1e-7) << "particle " << i;
    }
    EXPECT_LE(worst, 1e-15);
    std::printf("%s: max |v - get_velocities()| = %.3g; speeds H %.9f..%.9f, Au %.9f..%.9f\n",
                name, worst, lo[0], hi[0], lo[1], hi[1]);
    ASSERT_FALSE(s.notes.empty());
    EXPECT_NE(s.notes[0].find("196.966569"), std::string::npos) << s.notes[0];
  }
}

// gsd.hoomd writes a 3D trajectory whose later frames hold only what changed (HOOMD's rule:
// the rest is frame 0's): every frame, box, step, positions (unwrapped when asked) and
// velocities; no time, so none is made up.
TEST(Interop, WeReadWhatTheGsdModuleWrites) {
  if (!python_has("gsd.hoomd")) GTEST_SKIP() << kPython << " has no gsd (python3-gsd)";
  const fs::path dir = scratch("gsd_writes");
  const std::string out = python(dir,
                                 "import gsd.hoomd, numpy as np\n"
                                 "f = gsd.hoomd.open('traj.gsd', 'wb')\n"
                                 "for k in range(3):\n"
                                 "    s = gsd.hoomd.Snapshot()\n"
                                 "    s.configuration.step = 100 * k\n"
                                 "    s.particles.N = 2\n"
                                 "    if k == 0:\n"
                                 "        s.configuration.box = [8, 6, 4, 0, 0, 0]\n"
                                 "        s.particles.types = ['A']\n"
                                 "        s.particles.position = [[1, 2, -1.5], [-3.5, 0.25, 1]]\n"
                                 "        s.particles.image = [[0, 0, 0], [1, 0, -1]]\n"
                                 "        s.particles.diameter = [1, 0.5]\n"
                                 "    s.particles.velocity = [[0.5 * k, 0, -1], [0, 0.25, 0]]\n"
                                 "    f.append(s)\n"
                                 "f.close()\n");
  ASSERT_EQ(out.rfind("FAILED", 0), std::string::npos) << out;
  ReadOptions unwrap;
  unwrap.unwrap = true;
  const SnapshotFile f = open_snapshots((dir / "traj.gsd").string(), unwrap);
  ASSERT_EQ(f.frame_count(), 3u);
  // By default in the cell, as OVITO draws it, the image counts as columns.
  const Snapshot in_cell = read_snapshot((dir / "traj.gsd").string());
  EXPECT_EQ(in_cell.position[1], Eigen::Vector3d(-3.5, 0.25, 1));
  ASSERT_NE(in_cell.column("image_z"), nullptr);
  EXPECT_EQ(in_cell.column("image_z")->values, (std::vector<double>{0, -1}));
  for (std::size_t k = 0; k < 3; ++k) {
    const Snapshot s = f.read(k);
    EXPECT_EQ(s.info.dim, 3);
    EXPECT_EQ(s.info.step, static_cast<std::int64_t>(100 * k));
    EXPECT_FALSE(s.info.has_time);
    EXPECT_EQ(s.info.box, Eigen::Vector3d(8, 6, 4));
    ASSERT_EQ(s.size(), 2u);
    EXPECT_EQ(s.position[0], Eigen::Vector3d(1, 2, -1.5));
    EXPECT_EQ(s.position[1], Eigen::Vector3d(-3.5 + 8, 0.25, 1 - 4));  // unwrapped by image
    EXPECT_EQ(s.radius[1], 0.25);
    EXPECT_EQ(s.velocity[0], Eigen::Vector3d(0.5 * k, 0, -1));
  }
}

// What HOOMD writes unless asked: no velocity chunk in any frame, and gsd.hoomd leaves out frame
// 0's chunks of defaults (the image counts here). No velocities is not every speed 0 (a picture
// of all black on a made-up range); the image counts are columns of zeros; typeid names types.
TEST(Interop, GsdWithoutVelocitiesHasNoneAndMissingChunksAreDefaults) {
  if (!python_has("gsd.hoomd")) GTEST_SKIP() << kPython << " has no gsd (python3-gsd)";
  const fs::path dir = scratch("gsd_no_velocity");
  const std::string out = python(dir,
                                 "import gsd.hoomd\n"
                                 "f = gsd.hoomd.open('traj.gsd', 'wb')\n"
                                 "for k in range(2):\n"
                                 "    s = gsd.hoomd.Snapshot()\n"
                                 "    s.configuration.step = k\n"
                                 "    s.configuration.box = [10, 10, 0, 0, 0, 0]\n"
                                 "    s.particles.N = 3\n"
                                 "    s.particles.types = ['big', 'small']\n"
                                 "    s.particles.typeid = [1, 0, 1]\n"
                                 "    s.particles.position = [[1, 1, 0], [-2, 3, 0], [4, -4, 0]]\n"
                                 "    s.particles.image = [[0, 0, 0], [k, 0, 0], [0, 0, 0]]\n"
                                 "    f.append(s)\n"
                                 "f.close()\n");
  ASSERT_EQ(out.rfind("FAILED", 0), std::string::npos) << out;
  const SnapshotFile f = open_snapshots((dir / "traj.gsd").string(), {});
  for (std::size_t k = 0; k < 2; ++k) {
    const Snapshot s = f.read(k);
    EXPECT_FALSE(s.has_velocity()) << "frame " << k;
    EXPECT_EQ(s.type_names, (std::vector<std::string>{"big", "small"}));
    EXPECT_EQ(s.type, (std::vector<std::uint32_t>{1, 0, 1}));
    ASSERT_NE(s.column("image_x"), nullptr) << "frame " << k;
    EXPECT_EQ(s.column("image_x")->values, (std::vector<double>{0, double(k), 0}));
    ASSERT_NE(s.column("mass"), nullptr);
    EXPECT_EQ(s.column("mass")->values, (std::vector<double>(3, 1.0)));
  }
}

// ASE's species are the particle types (sorted by name), as OVITO colours them.
TEST(Interop, AseSpeciesAreParticleTypes) {
  if (!python_has("ase.io")) GTEST_SKIP() << kPython << " has no ase (python3-ase)";
  const fs::path dir = scratch("ase_species");
  const std::string out = python(dir,
                                 "from ase import Atoms\n"
                                 "import ase.io\n"
                                 "a = Atoms('HeArHeNe', positions=[[0, 0, 0], [2, 0, 0], [4, 0, "
                                 "0], [6, 0, 0]], cell=[10, 10, 10], pbc=True)\n"
                                 "ase.io.write('a.extxyz', a)\n");
  ASSERT_EQ(out.rfind("FAILED", 0), std::string::npos) << out;
  const Snapshot s = read_snapshot((dir / "a.extxyz").string());
  EXPECT_FALSE(s.has_velocity());
  EXPECT_EQ(s.type_names, (std::vector<std::string>{"Ar", "He", "Ne"}));
  EXPECT_EQ(s.type, (std::vector<std::uint32_t>{1, 0, 1, 2}));
}

// A LAMMPS dump of two atom types written by lmp itself: its types, in numeric order.
TEST(Interop, LammpsTypesAreParticleTypes) {
  if (!fs::exists("/usr/bin/lmp")) GTEST_SKIP() << "no /usr/bin/lmp (lammps)";
  const fs::path dir = scratch("lmp_types");
  std::ofstream(dir / "in.lmp") << "units lj\nboundary p p p\nregion b block 0 6 0 6 0 6\n"
                                   "create_box 2 b\ncreate_atoms 1 single 1 1 1\n"
                                   "create_atoms 2 single 3 3 3\ncreate_atoms 1 single 5 5 5\n"
                                   "mass * 1\ndump d all custom 1 d.dump id type x y z\n"
                                   "dump_modify d sort id\nrun 0\n";
  const std::string cmd = "cd " + dir.string() + " && /usr/bin/lmp -in in.lmp -log none > out.txt 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << "lmp failed; see " << (dir / "out.txt");
  const Snapshot s = read_snapshot((dir / "d.dump").string());
  EXPECT_FALSE(s.has_velocity());
  EXPECT_EQ(s.type_names, (std::vector<std::string>{"1", "2"}));
  EXPECT_EQ(s.type, (std::vector<std::uint32_t>{0, 1, 0}));
}

}  // namespace
}  // namespace gs
