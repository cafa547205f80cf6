// jobs/movie.h's movie of stored snapshots when a frame that the first pass read fails in
// the second (its file changed in between): the error names the file, and the output folder is
// left as it was: no movie, no partial file, no --keep-frames PNGs.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "io/xyz.h"
#include "jobs/movie.h"
#include "sim/error.h"
#include "sim/snapshot.h"

namespace gs::jobs {
namespace {

namespace fs = std::filesystem;

std::vector<std::string> names_in(const fs::path& dir) {
  std::vector<std::string> out;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    out.push_back(fs::relative(e.path(), dir).string());
  std::sort(out.begin(), out.end());
  return out;
}

// A small band of moving discs at time t in a 40 x 40 box.
Snapshot band(double t) {
  Snapshot s;
  s.info.time = t;
  s.info.dim = 2;
  s.info.box = {40, 40, 0};
  for (int i = 0; i < 200; ++i) {
    const double a = 0.0314 * i, r = 5 + 0.01 * t + (i % 3);
    s.position.emplace_back(20 + r * std::cos(a), 20 + r * std::sin(a), 0);
    s.velocity.emplace_back(std::cos(a) / (1 + i % 3), std::sin(a) / (1 + i % 3), 0);
    s.radius.push_back(0.5);
    s.active.push_back(1);
  }
  return s;
}

TEST(StoredMovie, AFrameFailingInTheSecondPassLeavesTheFolderAsItWas) {
  const fs::path root = fs::path(GRAINSHOCK_TEST_OUTPUT_DIR) / "stored_movie";
  fs::remove_all(root);
  fs::create_directories(root / "out");
  { std::ofstream(root / "out" / "notes.txt") << "earlier results\n"; }
  std::vector<std::string> files;
  for (int k = 0; k < 5; ++k) {
    files.push_back((root / ("t_" + std::to_string(k) + ".xyz")).string());
    write_xyz(files.back(), band(10.0 * k));
  }
  FrontMovieOptions o;
  o.movie.width = 160;
  o.movie.height = 120;
  o.camera = "fixed";
  o.keep_frames = true;
  o.quiet = true;
  StoredMovie m = prepare_stored_movie(files, o);
  ASSERT_EQ(m.frames(), 5u);
  // The last frame in time changes after the first pass: a particle line is no longer numbers.
  {
    std::ofstream(files[4] + ".new")
        << "1\nProperties=species:S:1:pos:R:3 Time=40 Dim=2\nX a b 0\n";
    fs::rename(files[4] + ".new", files[4]);
  }
  try {
    write_stored_movie(m, root / "out");
    FAIL() << "a frame that cannot be read must end the movie with an error";
  } catch (const UserError& e) {
    EXPECT_NE(std::string(e.what()).find("t_4.xyz"), std::string::npos) << e.what();
  }
  EXPECT_EQ(names_in(root / "out"), std::vector<std::string>{"notes.txt"});
}

}  // namespace
}  // namespace gs::jobs
