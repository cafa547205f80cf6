// Files that other programs write: hand-written samples in assets/io/ (the CI path), and files
// written on the spot by LAMMPS, ASE and the gsd module when they are installed.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "io/snapshot_file.h"
#include "sim/error.h"

namespace gs {
namespace {

namespace fs = std::filesystem;

std::string asset(const std::string& name) {
  return std::string(GRAINSHOCK_ASSETS_DIR) + "/io/" + name;
}

fs::path scratch(const std::string& name) {
  const fs::path d = fs::path(GRAINSHOCK_TEST_OUTPUT_DIR) / name;
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

void expect_near(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double tol = 1e-12) {
  EXPECT_LT((a - b).norm(), tol) << a.transpose() << " vs " << b.transpose();
}

// By default the positions in the cell, as OVITO draws them: x as written, the image flags
// kept as columns; with --unwrap (ReadOptions::unwrap) x plus the flags times the box.
TEST(LammpsDump, PositionsInTheCellUnlessUnwrapped) {
  const Snapshot a = read_snapshot(asset("custom_3d.lammpstrj"));
  expect_near(a.position[0], {1, 2, 2.5});
  expect_near(a.position[2], {4.5, 3.5, 2});
  ASSERT_NE(a.column("iy"), nullptr);
  EXPECT_EQ(a.column("iy")->values, (std::vector<double>{0, 0, 2}));
  ASSERT_EQ(a.notes.size(), 1u);
  EXPECT_NE(a.notes[0].find("--unwrap"), std::string::npos);
  // xu alone is folded into the cell.
  const std::string xu = "ITEM: TIMESTEP\n0\nITEM: NUMBER OF ATOMS\n1\nITEM: BOX BOUNDS pp pp pp\n"
                         "0 10\n0 10\n0 10\nITEM: ATOMS id xu yu zu\n1 23 -4 5\n";
  const Snapshot u = open_snapshots(MappedFile::from_bytes("xu.dump", xu)).read(0);
  expect_near(u.position[0], {3, 6, 5});
  ReadOptions unwrap;
  unwrap.unwrap = true;
  expect_near(open_snapshots(MappedFile::from_bytes("xu.dump", xu), unwrap).read(0).position[0],
              {23, -4, 5});
}

TEST(LammpsDump, CustomColumnsInAnyOrderWithImagesAndScaledFrames) {
  ReadOptions unwrap;
  unwrap.unwrap = true;
  const SnapshotFile f = open_snapshots(asset("custom_3d.lammpstrj"), unwrap);
  EXPECT_STREQ(f.format(), "LAMMPS dump");
  ASSERT_EQ(f.frame_count(), 2u);
  const Snapshot a = f.read(0);
  EXPECT_EQ(a.info.dim, 3);
  EXPECT_EQ(a.info.step, 100);
  EXPECT_EQ(a.info.time, 0.5);
  EXPECT_EQ(a.info.origin, Eigen::Vector3d(-5, 0, 1));
  EXPECT_EQ(a.info.box, Eigen::Vector3d(10, 4, 2));
  ASSERT_EQ(a.size(), 3u);
  expect_near(a.position[0], {11, 2, 0.5});  // x + ix Lx, z + iz Lz
  expect_near(a.position[2], {4.5, 11.5, 2});
  expect_near(a.velocity[0], {0.1, 0.2, 0.3});
  expect_near(a.velocity[2], {3, 2, -1});
  EXPECT_EQ(a.radius, (std::vector<double>{0.25, 0.5, 0.75}));
  ASSERT_NE(a.column("c_pe"), nullptr);
  EXPECT_EQ(a.column("c_pe")->values, (std::vector<double>{-3.5, -1, 0}));
  EXPECT_EQ(a.column("id")->values, (std::vector<double>{7, 3, 5}));
  EXPECT_EQ(a.column("ix"), nullptr);  // used for unwrapping

  const Snapshot b = f.read(1);  // scaled, a triclinic header with zero tilt
  EXPECT_EQ(b.info.step, 150);
  ASSERT_EQ(b.size(), 2u);
  expect_near(b.position[0], {0, 1, 2});
  expect_near(b.position[1], {-5, 4, 3});
  EXPECT_FALSE(b.has_velocity());
  EXPECT_EQ(b.radius[1], 0.5);
}

TEST(LammpsDump, TwoDimensionalDumpAtomIsDrawnAs2D) {
  const Snapshot s = read_snapshot(asset("atom_2d.lammpstrj"));
  EXPECT_EQ(s.info.dim, 2);
  EXPECT_EQ(s.info.box, Eigen::Vector3d(20, 10, 0));
  expect_near(s.position[0], {5, 5, 0});
  expect_near(s.position[1], {15, 1, 0});
}

std::string error_of(const std::string& text) {
  try {
    const SnapshotFile f = open_snapshots(MappedFile::from_bytes("bad.dump", text));
    for (std::size_t k = 0; k < f.frame_count(); ++k) f.read(k);
  } catch (const UserError& e) {
    return e.what();
  }
  return "accepted";
}

TEST(LammpsDump, BadDumpsNameFileAndLine) {
  const std::string head = "ITEM: TIMESTEP\n0\nITEM: NUMBER OF ATOMS\n2\n";
  const std::string box = "ITEM: BOX BOUNDS pp pp pp\n0 1\n0 1\n0 1\n";
  const std::string atoms = "ITEM: ATOMS id x y z\n1 0 0 0\n2 0.5 0.5 0.5\n";
  EXPECT_EQ(error_of(head + box + atoms), "accepted");
  auto msg = error_of(head + atoms);  // no BOX BOUNDS
  EXPECT_NE(msg.find("BOX BOUNDS"), std::string::npos) << msg;
  EXPECT_NE(msg.find("line 5"), std::string::npos) << msg;
  EXPECT_NE(msg.find("bad.dump"), std::string::npos) << msg;
  msg = error_of("ITEM: NUMBER OF ATOMS\n2\n" + box + atoms);  // no TIMESTEP
  EXPECT_NE(msg.find("TIMESTEP"), std::string::npos) << msg;
  msg = error_of(head + box + "ITEM: ATOMS id x y z\n1 0 0 0\n");  // truncated
  EXPECT_NE(msg.find("truncated"), std::string::npos) << msg;
  msg = error_of(head + box + atoms + "3 1 1 1\n");  // count below the lines
  EXPECT_NE(msg.find("line 12"), std::string::npos) << msg;
  msg = error_of(head + box + "ITEM: ATOMS id x y z\n1 0 0 0\n2 0.5 nan 0.5\n");
  EXPECT_NE(msg.find("line 11"), std::string::npos) << msg;
  msg = error_of(head + "ITEM: BOX BOUNDS xy xz yz pp pp pp\n0 1 0.5\n0 1 0\n0 1 0\n" + atoms);
  EXPECT_NE(msg.find("triclinic"), std::string::npos) << msg;
  msg = error_of("ITEM: TIMESTEP\n0\nITEM: NUMBER OF ATOMS\n1000000000000\n" + box + atoms);
  EXPECT_NE(msg.find("truncated"), std::string::npos) << msg;
  msg = error_of(head + box + "ITEM: ATOMS id type\n1 1\n2 1\n");
  EXPECT_NE(msg.find("no x"), std::string::npos) << msg;
  msg = error_of("ITEM: NUMBER OF ENTRIES\n2\n");
  EXPECT_NE(msg.find("unknown section"), std::string::npos) << msg;
}

TEST(ExtXyzFromOthers, AseMomentaAndOvito2D) {
  const Snapshot a = read_snapshot(asset("ase_momenta.extxyz"));
  EXPECT_EQ(a.info.dim, 2);  // pbc "T T F" and a zero third lattice vector
  EXPECT_EQ(a.info.time, 4);
  EXPECT_EQ(a.info.box, Eigen::Vector3d(12, 6, 0));
  expect_near(a.velocity[0], {1, -2, 0});  // momenta / masses
  expect_near(a.velocity[2], {0, 2, 0});

  const Snapshot o = read_snapshot(asset("ovito_2d.xyz"));
  EXPECT_EQ(o.info.dim, 2);  // pos:R:2
  EXPECT_EQ(o.info.origin, Eigen::Vector3d(-15, -5, 0));
  EXPECT_EQ(o.info.box, Eigen::Vector3d(30, 10, 0));
  expect_near(o.velocity[1], {0, 2, 0});
  EXPECT_EQ(o.radius, (std::vector<double>{0.5, 1}));
}

// ASE writes momenta and no masses; each mass is the element's (ASE's table): H, Au and argon
// (lower case, as ASE's reader capitalises it) all at speed 1, the made-up species A at mass 1.
// With a Z column, Z decides (as in ASE), X and Z = 0 keep mass 1. The note names the masses.
TEST(ExtXyzFromOthers, MomentaWithoutMassesTakeTheElementsMass) {
  const Snapshot s = read_snapshot(asset("ase_elements.extxyz"));
  ASSERT_EQ(s.size(), 4u);
  for (std::size_t i = 0; i < 4; ++i) expect_near(s.velocity[i], {0.6, 0.8, 0});
  ASSERT_EQ(s.notes.size(), 2u);  // the masses, and the missing time
  EXPECT_NE(s.notes[0].find("Au 196.966569"), std::string::npos) << s.notes[0];
  EXPECT_NE(s.notes[0].find("H 1.008"), std::string::npos) << s.notes[0];
  EXPECT_NE(s.notes[0].find("ar 39.948"), std::string::npos) << s.notes[0];
  EXPECT_NE(s.notes[0].find("mass 1 for A"), std::string::npos) << s.notes[0];
  EXPECT_FALSE(s.info.has_time);

  const Snapshot z = read_snapshot(asset("ase_atomic_numbers.extxyz"));
  ASSERT_EQ(z.size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) expect_near(z.velocity[i], {0.6, 0.8, 0});
  ASSERT_NE(z.column("Z"), nullptr);  // still there to colour by
  EXPECT_NE(z.notes.at(0).find("Z=79 (Au) 196.966569"), std::string::npos) << z.notes[0];
  EXPECT_TRUE(z.info.has_time);
  EXPECT_EQ(z.info.time, 2.5);

  // Ours (species X, ASE's mass 1 too) assume nothing: no note.
  const Snapshot x = open_snapshots(MappedFile::from_bytes(
      "x.xyz", "1\nProperties=species:S:1:pos:R:3:momenta:R:3 Time=1\nX 0 0 0 2 1 0\n")).read(0);
  expect_near(x.velocity[0], {2, 1, 0});
  EXPECT_TRUE(x.notes.empty()) << x.notes.front();

  // A masses column wins over the elements.
  const std::string with_masses =
      "1\nProperties=species:S:1:pos:R:3:masses:R:1:momenta:R:3\nAu 0 0 0 2 1 0 0\n";
  const Snapshot m = open_snapshots(MappedFile::from_bytes("masses.xyz", with_masses)).read(0);
  expect_near(m.velocity[0], {0.5, 0, 0});
}

// Runs a command; true if it exited 0.
bool run(const std::string& cmd) {
  return std::system(cmd.c_str()) == 0;
}

TEST(LammpsDump, FilesWrittenByLammps) {
  if (!run("command -v lmp > /dev/null 2>&1")) GTEST_SKIP() << "lmp (LAMMPS) is not installed";
  const fs::path d = scratch("lammps");
  std::ofstream(d / "in.test") << "units lj\ndimension 2\nboundary p p p\natom_style sphere\n"
                                  "lattice sq 0.5\nregion box block 0 6 0 4 -0.5 0.5\n"
                                  "create_box 1 box\ncreate_atoms 1 box\n"
                                  "set type 1 diameter 0.8\n"
                                  "velocity all create 1.0 4928459 loop geom\n"
                                  "pair_style soft 1.0\npair_coeff 1 1 0.0\n"
                                  "fix 1 all nve\nfix 2 all enforce2d\n"
                                  "dump 1 all custom 5 custom.dump id type xu yu zu vx vy vz "
                                  "radius\n"
                                  "dump 2 all atom 5 atom.dump\nrun 10\n";
  ASSERT_TRUE(run("cd " + d.string() + " && lmp -in in.test -log none -screen none"));
  const SnapshotFile custom = open_snapshots((d / "custom.dump").string());
  const SnapshotFile atom = open_snapshots((d / "atom.dump").string());
  ASSERT_EQ(custom.frame_count(), 3u);  // steps 0, 5, 10
  ASSERT_EQ(atom.frame_count(), 3u);
  for (std::size_t k = 0; k < 3; ++k) {
    const Snapshot c = custom.read(k), a = atom.read(k);
    EXPECT_EQ(c.info.step, static_cast<std::int64_t>(5 * k));
    EXPECT_EQ(c.info.dim, 2);
    EXPECT_EQ(a.info.dim, 2);
    ASSERT_EQ(c.size(), 24u);
    ASSERT_EQ(a.size(), 24u);
    EXPECT_TRUE(c.has_velocity());
    EXPECT_NEAR(c.radius[0], 0.4, 1e-6);
    // The lattice spacing is sqrt(1 / 0.5): the box is 6 x 4 of them.
    EXPECT_NEAR(c.info.box.x(), 6 * std::sqrt(2.0), 1e-12);
    EXPECT_NEAR(c.info.box.y(), 4 * std::sqrt(2.0), 1e-12);
  }
  // At step 0 both dumps hold the lattice, in id order. Both print 6 significant digits: xu
  // (< 8.5) within 5e-6, xs within 5e-7 of the box edge 8.5, so each coordinate agrees within
  // 1e-5 and the 2D distance within 1.5e-5.
  const Snapshot c0 = custom.read(0), a0 = atom.read(0);
  for (std::size_t i = 0; i < 24; ++i)
    EXPECT_LT((c0.position[i] - a0.position[i]).norm(), 1.5e-5) << i;
}

}  // namespace
}  // namespace gs
