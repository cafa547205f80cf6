// The movie of a run drawn as the run goes (jobs/movie.h write_run_movie, what `run --movie`
// does for a new run): frame for frame the movie write_front_movie makes by replaying the run,
// 240 frames, and the run's own files are the bytes they are without a movie (the engine's pauses
// at frame times change no history).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "jobs/movie.h"
#include "jobs/run_loop.h"
#include "tests/render/movie_decode.h"

namespace gs::jobs {
namespace {

namespace fs = std::filesystem;

std::string bytes(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::ostringstream s;
  s << f.rdbuf();
  return s.str();
}

fs::path fresh(const std::string& name) {
  const fs::path dir = fs::path(GRAINSHOCK_TEST_OUTPUT_DIR) / "run_movie" / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

RunPlan small_kick() {
  RunPlan plan;  // the C++ defaults: the paper's box, 2D
  plan.physics.particles = 4000;
  plan.physics.restitution = 0.5;
  plan.physics.t_max = 3000;
  plan.snapshot_times = {700};
  return plan;
}

TEST(RunMovie, DrawnAsTheRunGoesIsTheReplayedMovie) {
  const RunPlan plan = small_kick();
  FrontMovieOptions m;  // as the Fig. 1 job's: 240 frames, 1920x1080, with the inset
  m.inset = true;
  m.quiet = true;
  m.t_start = 0.01;  // the first frames before the first collision: the kicked disc alone
  ASSERT_TRUE(movie_in_one_pass(plan.physics, m));

  const fs::path live = fresh("live"), plain = fresh("plain"), replay = fresh("replay");
  {
    RunLoop loop(plan, live, "test");
    loop.checkpoint_every = 0;
    const FrontMovieResult r = write_run_movie(loop, plan.physics, m, live);
    EXPECT_FALSE(r.stopped);
    EXPECT_EQ(r.frames, 240);
    EXPECT_EQ(loop.simulation().time(), plan.physics.t_max);  // the last frame is at t-max
    ASSERT_TRUE(loop.run());
  }
  {
    RunLoop loop(plan, plain, "test");
    loop.checkpoint_every = 0;
    ASSERT_TRUE(loop.run());
  }
  for (const char* f : {"timeseries.csv", "snapshots/tsim_700.xyz", "snapshots/tsim_3000.xyz"})
    EXPECT_TRUE(bytes(live / f) == bytes(plain / f)) << f;

  EXPECT_FALSE(write_front_movie(plan.physics, m, replay).stopped);
  const std::string drawn = bytes(live / "movie.mp4");
  ASSERT_FALSE(drawn.empty());
  EXPECT_TRUE(drawn == bytes(replay / "movie.mp4")) << "the live movie differs from the replay";
  EXPECT_EQ(render::decode_movie(live / "movie.mp4").frames, 240);
}

// Plain speed without --range spans every frame: that needs the pass ahead, which only a replay
// can give.
TEST(RunMovie, ARangeOverAllFramesIsNotDrawnInOnePass) {
  FrontMovieOptions m;
  m.colour_by = "speed";
  EXPECT_FALSE(movie_in_one_pass(small_kick().physics, m));
  m.range = {0.1, 1};
  EXPECT_TRUE(movie_in_one_pass(small_kick().physics, m));
}

}  // namespace
}  // namespace gs::jobs
