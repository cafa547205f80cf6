#include "io/snapshot_file.h"
#include "io/xyz.h"

#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "sim/error.h"
#include "tests/sim/test_output.h"

namespace gs {
namespace {

namespace fs = std::filesystem;

using test::out_path;

std::string write_text(const std::string& name, const std::string& text) {
  const auto p = out_path(name);
  std::ofstream(p, std::ios::binary) << text;
  return p;
}

// The message of the UserError read_snapshot throws, or "accepted".
std::string read_error(const std::string& path) {
  try {
    read_snapshot(path);
  } catch (const UserError& e) {
    return e.what();
  }
  return "accepted";
}

Snapshot sample(bool with_velocity, bool with_first) {
  Snapshot s;
  s.info.dim = 2;
  s.info.set_cubic_box(63.245553203367585);
  s.info.time = 1.0 / 3.0;
  s.info.density = 0.25;
  s.info.restitution = 0.1;
  s.info.cutoff = 1e-4;
  s.info.speed = 1;
  s.info.seed = 18446744073709551615ull;
  for (int i = 0; i < 5; ++i) {
    s.position.emplace_back(0.1 * i + 1e-17, -std::sqrt(2.0) * i, 0);
    if (with_velocity) s.velocity.emplace_back(std::exp(-i), 1.0 / 7 * i, 0);
    s.radius.push_back(0.5);
    s.active.push_back(i % 2);
    if (with_first) s.first_collision.push_back(i % 2 ? 0.1 * i : -1);
  }
  return s;
}

TEST(Xyz, RoundTripIsExact) {
  for (auto flavour : {XyzFlavour::Ase, XyzFlavour::Ovito})
    for (bool vel : {true, false})
      for (bool first : {true, false}) {
        Snapshot s = sample(vel, first);
        s.info.origin = Eigen::Vector3d(-1.5, 2, 0);
        s.info.step = 42;
        s.columns.push_back({"c_pe", {1, 2, 3, 4, 5e-300}});
        const auto p = out_path("round_trip.xyz");
        write_xyz(p, s, flavour);
        const Snapshot t = read_snapshot(p);
        EXPECT_EQ(t.info.dim, 2);
        EXPECT_EQ(t.info.box, s.info.box);
        EXPECT_EQ(t.info.time, s.info.time);
        EXPECT_EQ(t.info.density, s.info.density);
        EXPECT_EQ(t.info.restitution, s.info.restitution);
        EXPECT_EQ(t.info.cutoff, s.info.cutoff);
        EXPECT_EQ(t.info.speed, s.info.speed);
        EXPECT_EQ(t.info.seed, s.info.seed);
        EXPECT_EQ(t.position, s.position);
        EXPECT_EQ(t.velocity, s.velocity);
        EXPECT_EQ(t.radius, s.radius);
        EXPECT_EQ(t.active, s.active);
        EXPECT_EQ(t.first_collision, s.first_collision);
        EXPECT_EQ(t.info.origin, s.info.origin);
        EXPECT_EQ(t.info.step, 42);
        ASSERT_EQ(t.columns.size(), 1u);
        EXPECT_EQ(t.columns[0].name, "c_pe");
        EXPECT_EQ(t.columns[0].values, s.columns[0].values);
        EXPECT_FALSE(fs::exists(p + ".tmp." + std::to_string(::getpid())));
      }
}

TEST(Xyz, ReadsHandWrittenFiles) {
  // Plain XYZ: positions only, no Dim (so 3D), defaults for the rest.
  auto s = read_snapshot(write_text("plain.xyz", "2\nhello\nC 1 2 3\nC 4 5 6.5\n"));
  EXPECT_EQ(s.info.dim, 3);
  EXPECT_FALSE(s.info.has_box());
  ASSERT_EQ(s.size(), 2u);
  EXPECT_EQ(s.position[1], Eigen::Vector3d(4, 5, 6.5));
  EXPECT_FALSE(s.has_velocity());
  EXPECT_EQ(s.radius[0], 0.5);
  EXPECT_EQ(s.active[1], 1);
  EXPECT_TRUE(s.first_collision.empty());

  // Other order, an extra property, logical active, quoted values, a trailing blank line.
  s = read_snapshot(write_text("reordered.xyz",
                               "2\nTime=2.5 Properties=vel:R:3:charge:R:1:pos:R:3:active:L:1 "
                               "Dim=2 Lattice=\"10 0 0 0 10 0 0 0 10\" pbc=\"T T T\"\n"
                               "1 0 0  7  3 4 0  T\n-1 2 0 7 5 6 0 F\n\n"));
  EXPECT_EQ(s.info.dim, 2);
  EXPECT_EQ(s.info.box, Eigen::Vector3d(10, 10, 0));
  EXPECT_EQ(s.info.time, 2.5);
  EXPECT_EQ(s.position[0], Eigen::Vector3d(3, 4, 0));
  EXPECT_EQ(s.velocity[1], Eigen::Vector3d(-1, 2, 0));
  EXPECT_EQ(s.active[0], 1);
  EXPECT_EQ(s.active[1], 0);
}

TEST(Xyz, RejectsBadInputNamingFileAndLine) {
  const auto missing = out_path("does_not_exist.xyz");
  EXPECT_NE(read_error(missing).find(missing), std::string::npos);

  const std::string head = "3\nProperties=species:S:1:pos:R:3:velo:R:3 Dim=2\n";
  const auto truncated = write_text("truncated.xyz", head + "X 0 0 0 1 0 0\nX 1 1 0 0 0 0\n");
  auto msg = read_error(truncated);
  EXPECT_NE(msg.find(truncated), std::string::npos) << msg;
  EXPECT_NE(msg.find("truncated"), std::string::npos) << msg;

  const auto short_line =
      write_text("short_line.xyz", head + "X 0 0 0 1 0 0\nX 1 1 0\nX 0 0 0 0 0 0\n");
  msg = read_error(short_line);
  EXPECT_NE(msg.find("line 4"), std::string::npos) << msg;

  const auto bad_number =
      write_text("bad_number.xyz", head + "X 0 0 0 1 0 0\nX 1 1 0 0 0 0\nX 1 zz 0 0 0 0\n");
  msg = read_error(bad_number);
  EXPECT_NE(msg.find("line 5"), std::string::npos) << msg;
  EXPECT_NE(msg.find("zz"), std::string::npos) << msg;

  EXPECT_NE(
      read_error(write_text("nan.xyz", head + "X nan 0 0 1 0 0\nX 1 1 0 0 0 0\nX 1 1 0 0 0 0\n"))
          .find("line 3"),
      std::string::npos);
  EXPECT_NE(
      read_error(write_text("z_in_2d.xyz", head + "X 0 0 1 1 0 0\nX 1 1 0 0 0 0\nX 1 1 0 0 0 0\n"))
          .find("line 3"),
      std::string::npos);
  EXPECT_NE(read_error(write_text("count.xyz", "three\n\n")).find("line 1"), std::string::npos);
  EXPECT_NE(read_error(write_text("empty.xyz", "")), "accepted");
  EXPECT_NE(read_error(write_text("no_comment.xyz", "1\n")).find("line 2"), std::string::npos);
  EXPECT_NE(read_error(write_text("no_pos.xyz", "1\nProperties=species:S:1:velo:R:3\nX 0 0 0\n"))
                .find("pos"),
            std::string::npos);
  EXPECT_NE(read_error(write_text("bad_props.xyz", "1\nProperties=pos:R\n1 2 3\n")).find("line 2"),
            std::string::npos);
  EXPECT_NE(read_error(write_text("quote.xyz", "1\nLattice=\"1 0 0\n1 2 3\n")).find("quote"),
            std::string::npos);
  EXPECT_NE(read_error(write_text("radius.xyz", "1\nProperties=pos:R:3:radius:R:1\n1 2 3 -1\n"))
                .find("radius"),
            std::string::npos);
}

}  // namespace
}  // namespace gs
