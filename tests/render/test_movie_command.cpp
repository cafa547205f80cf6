// `grainshock movie` as users call it: the movie decoded back, its frames against the PNGs the
// same run wrote, bad input, and a run stopped with SIGTERM.
#include <gtest/gtest.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

#include "render/png.h"
#include "tests/apps/cli_test_util.h"
#include "tests/render/movie_decode.h"

extern char** environ;

namespace gs::render {
namespace {

namespace fs = std::filesystem;

fs::path fresh_dir(const std::string& name) {
  const fs::path dir = fs::path(GRAINSHOCK_TEST_OUTPUT_DIR) / "movie_command" / name;
  fs::remove_all(dir);
  fs::create_directories(dir.parent_path());
  return dir;
}

using Result = test::CommandResult;

Result movie(const std::string& args) {
  return test::grainshock("movie " + args);
}

std::vector<std::string> names_in(const fs::path& dir) {
  std::vector<std::string> out;
  if (fs::exists(dir))
    for (const auto& e : fs::directory_iterator(dir)) out.push_back(e.path().filename().string());
  std::sort(out.begin(), out.end());
  return out;
}

double png_time(const fs::path& png) {
  for (const auto& [k, v] : read_png_text(png.string()))
    if (k == "Time") return std::stod(v);
  ADD_FAILURE() << png << " has no Time";
  return -1;
}

constexpr const char* kSmallRun = "--particles 3000 --seed 7 --quiet";

TEST(MovieCommand, WritesTheFramesAskedForAndMatchesThePngRenderer) {
  const auto dir = fresh_dir("basic");
  const Result r =
      movie(std::string(kSmallRun) +
            " --t-max 200 --frames 24 --fps 12 --width 320 --height 240 --keep-frames --out " +
            dir.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(names_in(dir), (std::vector<std::string>{"frames", "movie.mp4", "run.toml"}));
  EXPECT_EQ(names_in(dir / "frames").size(), 24u);

  const int k = 20;
  const Decoded d = decode_movie(dir / "movie.mp4", k);
  EXPECT_EQ(d.codec, AV_CODEC_ID_H264);
  EXPECT_EQ(d.width, 320);
  EXPECT_EQ(d.height, 240);
  EXPECT_EQ(d.frames, 24);
  EXPECT_EQ(av_cmp_q(d.avg_frame_rate, AVRational{12, 1}), 0);
  EXPECT_NEAR(d.duration, 2.0, 1e-3);
  // The PNG of the same frame is the renderer's picture of the same snapshot; the bound is the
  // one justified in test_movie.cpp (yuv420p round trip), and frame k - 1 must miss it.
  const Image png = read_png((dir / "frames" / "frame_00020.png").string());
  const Image previous = read_png((dir / "frames" / "frame_00019.png").string());
  ASSERT_EQ(d.rgb.width, 320);
  EXPECT_GE(psnr(d.rgb, png, 320, 240), 30.0);
  EXPECT_LT(psnr(d.rgb, previous, 320, 240), psnr(d.rgb, png, 320, 240) - 3);
}

TEST(MovieCommand, FrameTimesAreLinearOrLogarithmic) {
  const auto lin = fresh_dir("lin");
  ASSERT_EQ(movie(std::string(kSmallRun) +
                  " --t-max 100 --frames 4 --frame-spacing lin --width 64 --height 48"
                  " --keep-frames --out " +
                  lin.string())
                .exit_code,
            0);
  const double want_lin[] = {25, 50, 75, 100};
  for (int k = 0; k < 4; ++k)
    EXPECT_NEAR(png_time(lin / "frames" / ("frame_0000" + std::to_string(k) + ".png")), want_lin[k],
                1e-9);
  const auto log = fresh_dir("log");
  ASSERT_EQ(movie(std::string(kSmallRun) +
                  " --t-max 100 --frames 3 --frame-spacing log --t-start 1 --width 64"
                  " --height 48 --keep-frames --out " +
                  log.string())
                .exit_code,
            0);
  const double want_log[] = {1, 10, 100};
  for (int k = 0; k < 3; ++k)
    EXPECT_NEAR(png_time(log / "frames" / ("frame_0000" + std::to_string(k) + ".png")), want_log[k],
                1e-9);
  EXPECT_EQ(decode_movie(log / "movie.mp4").frames, 3);
}

TEST(MovieCommand, OddSizeMpeg4And3dSlab) {
  const auto odd = fresh_dir("odd_mpeg4");
  const Result r = movie(std::string(kSmallRun) +
                         " --t-max 200 --frames 6 --width 161 --height 91 --codec mpeg4"
                         " --fps 25 --out " +
                         odd.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Decoded d = decode_movie(odd / "movie.mp4");
  EXPECT_EQ(d.codec, AV_CODEC_ID_MPEG4);
  EXPECT_EQ(d.width, 162);
  EXPECT_EQ(d.height, 92);
  EXPECT_EQ(d.frames, 6);

  const auto three = fresh_dir("3d");
  const Result r3 = movie(
      "--dim 3 --particles 3000 --t-max 60 --quiet --frames 5 --slab 6"
      " --width 160 --height 120 --out " +
      three.string());
  ASSERT_EQ(r3.exit_code, 0) << r3.err;
  EXPECT_EQ(decode_movie(three / "movie.mp4").frames, 5);
}

TEST(MovieCommand, BadInputIsOneLineNonZeroAndNoMovie) {
  const std::vector<std::string> bad = {
      "--fps 0",
      "--fps -3",
      "--codec vp13",
      "--crf 99",
      "--frames 0",
      "--frames 2000000",
      "--frames 10 --frame-spacing log --t-start 99.9999999999",
      "--frame-spacing log --t-start 300",
      "--frame-spacing cubic",
      "--camera shaky",
      "--width 0",
  };
  int i = 0;
  for (const auto& args : bad) {
    const auto dir = fresh_dir("bad" + std::to_string(i++));
    const std::string frames = args.find("--frames") == std::string::npos ? " --frames 5" : "";
    const Result r = movie(std::string(kSmallRun) + " --t-max 100" + frames + " " + args +
                           " --out " + dir.string());
    EXPECT_NE(r.exit_code, 0) << args;
    EXPECT_EQ(r.err_lines(), 1) << args << ": " << r.err;
    EXPECT_NE(r.err.find("error"), std::string::npos) << args << ": " << r.err;
    EXPECT_FALSE(fs::exists(dir)) << args << ": input is checked before the folder is made";
  }
  const Result r = movie(std::string(kSmallRun) + " --out /proc/grainshock-movie");
  EXPECT_NE(r.exit_code, 0);
  EXPECT_EQ(r.err_lines(), 1) << r.err;
  EXPECT_FALSE(fs::exists("/proc/grainshock-movie/movie.mp4"));
}

TEST(MovieCommand, SigtermFinishesTheMovieWithTheFramesSoFar) {
  const auto dir = fresh_dir("sigterm");
  // A fixed camera and colour range need no first pass, so frames flow from the start; the run
  // is far longer than the test waits.
  std::vector<std::string> args = {GRAINSHOCK_BINARY,
                                   "movie",
                                   "--particles",
                                   "3000",
                                   "--t-max",
                                   "100000",
                                   "--frames",
                                   "20000",
                                   "--frame-spacing",
                                   "lin",
                                   "--camera",
                                   "fixed",
                                   "--range",
                                   "0.001",
                                   "1",
                                   "--width",
                                   "160",
                                   "--height",
                                   "120",
                                   "--keep-frames",
                                   "--quiet",
                                   "--out",
                                   dir.string()};
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid = -1;
  ASSERT_EQ(posix_spawn(&pid, argv[0], nullptr, nullptr, argv.data(), environ), 0);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  while (!fs::exists(dir / "frames" / "frame_00010.png") &&
         std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  ASSERT_EQ(kill(pid, SIGTERM), 0);
  int status = 0;
  ASSERT_EQ(waitpid(pid, &status, 0), pid);
  ASSERT_TRUE(WIFEXITED(status)) << "killed by the signal instead of finishing";
  EXPECT_EQ(WEXITSTATUS(status), 130);  // interrupted, whatever the signal (apps/exit_code.h)
  const auto pngs = names_in(dir / "frames").size();
  EXPECT_GE(pngs, 11u);
  EXPECT_LT(pngs, 20000u);
  EXPECT_EQ(names_in(dir), (std::vector<std::string>{"frames", "movie.mp4", "run.toml"}));
  const Decoded d = decode_movie(dir / "movie.mp4");
  EXPECT_EQ(d.frames, static_cast<int>(pngs)) << "every rendered frame is in the movie";
  EXPECT_NEAR(d.duration, pngs / 30.0, 1e-3);
}

}  // namespace
}  // namespace gs::render
