// HOOMD GSD: a file the gsd Python module wrote (assets/io, regenerated and cross-checked with
// /usr/bin/python3's gsd when installed), our writer read back by us and by gsd, and corrupt
// files refused in one line.
#include "io/gsd.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "sim/error.h"
#include "tests/sim/test_output.h"

namespace gs {
namespace {

namespace fs = std::filesystem;

using test::out_path;

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

bool have_python_gsd() {
  return std::system("/usr/bin/python3 -c 'import gsd.hoomd' > /dev/null 2>&1") == 0;
}

// The file of assets/io/hoomd_2d_2frames.gsd, as gsd.hoomd 2.7 wrote it: 2D, box 10 x 8, types
// A B B, diameters 1 0.5 2, at rest in frame 0 (so no velocity chunk) and moving in frame 1
// (which holds only step and velocity: the rest comes from frame 0).
TEST(Gsd, ReadsWhatTheGsdModuleWrote) {
  const SnapshotFile f =
      open_snapshots(std::string(GRAINSHOCK_ASSETS_DIR) + "/io/hoomd_2d_2frames.gsd");
  EXPECT_STREQ(f.format(), "GSD");
  ASSERT_EQ(f.frame_count(), 2u);
  const Snapshot a = f.read(0), b = f.read(1);
  EXPECT_EQ(a.info.dim, 2);
  EXPECT_EQ(a.info.box, Eigen::Vector3d(10, 8, 0));
  EXPECT_EQ(a.info.origin, Eigen::Vector3d(-5, -4, 0));
  EXPECT_EQ(a.info.step, 0);
  EXPECT_EQ(b.info.step, 10);
  ASSERT_EQ(a.size(), 3u);
  EXPECT_EQ(a.position[2], Eigen::Vector3d(4, -3.5, 0));
  EXPECT_EQ(b.position[2], Eigen::Vector3d(4, -3.5, 0));
  EXPECT_EQ(a.velocity[1], Eigen::Vector3d::Zero());
  EXPECT_EQ(b.velocity[1], Eigen::Vector3d(0, 1, 0));
  EXPECT_EQ(b.radius, (std::vector<double>{0.5, 0.25, 1}));
  ASSERT_NE(b.column("typeid"), nullptr);
  EXPECT_EQ(b.column("typeid")->values, (std::vector<double>{0, 1, 1}));
  EXPECT_EQ(b.type_names, (std::vector<std::string>{"A", "B"}));
  EXPECT_EQ(b.type, (std::vector<std::uint32_t>{0, 1, 1}));
}

Snapshot sample() {
  Snapshot s;
  s.info.dim = 2;
  s.info.set_cubic_box(20);
  s.info.time = 12.5;
  s.position = {{1, 2, 0}, {19.5, 0.25, 0}, {45, -3, 0}};  // the last is two boxes over
  s.velocity = {{0, 0, 0}, {1, -2, 0}, {0.5, 0.5, 0}};
  s.radius = {0.5, 0.5, 0.75};
  s.active = {0, 1, 1};
  s.first_collision = {-1, 3, 4.5};
  return s;
}

TEST(Gsd, OurWriterReadsBack) {
  const auto path = out_path("ours.gsd");
  write_gsd(path, sample());
  const Snapshot t = read_snapshot(path);
  const Snapshot s = sample();
  EXPECT_EQ(t.info.dim, 2);
  EXPECT_EQ(t.info.time, 12.5);
  EXPECT_EQ(t.info.box, Eigen::Vector3d(20, 20, 0));
  ASSERT_EQ(t.size(), 3u);
  // GSD boxes are centred on 0, so the box corner moves to -L/2 and the positions with it.
  // They are 32-bit floats in that box, unwrapped again by the image counts: |x| <= 10 there,
  // so each lands within 10 * 2^-24 ~ 6e-7 of the original (relative to the corner).
  EXPECT_EQ(t.info.origin, Eigen::Vector3d(-10, -10, 0));
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_LT(((t.position[i] - t.info.origin) - (s.position[i] - s.info.origin)).norm(), 2e-6)
        << i;
    EXPECT_LT((t.velocity[i] - s.velocity[i]).norm(), 1e-6) << i;
  }
  EXPECT_EQ(t.radius, s.radius);
  EXPECT_EQ(t.active, s.active);
  EXPECT_EQ(t.first_collision, s.first_collision);
}

// A snapshot of the unbounded medium says so (log/Unbounded, as XYZ's Medium=unbounded), so that
// no reader frames its grid as a box; a box snapshot's bytes do not change.
TEST(Gsd, TheUnboundedMediumIsMarked) {
  const auto path = out_path("unbounded.gsd");
  Snapshot s = sample();
  write_gsd(path, s);
  EXPECT_EQ(slurp(path).find("log/Unbounded"), std::string::npos);
  EXPECT_FALSE(read_snapshot(path).info.unbounded);
  s.info.unbounded = true;
  write_gsd(path, s);
  EXPECT_TRUE(read_snapshot(path).info.unbounded);
}

// Chunks at the schema's defaults (image 0, diameter 1) are not written; reading gives the same.
TEST(Gsd, DefaultChunksAreLeftOut) {
  Snapshot s = sample();
  s.position[2] = {15, 3, 0};  // every particle inside the box
  s.radius.assign(3, 0.5);
  const auto path = out_path("defaults.gsd");
  write_gsd(path, s);
  const std::string bytes = slurp(path);
  EXPECT_EQ(bytes.find("particles/image"), std::string::npos);
  EXPECT_EQ(bytes.find("particles/diameter"), std::string::npos);
  const Snapshot t = read_snapshot(path);
  EXPECT_EQ(t.radius, s.radius);
  // Relative to the box corner (ours at 0, GSD's at -L/2); float32 of numbers exact in binary.
  for (std::size_t i = 0; i < s.size(); ++i)
    EXPECT_EQ(t.position[i] - t.info.origin, s.position[i]) << i;
  s.position[2] = {45, -3, 0};
  write_gsd(path, s);
  EXPECT_NE(slurp(path).find("particles/image"), std::string::npos);
  const Snapshot u = read_snapshot(path);
  EXPECT_EQ(u.position[2] - u.info.origin, Eigen::Vector3d(45, -3, 0));
}

TEST(Gsd, TheGsdModuleReadsOurs) {
  if (!have_python_gsd()) GTEST_SKIP() << "/usr/bin/python3 with the gsd module is not installed";
  const auto path = out_path("for_python.gsd");
  write_gsd(path, sample());
  const std::string script =
      "import gsd.hoomd, numpy as np\n"
      "f = gsd.hoomd.open('" +
      path +
      "', 'rb')\n"
      "s = f[0]\n"
      "assert len(f) == 1 and s.configuration.dimensions == 2\n"
      "assert np.allclose(s.configuration.box, [20, 20, 0, 0, 0, 0])\n"
      "u = s.particles.position + s.particles.image * 20 + 10\n"
      "assert np.allclose(u[:, :2], [[1, 2], [19.5, 0.25], [45, -3]], atol=1e-5), u\n"
      "assert np.allclose(s.particles.velocity[1], [1, -2, 0])\n"
      "assert np.allclose(s.particles.diameter, [1, 1, 1.5])\n"
      "assert list(s.log['particles/active']) == [0, 1, 1]\n";
  std::ofstream(out_path("check.py")) << script;
  EXPECT_EQ(std::system(("/usr/bin/python3 " + out_path("check.py")).c_str()), 0);
}

std::string error_of(std::string bytes) {
  try {
    const SnapshotFile f = open_snapshots(MappedFile::from_bytes("bad.gsd", std::move(bytes)));
    for (std::size_t k = 0; k < f.frame_count(); ++k) f.read(k);
  } catch (const UserError& e) {
    return e.what();
  }
  return "accepted";
}

template <class T>
void poke(std::string& b, std::size_t at, T v) {
  std::memcpy(b.data() + at, &v, sizeof v);
}

TEST(Gsd, CorruptFilesAreRefusedInOneLine) {
  const auto path = out_path("good.gsd");
  write_gsd(path, sample());
  const std::string good = slurp(path);
  ASSERT_EQ(error_of(good), "accepted");
  std::uint64_t index_at = 0, entries = 0;
  std::memcpy(&index_at, good.data() + 8, 8);
  std::memcpy(&entries, good.data() + 16, 8);

  std::string b = good;
  b[3] ^= 1;
  EXPECT_NE(error_of(b).find("magic"), std::string::npos) << error_of(b);
  EXPECT_NE(error_of(good.substr(0, 100)).find("bad.gsd"), std::string::npos);
  b = good;
  poke<std::uint64_t>(b, 16, 1ull << 60);  // index entries beyond the file
  EXPECT_NE(error_of(b).find("index"), std::string::npos) << error_of(b);
  b = good;
  poke<std::uint64_t>(b, index_at + 8, 1ull << 40);  // entry 0 rows: past the end
  EXPECT_NE(error_of(b).find("outside the file"), std::string::npos) << error_of(b);
  b = good;
  poke<std::uint64_t>(b, index_at + 8, 0);  // entry 0: no rows but 4e9 values per row
  poke<std::uint32_t>(b, index_at + 24, 4294574081u);
  EXPECT_NE(error_of(b).find("values per row"), std::string::npos) << error_of(b);
  b = good;
  poke<std::uint16_t>(b, index_at + 28, 999);  // entry 0 names a chunk that is not there
  EXPECT_NE(error_of(b).find("index entry 0"), std::string::npos) << error_of(b);
  b = good;
  poke<std::uint8_t>(b, index_at + 30, 77);  // unknown type
  EXPECT_NE(error_of(b).find("unknown type"), std::string::npos) << error_of(b);
  b = good;
  poke<std::uint64_t>(b, index_at, 3);  // entry 0 in frame 3, the next in frame 0
  EXPECT_NE(error_of(b).find("frame order"), std::string::npos) << error_of(b);
  b = good;
  for (std::uint64_t e = entries; e-- > 0;) {  // the last entry in use, in frame 1e12
    std::int64_t loc = 0;
    std::memcpy(&loc, good.data() + index_at + 32 * e + 16, 8);
    if (loc == 0) continue;
    poke<std::uint64_t>(b, index_at + 32 * e, 1000000000000ull);
    break;
  }
  EXPECT_NE(error_of(b).find("names frame 1000000000000"), std::string::npos) << error_of(b);
  // particles/N larger than the positions: found, not believed.
  for (std::uint64_t e = 0; e < entries; ++e) {
    b = good;
    std::uint64_t n = 0;
    std::memcpy(&n, good.data() + index_at + 32 * e + 8, 8);
    std::int64_t loc = 0;
    std::memcpy(&loc, good.data() + index_at + 32 * e + 16, 8);
    if (n == 1 && good.substr(loc, 4) == std::string("\x03\0\0\0", 4)) {  // particles/N = 3
      poke<std::uint32_t>(b, loc, 4000000000u);
      auto msg = error_of(b);
      EXPECT_NE(msg.find("particles/N"), std::string::npos) << msg;
      EXPECT_NE(msg.find("frame 0"), std::string::npos) << msg;
      // The same chunk as a float: NaN, negative or fractional is not a count.
      for (float bad : {std::nanf(""), -3.0f, 2.5f, 1e30f}) {
        b = good;
        poke<std::uint8_t>(b, index_at + 32 * e + 30, 9);  // F32
        poke<float>(b, loc, bad);
        msg = error_of(b);
        EXPECT_NE(msg.find("particles/N is not a count"), std::string::npos) << bad << ": " << msg;
      }
    }
  }
}

}  // namespace
}  // namespace gs
