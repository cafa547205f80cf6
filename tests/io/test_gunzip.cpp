// Gzip-compressed snapshots: inflated through zlib and read like the file they hold; a file cut
// short, corrupt or inflating past the bound is refused in one line naming it.
#include "io/gunzip.h"

#include <gtest/gtest.h>
#include <zlib.h>

#include <filesystem>
#include <fstream>

#include "io/snapshot_file.h"
#include "sim/error.h"

namespace gs {
namespace {

namespace fs = std::filesystem;

// `text` as gzip writes it (deflate in a gzip wrapper), through zlib's own compressor.
std::string gzip(const std::string& text) {
  z_stream z{};
  EXPECT_EQ(deflateInit2(&z, 6, Z_DEFLATED, 16 + MAX_WBITS, 8, Z_DEFAULT_STRATEGY), Z_OK);
  std::string out(deflateBound(&z, text.size()) + 32, '\0');
  z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(text.data()));
  z.avail_in = static_cast<uInt>(text.size());
  z.next_out = reinterpret_cast<Bytef*>(out.data());
  z.avail_out = static_cast<uInt>(out.size());
  EXPECT_EQ(deflate(&z, Z_FINISH), Z_STREAM_END);
  out.resize(z.total_out);
  deflateEnd(&z);
  return out;
}

std::string error_of(const std::string& bytes, std::size_t limit = 1 << 20) {
  try {
    gunzip(bytes, "t.xyz.gz", limit);
  } catch (const UserError& e) {
    return e.what();
  }
  return "accepted";
}

const std::string kXyz =
    "2\nLattice=\"10.0 0.0 0.0 0.0 10.0 0.0 0.0 0.0 10.0\" "
    "Properties=species:S:1:pos:R:3:velo:R:3 Time=2.5 pbc=\"T T T\"\n"
    "A 1.0 2.0 3.0 0.5 0.0 0.0\n"
    "A 4.0 5.0 6.0 0.0 0.25 0.0\n";

TEST(Gunzip, InflatesWhatZlibCompressedAndConcatenatedMembers) {
  const std::string z = gzip(kXyz);
  ASSERT_TRUE(is_gzip(z));
  EXPECT_FALSE(is_gzip(kXyz));
  EXPECT_EQ(gunzip(z, "t", 1 << 20), kXyz);
  EXPECT_EQ(gunzip(z + gzip("more") + std::string(8, '\0'), "t", 1 << 20), kXyz + "more");
  // Larger than one inflate chunk (256 KiB), so the output grows.
  std::string big;
  for (int i = 0; i < 40000; ++i) big += "A " + std::to_string(i) + " 1.0 2.0\n";
  EXPECT_EQ(gunzip(gzip(big), "t", big.size()), big);
}

TEST(Gunzip, TruncatedCorruptAndBombsAreOneLineNamingTheFile) {
  const std::string z = gzip(kXyz);
  const std::string cut = error_of(z.substr(0, z.size() / 2));
  EXPECT_NE(cut.find("snapshot 't.xyz.gz': cut short"), std::string::npos) << cut;
  std::string bad = z;
  bad[12] = static_cast<char>(bad[12] ^ 0x55);
  bad[13] = static_cast<char>(bad[13] ^ 0xaa);
  const std::string corrupt = error_of(bad);
  EXPECT_NE(corrupt.find("snapshot 't.xyz.gz': corrupt gzip data"), std::string::npos) << corrupt;
  std::string trailer = z;
  trailer[trailer.size() - 6] = static_cast<char>(trailer[trailer.size() - 6] ^ 1);  // CRC-32
  EXPECT_NE(error_of(trailer).find("corrupt gzip data"), std::string::npos) << error_of(trailer);
  EXPECT_NE(error_of(z + "junk").find("after the end of its gzip stream"), std::string::npos);
  // 64 MB of zeros compress to about 64 kB; a bound of 1 MB stops it early.
  const std::string bomb = error_of(gzip(std::string(64 << 20, '\0')), 1 << 20);
  EXPECT_NE(bomb.find("inflates to more than 0.00105 GB"), std::string::npos) << bomb;
  for (const std::string& m : {cut, corrupt, bomb}) EXPECT_EQ(m.find('\n'), std::string::npos);
}

TEST(Gunzip, SnapshotFilesReadCompressedAsTheyReadPlain) {
  const fs::path dir = fs::path(GRAINSHOCK_TEST_OUTPUT_DIR) / "gunzip";
  fs::create_directories(dir);
  std::ofstream(dir / "t.xyz.gz", std::ios::binary) << gzip(kXyz + kXyz);
  const SnapshotFile f = open_snapshots((dir / "t.xyz.gz").string());
  ASSERT_EQ(f.frame_count(), 2u);
  const Snapshot s = f.read(1);
  EXPECT_EQ(s.size(), 2u);
  EXPECT_EQ(s.info.time, 2.5);
  EXPECT_EQ(s.velocity[1].y(), 0.25);
  std::ofstream(dir / "cut.xyz.gz", std::ios::binary) << gzip(kXyz).substr(0, 20);
  try {
    open_snapshots((dir / "cut.xyz.gz").string());
    ADD_FAILURE() << "a cut .gz was read";
  } catch (const UserError& e) {
    EXPECT_NE(std::string(e.what()).find("cut.xyz.gz': cut short"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace gs
