// The shared snapshot reader: formats told apart by content, frames read one at a time, the
// dimension stated or inferred, and hostile files refused with one line naming file and line.
#include "io/snapshot_file.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <tuple>

#include "io/gsd.h"
#include "sim/error.h"
#include "sim/escaped.h"
#include "tests/sim/test_output.h"

namespace gs {
namespace {

SnapshotFile from_text(const std::string& text, ReadOptions o = {}) {
  return open_snapshots(MappedFile::from_bytes("mem.xyz", text), o);
}

// The message of the UserError that opening and reading every frame throws, or "accepted".
std::string error_of(const std::string& text, ReadOptions o = {}) {
  try {
    const SnapshotFile f = from_text(text, o);
    for (std::size_t k = 0; k < f.frame_count(); ++k) f.read(k);
  } catch (const UserError& e) {
    return e.what();
  }
  return "accepted";
}

TEST(ExtXyz, ReadsAseDefaultOutputWithMomenta) {
  // What ASE 3.22's write() gives for Atoms with momenta and masses.
  const auto s =
      from_text(
          "2\nLattice=\"10.0 0.0 0.0 0.0 12.0 0.0 0.0 0.0 8.0\" "
          "Properties=species:S:1:pos:R:3:masses:R:1:momenta:R:3 time=2.5 pbc=\"T T T\"\n"
          "Ar 1.0 2.0 3.0 2.0 4.0 0.0 -2.0\n"
          "Ar 4.0 5.0 6.0 2.0 0.0 2.0 1.0\n")
          .read(0);
  EXPECT_EQ(s.info.dim, 3);
  EXPECT_EQ(s.info.box, Eigen::Vector3d(10, 12, 8));
  EXPECT_EQ(s.info.time, 2.5);
  ASSERT_TRUE(s.has_velocity());
  EXPECT_EQ(s.velocity[0], Eigen::Vector3d(2, 0, -1));  // momenta / masses
  EXPECT_EQ(s.velocity[1], Eigen::Vector3d(0, 1, 0.5));
  EXPECT_EQ(s.active, (std::vector<std::uint8_t>{1, 1}));
  EXPECT_EQ(s.radius[1], 0.5);
}

TEST(ExtXyz, MomentaWithoutMassesMeanUnitMass) {
  const auto s =
      from_text("1\nProperties=species:S:1:pos:R:3:momenta:R:3\nX 1 2 3 4 5 6\n").read(0);
  EXPECT_EQ(s.velocity[0], Eigen::Vector3d(4, 5, 6));
}

TEST(ExtXyz, TwoDimensionalConventions) {
  // OVITO's 2D form: two position components.
  auto s = from_text(
               "2\nProperties=Z:I:1:pos:R:2:velo:R:2 Lattice=\"5 0 0 0 7 0 0 0 1\"\n"
               "6 1 2 3 4\n8 3 4 5 6\n")
               .read(0);
  EXPECT_EQ(s.info.dim, 2);
  EXPECT_EQ(s.position[1], Eigen::Vector3d(3, 4, 0));
  EXPECT_EQ(s.velocity[1], Eigen::Vector3d(5, 6, 0));
  EXPECT_EQ(s.info.box, Eigen::Vector3d(5, 7, 0));
  ASSERT_NE(s.column("Z"), nullptr);  // species as Z: an extra column
  EXPECT_EQ(s.column("Z")->values, (std::vector<double>{6, 8}));

  // pbc "T T F" with a zero third lattice vector, z not all zero: stated 2D, so z must be 0.
  const std::string ttf =
      "1\nLattice=\"5 0 0 0 7 0 0 0 0\" pbc=\"T T F\" Properties=species:S:1:pos:R:3\n";
  EXPECT_EQ(from_text(ttf + "C 1 2 0\n").read(0).info.dim, 2);
  EXPECT_NE(error_of(ttf + "C 1 2 0.5\n").find("line 3"), std::string::npos);

  // Nothing stated: all z exactly 0 is 2D, one non-zero z is 3D.
  const std::string plain = "2\nplain\nC 1 2 0\nC 3 4 ";
  EXPECT_EQ(from_text(plain + "0\n").read(0).info.dim, 2);
  EXPECT_EQ(from_text(plain + "1e-300\n").read(0).info.dim, 3);
  // "T T T" with a full lattice, z = 0: still 2D by the z rule.
  EXPECT_EQ(from_text("1\nLattice=\"5 0 0 0 5 0 0 0 5\" pbc=\"T T T\"\nC 1 2 0\n").read(0).info.dim,
            2);
  // --dim overrides both ways; the components beyond it are dropped.
  ReadOptions three;
  three.dim = 3;
  EXPECT_EQ(from_text(plain + "0\n", three).read(0).info.dim, 3);
  ReadOptions two;
  two.dim = 2;
  const auto flat = from_text(plain + "9\n", two).read(0);
  EXPECT_EQ(flat.info.dim, 2);
  EXPECT_EQ(flat.position[1], Eigen::Vector3d(3, 4, 0));
}

TEST(ExtXyz, LatticeRectangularInAnyOrderTriclinicRefused) {
  const std::string props = "\" Properties=species:S:1:pos:R:3\nC 1 2 3\n";
  auto s = from_text("1\nLattice=\"0 0 9 4 0 0 0 -6 0\" Origin=\"1 2 3" + props).read(0);
  EXPECT_EQ(s.info.box, Eigen::Vector3d(4, 6, 9));
  EXPECT_EQ(s.info.origin, Eigen::Vector3d(1, -4, 3));  // the -6 vector reaches down from y = 2
  const auto msg = error_of("1\nLattice=\"4 0 0 1 5 0 0 0 6" + props);
  EXPECT_NE(msg.find("triclinic"), std::string::npos) << msg;
  EXPECT_NE(msg.find("line 2"), std::string::npos) << msg;
  EXPECT_NE(msg.find("mem.xyz"), std::string::npos) << msg;
}

TEST(ExtXyz, MultiFrameAndExtraColumns) {
  const std::string frame0 =
      "2\nTime=1 Properties=species:S:1:pos:R:3:forces:R:3:c_pe:R:1:fixed:L:1\n"
      "A 0 0 0 1 2 3 -1.5 T\nB 1 0 0 4 5 6 -2.5 F\n";
  const std::string frame1 = "1\nTime=2.5 Properties=species:S:1:pos:R:3:energy:R:1\nA 9 9 9 7\n";
  const SnapshotFile f = from_text(frame0 + frame1 + "\n\n");
  ASSERT_EQ(f.frame_count(), 2u);
  const Snapshot a = f.read(0), b = f.read(1);
  EXPECT_EQ(a.info.time, 1);
  EXPECT_EQ(b.info.time, 2.5);
  ASSERT_EQ(b.size(), 1u);
  EXPECT_EQ(b.position[0], Eigen::Vector3d(9, 9, 9));
  ASSERT_NE(a.column("forces_y"), nullptr);
  EXPECT_EQ(a.column("forces_y")->values, (std::vector<double>{2, 5}));
  EXPECT_EQ(a.column("c_pe")->values, (std::vector<double>{-1.5, -2.5}));
  EXPECT_EQ(a.column("fixed")->values, (std::vector<double>{1, 0}));
  EXPECT_EQ(a.column("energy"), nullptr);
  EXPECT_EQ(b.column("energy")->values, (std::vector<double>{7}));

  EXPECT_EQ(error_of(frame0 + frame1.substr(0, frame1.size() - 1)),
            "accepted");  // no final newline
  try {
    f.read(2);
    ADD_FAILURE() << "frame 2 of 2 was read";
  } catch (const UserError& e) {
    EXPECT_NE(std::string(e.what()).find("has 2 frames"), std::string::npos) << e.what();
  }
}

TEST(ExtXyz, CountsAreCheckedBeforeAnythingIsAllocated) {
  const std::string small = "1\nProperties=species:S:1:pos:R:3\nX 0 0 0\n";
  // A count far beyond the file: an error about the frame, not bad_alloc.
  auto msg = error_of("1000000000000000\ncomment\nX 0 0 0\n");
  EXPECT_NE(msg.find("truncated"), std::string::npos) << msg;
  EXPECT_NE(msg.find("line 1"), std::string::npos) << msg;
  msg = error_of("100000000\n" + small.substr(2));
  EXPECT_NE(msg.find("truncated"), std::string::npos) << msg;
  // A count smaller than the lines: the next "count line" is a particle line.
  std::string body;
  for (int i = 0; i < 20; ++i) body += "X 0 0 0\n";
  msg = error_of("10\nProperties=species:S:1:pos:R:3\n" + body);
  EXPECT_NE(msg.find("line 13"), std::string::npos) << msg;
  EXPECT_NE(msg.find("count of frame 0"), std::string::npos) << msg;
  // Property counts adding past 2^31, or more columns than the lines can hold.
  msg = error_of("1\nProperties=pos:R:3:a:R:2147483647:b:R:2147483647\n0 0 0\n");
  EXPECT_NE(msg.find("line 2"), std::string::npos) << msg;
  msg = error_of("2\nProperties=pos:R:3:a:R:100000\n0 0 0\n0 0 0\n");
  EXPECT_NE(msg.find("line 2"), std::string::npos) << msg;
  msg = error_of("1\nProperties=pos:R:-3\n0 0 0\n");
  EXPECT_NE(msg.find("line 2"), std::string::npos) << msg;
}

TEST(ExtXyz, NonFiniteAndMalformedValues) {
  const std::string head = "2\nProperties=species:S:1:pos:R:3:velo:R:3\nX 0 0 0 0 0 0\n";
  for (const char* bad : {"nan", "inf", "-inf", "1e400", "0x1", "1.0.0", ""}) {
    const auto msg = error_of(head + "X 1 " + bad + " 0 0 0 0\n");
    EXPECT_NE(msg.find("line 4"), std::string::npos) << bad << ": " << msg;
  }
  EXPECT_NE(error_of(head + "X 1 1 1 0 0 0 7\n").find("found 8"), std::string::npos);
}

// Frames of many rows are scanned in two halves at once (io/text_scan.h): the values are the
// same as one pass gives, and of two bad lines the earlier one is named.
TEST(SnapshotFile, LargeFramesReadInTwoHalvesAsInOnePass) {
  const int n = 100000;  // above the split threshold of 2^15 rows
  std::string xyz = std::to_string(n) + "\nProperties=species:S:1:pos:R:3:velo:R:3\n";
  std::string dump = "ITEM: TIMESTEP\n0\nITEM: NUMBER OF ATOMS\n" + std::to_string(n) +
                     "\nITEM: BOX BOUNDS pp pp pp\n0 10\n0 10\n0 10\nITEM: ATOMS id x y z ix iy "
                     "iz vx\n";
  for (int i = 0; i < n; ++i) {
    const std::string x = std::to_string(i % 1000) + ".25", y = std::to_string(i / 1000);
    xyz += "X " + x + " " + y + " 1 " + std::to_string(i) + " 0 -1\n";
    dump += std::to_string(i + 1) + " " + std::to_string(i % 10) + " 1 2 " +
            std::to_string(i % 3 - 1) + " 0 0 " + std::to_string(i) + "\n";
  }
  const Snapshot a = from_text(xyz).read(0);
  ASSERT_EQ(a.size(), static_cast<std::size_t>(n));
  for (int i = 0; i < n; i += 997) {
    EXPECT_EQ(a.position[i], Eigen::Vector3d(i % 1000 + 0.25, i / 1000, 1)) << i;
    EXPECT_EQ(a.velocity[i], Eigen::Vector3d(i, 0, -1)) << i;
  }
  ReadOptions unwrap;
  unwrap.unwrap = true;
  const Snapshot d = open_snapshots(MappedFile::from_bytes("big.dump", dump), unwrap).read(0);
  ASSERT_EQ(d.size(), static_cast<std::size_t>(n));
  for (int i = 0; i < n; i += 997) {  // x unwrapped by its own row's image flag
    EXPECT_EQ(d.position[i].x(), i % 10 + 10.0 * (i % 3 - 1)) << i;
    EXPECT_EQ(d.velocity[i].x(), i) << i;
  }
  // Line numbers: the count and comment lines come first, so row i is line i + 3.
  auto spoil = [&](std::string text, std::vector<int> rows) {
    for (int r : rows) {
      std::size_t at = 0;
      for (int k = 0; k < r + 2; ++k) at = text.find('\n', at) + 1;
      text.replace(at, 1, "Y 0 zz");  // "X 1.25 ..." becomes "Y 0 zz1.25 ...": not a number
    }
    return error_of(text);
  };
  EXPECT_NE(spoil(xyz, {80000}).find("line 80003"), std::string::npos) << spoil(xyz, {80000});
  EXPECT_NE(spoil(xyz, {10, 80000}).find("line 13:"), std::string::npos);
  EXPECT_NE(spoil(xyz, {49999, 50000}).find("line 50002:"), std::string::npos);
}

TEST(SnapshotFile, UnknownContentIsNamed) {
  const auto msg = error_of("hello world\n1 2 3\n");
  EXPECT_NE(msg.find("mem.xyz"), std::string::npos) << msg;
  EXPECT_NE(msg.find("hello world"), std::string::npos) << msg;
  EXPECT_NE(error_of(""), "accepted");
  EXPECT_NE(error_of("\n\n  \n"), "accepted");
}

// Finite but absurd coordinates and radii (1e300 in text, 3e38 in GSD's floats) were drawn as an
// empty picture; they are refused naming the file, the frame and the column as the file names
// it. The bound itself (kMaxCoordinate) is accepted.
TEST(SnapshotFile, AbsurdCoordinatesAndRadiiAreRefusedNamingFrameAndColumn) {
  const std::string fine = "1\nProperties=species:S:1:pos:R:3:radius:R:1\nA 1 2 3 0.5\n";
  auto xyz = [](const std::string& row) {
    return "1\nProperties=species:S:1:pos:R:3:radius:R:1\n" + row + "\n";
  };
  auto dump = [](const std::string& columns, const std::string& row) {
    return "ITEM: TIMESTEP\n0\nITEM: NUMBER OF ATOMS\n1\nITEM: BOX BOUNDS pp pp pp\n0 10\n0 10\n"
           "0 10\nITEM: ATOMS " + columns + "\n" + row + "\n";
  };
  const std::vector<std::pair<std::string, std::string>> cases = {
      {fine + xyz("A 1e300 0 0 0.5"), "frame 1, column 'pos': particle 0 has x = 1e+300"},
      {xyz("A 0 -2e13 0 0.5"), "frame 0, column 'pos': particle 0 has y = -2e+13"},
      {xyz("A 0 0 0 1e300"), "frame 0, column 'radius': particle 0 has radius 1e+300"},
      {dump("id x y z", "1 1e300 1 1"), "frame 0, column 'x': particle 0 has x = 1e+300"},
      {dump("id xs ys zs", "1 0.5 1e299 0.5"), "column 'ys': particle 0 has y = 1e+299"},
      {dump("id x y z diameter", "1 1 1 1 1e300"),
       "column 'diameter': particle 0 has radius 5e+299"},
  };
  for (const auto& [text, says] : cases) {
    const std::string msg = error_of(text);
    EXPECT_NE(msg.find("snapshot 'mem.xyz' frame "), std::string::npos) << msg;
    EXPECT_NE(msg.find(says), std::string::npos) << text << "\n" << msg;
  }
  EXPECT_EQ(error_of(xyz("A 1e12 -1e12 0 1e12")), "accepted");

  // GSD holds floats: 3e38 is finite there.
  for (const auto& [x, r, says] :
       {std::tuple{3e38, 0.5, std::string("column 'particles/position': particle 1 has x = ")},
        std::tuple{1.0, 1e38, std::string("column 'particles/diameter': particle 1 has radius")}}) {
    Snapshot s;
    s.info.dim = 2;
    s.position = {{1, 2, 0}, {x, 0, 0}};
    s.radius = {0.5, r};
    s.active = {1, 1};
    const std::string path = test::out_path("absurd.gsd");
    write_gsd(path, s);
    std::string msg = "accepted";
    try {
      read_snapshot(path);
    } catch (const UserError& e) {
      msg = e.what();
    }
    EXPECT_NE(msg.find("absurd.gsd' frame 0, " + says), std::string::npos) << msg;
  }
}

// A frame of no particles is read as one (its Properties were blamed for columns its no lines
// could not hold).
TEST(ExtXyz, AFrameOfNoParticlesIsRead) {
  const SnapshotFile f = from_text("0\nProperties=species:S:1:pos:R:3 Time=1\n");
  ASSERT_EQ(f.frame_count(), 1u);
  EXPECT_EQ(f.read(0).size(), 0u);
}

// The one quoting rule for input in messages: controls and bytes that are not UTF-8 as \xNN,
// UTF-8 text kept, long text cut.
TEST(SnapshotFile, QuotedInputIsEscaped) {
  EXPECT_EQ(escaped("a\x1b[31mb\x07\n"), "a\\x1B[31mb\\x07\\x0A");
  EXPECT_EQ(escaped("caf\xc3\xa9 \xff\xc2\x9b"), "caf\xc3\xa9 \\xFF\\xC2\\x9B");
  EXPECT_EQ(escaped("abcdef", 3), "abc...");
  const std::string msg = error_of("\x1b]0;title\x07 1 2\n");
  EXPECT_EQ(msg.find('\x1b'), std::string::npos) << msg;
  EXPECT_NE(msg.find("\\x1B]0;title\\x07 1 2"), std::string::npos) << msg;
}

}  // namespace
}  // namespace gs
