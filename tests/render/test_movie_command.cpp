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
#include <fstream>
#include <iterator>
#include <random>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "io/snapshot_file.h"
#include "render/png.h"
#include "render/scene.h"
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

constexpr const char* kSmallRun = "--medium box --particles 3000 --seed 7 --quiet";

TEST(MovieCommand, WritesTheFramesAskedForAndMatchesThePngRenderer) {
  const auto dir = fresh_dir("basic");
  const Result r =
      movie(std::string(kSmallRun) +
            " --t-max 200 --frames 24 --fps 12 --width 320 --height 240 --keep-frames --out " +
            dir.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(names_in(dir), (std::vector<std::string>{"frames", "movie.mp4", "movie.toml"}));
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

// movie.toml holds every setting: --config gives the same movie.toml and the same frames, for a
// simulated movie and for one of stored snapshots (whose files are in it too).
TEST(MovieCommand, MovieTomlReproducesTheMovie) {
  const auto a = fresh_dir("toml_a"), b = fresh_dir("toml_b");
  Result r = movie(std::string(kSmallRun) +
                   " --restitution 0.3 --t-max 150 --frames 6 --frame-spacing lin --width 160 "
                   "--height 120 --inset --colormap viridis --range 0.2 1.8 --out " +
                   a.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string toml = test::read_file(a / "movie.toml");
  for (const char* line :
       {"\nrestitution = 0.3\n", "\nframes = 6\n", "\ninset = true\n", "\ncolormap = \"viridis\"\n",
        "\nrange = [0.2, 1.8]\n", "\nclip = false\n", "\nseed = 7\n"})
    EXPECT_NE(toml.find(line), std::string::npos) << line << " not in\n" << toml;
  EXPECT_EQ(toml.find("\nout = "), std::string::npos) << "the folder is not a setting";
  r = movie("--quiet --config " + (a / "movie.toml").string() + " --out " + b.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(test::read_file(b / "movie.toml"), toml);
  EXPECT_EQ(test::read_file(b / "movie.mp4"), test::read_file(a / "movie.mp4"));

  const auto c = fresh_dir("toml_c"), d = fresh_dir("toml_d");
  r = test::grainshock(
      "run --medium box --particles 2000 --t-max 100 --snapshot-times 50 --quiet --out " +
      c.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = movie("--quiet --width 160 --height 120 " + (c / "snapshots/tsim_50.xyz").string() + " " +
            (c / "snapshots/tsim_100.xyz").string() + " --out " + d.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto e = fresh_dir("toml_e");
  r = movie("--quiet --config " + (d / "movie.toml").string() + " --out " + e.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(decode_movie(e / "movie.mp4").frames, 2);
  EXPECT_EQ(test::read_file(e / "movie.mp4"), test::read_file(d / "movie.mp4"));
}

// movie.toml names its snapshots relative to itself: made from the run folder with relative
// names, it draws the same movie through --config from another folder, and from a copy of both
// folders moved elsewhere.
TEST(MovieCommand, MovieTomlWorksFromAnyFolder) {
  const auto run = fresh_dir("anywhere_run"), a = fresh_dir("anywhere_a");
  Result r = test::grainshock(
      "run --medium box --particles 2000 --t-max 100 --snapshot-times 50 --quiet --out " +
      run.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = test::grainshock("movie --quiet --width 160 --height 120 snapshots/tsim_50.xyz "
                       "snapshots/tsim_100.xyz --out " + a.string(),
                       "cd " + run.string() + " &&");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string toml = test::read_file(a / "movie.toml");
  EXPECT_NE(toml.find("../anywhere_run/snapshots/tsim_50.xyz"), std::string::npos) << toml;
  const auto b = fresh_dir("anywhere_b");
  r = test::grainshock("movie --quiet --config " + (a / "movie.toml").string() + " --out " +
                           b.string(),
                       "cd / &&");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(test::read_file(b / "movie.mp4"), test::read_file(a / "movie.mp4"));

  const auto moved = fresh_dir("anywhere_moved");
  fs::create_directories(moved);
  fs::copy(run, moved / "anywhere_run", fs::copy_options::recursive);
  fs::copy(a, moved / "anywhere_a", fs::copy_options::recursive);
  const auto c = fresh_dir("anywhere_c");
  r = movie("--quiet --config " + (moved / "anywhere_a/movie.toml").string() + " --out " +
            c.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(test::read_file(c / "movie.mp4"), test::read_file(a / "movie.mp4"));
}

// movie.toml is written by toml++ with each value typed by its flag: a snapshot named 1e2 (or
// with a quote in its name) stays a string and is found again by --config.
TEST(MovieCommand, MovieTomlKeepsFileNamesThatLookLikeNumbers) {
  const auto run = fresh_dir("names_run"), a = fresh_dir("names_a"), b = fresh_dir("names_b");
  Result r = test::grainshock(
      "run --medium box --particles 2000 --t-max 100 --snapshot-times 50 --quiet --out " +
      run.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // Beside movie.toml, so that the names are written bare.
  fs::create_directories(a);
  fs::copy_file(run / "snapshots/tsim_50.xyz", a / "1e2");
  fs::copy_file(run / "snapshots/tsim_100.xyz", a / "say\"when\"");
  r = test::grainshock("movie --quiet --width 160 --height 120 1e2 'say\"when\"' --force --out .",
                       "cd " + a.string() + " &&");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string toml = test::read_file(a / "movie.toml");
  EXPECT_NE(toml.find("\nsnapshots = [ \"1e2\", \"say\\\"when\\\"\" ]\n"), std::string::npos)
      << toml;
  EXPECT_NE(toml.find("\ncrf = 18\n"), std::string::npos) << toml;
  EXPECT_NE(toml.find("\nazimuth = 30.0\n"), std::string::npos) << toml;
  r = movie("--quiet --config " + (a / "movie.toml").string() + " --out " + b.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(decode_movie(b / "movie.mp4").frames, 2);
  EXPECT_EQ(test::read_file(b / "movie.mp4"), test::read_file(a / "movie.mp4"));
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
      "--dim 3 --medium box --particles 3000 --t-max 60 --quiet --frames 5 --slab 6"
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

// Snapshots of one small 2D run at four times, written by `grainshock run`.
std::vector<std::string> stored_snapshots(const std::string& name, const std::string& physics) {
  const auto run = fresh_dir(name);
  const Result r = test::grainshock("run " + physics +
                                    " --quiet --snapshot-times 50,100,150 --out " + run.string());
  EXPECT_EQ(r.exit_code, 0) << r.err;
  std::vector<std::string> files;
  for (const char* t : {"50", "100", "150", "200"})
    files.push_back((run / "snapshots" / (std::string("tsim_") + t + ".xyz")).string());
  return files;
}

// The --keep-frames PNGs of `dir` carry these times, frame by frame.
void expect_kept_frame_times(const fs::path& dir, const std::vector<double>& want) {
  for (std::size_t k = 0; k < want.size(); ++k)
    EXPECT_NEAR(png_time(dir / "frames" / ("frame_0000" + std::to_string(k) + ".png")), want[k],
                1e-9);
}

// The decoded 320x240 frame `d.rgb` is `snapshot` as `grainshock render` draws it with the same
// camera and style, and not `other`; the bound is test_movie.cpp's (yuv420p round trip).
void expect_frame_is_render(const Decoded& d, const std::string& snapshot, const std::string& other,
                            const fs::path& dir) {
  const auto png = dir / "render_same.png", miss = dir / "render_other.png";
  // The movie's default style: no inset (render draws one for a run's snapshot by default).
  const std::string args = " --framing box --no-inset --width 320 --height 240 --out ";
  ASSERT_EQ(test::grainshock("render " + snapshot + args + png.string()).exit_code, 0);
  ASSERT_EQ(test::grainshock("render " + other + args + miss.string()).exit_code, 0);
  const double same = psnr(d.rgb, read_png(png.string()), 320, 240);
  EXPECT_GE(same, 30.0);
  EXPECT_LT(psnr(d.rgb, read_png(miss.string()), 320, 240), same - 3);
}

TEST(MovieCommand, FromStoredSnapshotsInOrderOfTimeMatchingThePngRenderer) {
  const auto files = stored_snapshots("stored_run", std::string(kSmallRun) + " --t-max 200");
  const auto dir = fresh_dir("stored");
  // Given out of order: the movie puts them in order of Time.
  const Result r =
      movie(files[2] + " " + files[0] + " " + files[3] + " " + files[1] +
            " --camera fixed --width 320 --height 240 --keep-frames --out " + dir.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(names_in(dir), (std::vector<std::string>{"frames", "movie.mp4", "movie.toml"}));
  const Decoded d = decode_movie(dir / "movie.mp4", 2);
  EXPECT_EQ(d.frames, 4);
  EXPECT_EQ(d.width, 320);
  EXPECT_EQ(d.height, 240);
  expect_kept_frame_times(dir, {50, 100, 150, 200});
  // Frame 2 is t = 150 as `grainshock render` draws it with the same camera and style.
  expect_frame_is_render(d, files[2], files[1], dir);
}

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

// The snapshot as a LAMMPS text dump frame (`dump custom ... id type x y z vx vy vz radius`),
// its active particles only, as a LAMMPS user would dump a group.
std::string dump_frame(const Snapshot& s, std::int64_t step) {
  std::ostringstream o;
  o.precision(17);
  std::size_t n = 0;
  for (auto a : s.active) n += a != 0;
  o << "ITEM: TIME\n"
    << s.info.time << "\nITEM: TIMESTEP\n"
    << step << "\nITEM: NUMBER OF ATOMS\n"
    << n << "\nITEM: BOX BOUNDS pp pp pp\n";
  for (int a = 0; a < 3; ++a)
    o << s.info.origin[a] << " " << s.info.origin[a] + s.info.box[a] << "\n";
  o << "ITEM: ATOMS id type x y z vx vy vz radius\n";
  for (std::size_t i = 0; i < s.size(); ++i)
    if (s.active[i])
      o << i + 1 << " 1 " << s.position[i].x() << " " << s.position[i].y() << " "
        << s.position[i].z() << " " << s.velocity[i].x() << " " << s.velocity[i].y() << " "
        << s.velocity[i].z() << " " << s.radius[i] << "\n";
  return o.str();
}

// Every frame of every file is a movie frame, all in order of Time: two extended XYZ files of
// two frames each, their times interleaved, and a LAMMPS dump of three timesteps out of order.
TEST(MovieCommand, EveryFrameOfMultiFrameFilesInOrderOfTime) {
  const auto files = stored_snapshots("multi_run", std::string(kSmallRun) + " --t-max 200");
  const auto dir = fresh_dir("multi");
  const auto in = fresh_dir("multi_input");
  fs::create_directories(in);
  const std::string a = (in / "a.xyz").string(), b = (in / "b.xyz").string();
  { std::ofstream(a, std::ios::binary) << slurp(files[2]) << slurp(files[0]); }
  { std::ofstream(b, std::ios::binary) << slurp(files[3]) << slurp(files[1]); }
  const std::string size = " --camera fixed --width 320 --height 240";
  const Result r = movie(a + " " + b + size + " --keep-frames --out " + dir.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Decoded d = decode_movie(dir / "movie.mp4", 1);
  EXPECT_EQ(d.frames, 4);
  expect_kept_frame_times(dir, {50, 100, 150, 200});
  // Decoded frame 1 is t = 100 (frame 1 of b.xyz) as `grainshock render` draws that snapshot.
  expect_frame_is_render(d, files[1], files[0], dir);

  const std::string dump = (in / "three.lammpstrj").string();
  {
    std::ofstream o(dump, std::ios::binary);
    o << dump_frame(read_snapshot(files[2]), 300) << dump_frame(read_snapshot(files[0]), 100)
      << dump_frame(read_snapshot(files[1]), 200);
  }
  const auto dump_dir = fresh_dir("multi_dump");
  const Result rd = movie(dump + size + " --keep-frames --out " + dump_dir.string());
  ASSERT_EQ(rd.exit_code, 0) << rd.err;
  EXPECT_EQ(decode_movie(dump_dir / "movie.mp4").frames, 3);
  expect_kept_frame_times(dump_dir, {50, 100, 150});
}

// The rows (top to bottom) of the kept frame's box outline: rows holding at least 40 pixels of
// the outline's colour (halfway from the background to the text), which no row of glyphs has.
std::pair<int, int> outline_rows(const fs::path& png) {
  const Image img = read_png(png.string());
  const Palette pal = palette(Style{}.background);
  std::uint8_t line[3];
  for (int k = 0; k < 3; ++k) line[k] = std::uint8_t((pal.background[k] + pal.text[k]) / 2);
  int top = -1, bottom = -1;
  for (int y = 0; y < img.height; ++y) {
    int count = 0;
    for (int x = 0; x < img.width; ++x) {
      const std::uint8_t* p = img.pixel(x, y);
      count += p[0] == line[0] && p[1] == line[1] && p[2] == line[2];
    }
    if (count < 40) continue;
    if (top < 0) top = y;
    bottom = y;
  }
  return {top, bottom};
}

// A box that moves: `movie` draws it in one fixed camera that frames the union of the boxes,
// each frame outlining its own box. The top and bottom edges of the outline, in pixels, must
// lie as far apart as the box's edge (40, 34, 28, 22) and stay centred (the box shrinks about
// its centre and the camera does not move).
void expect_shrinking_outline(const fs::path& frames, const std::vector<double>& edges) {
  const auto [top0, bottom0] = outline_rows(frames / "frame_00000.png");
  ASSERT_GT(bottom0, top0 + 20) << "no outline in the first frame";
  for (std::size_t k = 1; k < edges.size(); ++k) {
    char name[32];
    std::snprintf(name, sizeof name, "frame_%05zu.png", k);
    const auto [top, bottom] = outline_rows(frames / name);
    ASSERT_GT(bottom, top) << name << ": no outline";
    // Within 2 px of the box's share of the first frame's outline (edges land on whole pixels).
    EXPECT_NEAR(bottom - top, (bottom0 - top0) * edges[k] / edges[0], 2.0) << name;
    EXPECT_NEAR(top + bottom, top0 + bottom0, 3.0) << name;
  }
}

// A LAMMPS dump whose box shrinks from 40 to 22 over four frames, the atoms moving with it (what
// `fix deform ... remap x` writes): refused before as "a movie's frames share one box".
TEST(MovieCommand, ABoxThatShrinksIsDrawnInOneCameraEachFrameWithItsOwnBox) {
  const auto dir = fresh_dir("shrinking");
  const std::string dump = std::string(GRAINSHOCK_ASSETS_DIR) + "/io/shrinking_box_2d.lammpstrj";
  const Result r = movie(dump + " --camera fixed --width 320 --height 240 --keep-frames --quiet "
                         "--out " + dir.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(decode_movie(dir / "movie.mp4").frames, 4);
  expect_shrinking_outline(dir / "frames", {40, 34, 28, 22});
}

// The same with a dump written by LAMMPS itself: a dilute 2D Lennard-Jones gas squeezed to 0.8 of its
// edge by fix deform over 300 steps, dumped every 100.
TEST(MovieCommand, ALammpsFixDeformRunIsDrawnWithItsShrinkingBox) {
  if (std::system("command -v lmp >/dev/null 2>&1") != 0)
    GTEST_SKIP() << "no lmp program to write a fix deform dump with (Debian package lammps)";
  const auto in = fresh_dir("deform_input"), dir = fresh_dir("deform");
  fs::create_directories(in);
  std::ofstream(in / "in.deform")
      << "units lj\ndimension 2\nboundary p p p\natom_style atomic\nlattice sq 0.1\n"
         "region box block 0 20 0 20 -0.5 0.5\ncreate_box 1 box\ncreate_atoms 1 box\n"
         "mass 1 1.0\nvelocity all create 1.0 87287 loop geom\npair_style lj/cut 2.5\n"
         "pair_coeff 1 1 1.0 1.0 2.5\nfix 1 all nve\nfix 2 all enforce2d\n"
         "fix 3 all deform 1 x scale 0.8 y scale 0.8 remap x\n"
         "dump 1 all custom 100 deform.lammpstrj id type x y z vx vy vz\nrun 300\n";
  const std::string lmp =
      "cd " + in.string() + " && lmp -in in.deform -log none -screen none >/dev/null 2>&1";
  ASSERT_EQ(std::system(lmp.c_str()), 0) << lmp;
  const Result r = movie((in / "deform.lammpstrj").string() +
                         " --camera fixed --width 320 --height 240 --keep-frames --quiet --out " +
                         dir.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(decode_movie(dir / "movie.mp4").frames, 4);
  // fix deform scales the edge linearly in time: 1, 0.9333, 0.8667, 0.8 of it.
  expect_shrinking_outline(dir / "frames", {1, 14 / 15.0, 13 / 15.0, 0.8});
}

// The camera turns by --orbit over the movie: the first frame is the picture at --azimuth, the
// last the picture at --azimuth + --orbit.
// Others' 3D files are drawn whole by default, as `render` draws them (and OVITO): a movie of
// an argon box's two frames is the --slab 0 movie, frame by frame, and --slab 6 is another one.
TEST(MovieCommand, Others3dFilesAreDrawnWholeUnlessASlabIsAskedFor) {
  const fs::path dir = fresh_dir("others_3d");
  fs::create_directories(dir);
  const fs::path atoms = dir / "atoms.xyz";
  {
    std::ofstream f(atoms);
    unsigned x = 12345;
    auto next = [&] { return (x = x * 1103515245u + 12345u) / 4294967296.0 * 20; };
    for (int frame = 0; frame < 2; ++frame) {
      f << "300\nLattice=\"20 0 0 0 20 0 0 0 20\" Properties=species:S:1:pos:R:3 Time=" << frame
        << " pbc=\"T T T\"\n";
      for (int i = 0; i < 300; ++i) {
        const double a = next(), b = next(), c = next();
        f << "Ar " << a << " " << b << " " << c << "\n";
      }
    }
  }
  auto frames_of = [&](const std::string& flags) {
    std::string name = "movie" + flags;
    std::replace(name.begin(), name.end(), ' ', '_');
    const fs::path out = dir / name;
    const Result r = movie(atoms.string() + " --camera fixed --width 160 --height 120 " + flags +
                           " --keep-frames --quiet --out " + out.string());
    EXPECT_EQ(r.exit_code, 0) << r.err;
    std::vector<std::vector<std::uint8_t>> images;
    for (int k = 0; k < 2; ++k)
      images.push_back(
          read_png((out / "frames" / ("frame_0000" + std::to_string(k) + ".png")).string()).rgba);
    return images;
  };
  const auto by_default = frames_of("");
  EXPECT_EQ(by_default, frames_of("--slab 0")) << "the default is not the whole box";
  EXPECT_NE(by_default, frames_of("--slab 6"));
}

TEST(MovieCommand, OrbitTurnsTheCameraByTheGivenAzimuth) {
  const auto files =
      stored_snapshots("orbit_run", "--dim 3 --medium box --particles 3000 --seed 5 --t-max 200");
  const auto dir = fresh_dir("orbit");
  const std::string snap = files[3];
  const Result r = movie(snap + " " + snap + " " + snap +
                         " --camera fixed --slab 0 --azimuth 30 --orbit 90 --width 240 --height"
                         " 180 --out " +
                         dir.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Decoded first = decode_movie(dir / "movie.mp4", 0);
  const Decoded last = decode_movie(dir / "movie.mp4", 2);
  ASSERT_EQ(first.frames, 3);
  std::vector<Image> at;
  for (const char* az : {"30", "120"}) {
    const auto png = dir / (std::string("az_") + az + ".png");
    ASSERT_EQ(test::grainshock("render " + snap + " --framing box --slab 0 --no-inset --azimuth " +
                               az + " --width 240 --height 180 --out " + png.string())
                  .exit_code,
              0);
    at.push_back(read_png(png.string()));
  }
  EXPECT_GE(psnr(first.rgb, at[0], 240, 180), 30.0);
  EXPECT_GE(psnr(last.rgb, at[1], 240, 180), 30.0);
  EXPECT_LT(psnr(last.rgb, at[0], 240, 180), psnr(last.rgb, at[1], 240, 180) - 3);
}

TEST(MovieCommand, BadStoredSnapshotsAreOneLineAndLeaveNothing) {
  const auto files = stored_snapshots("bad_run", std::string(kSmallRun) + " --t-max 200");
  const auto three =
      stored_snapshots("bad_run_3d", "--dim 3 --medium box --particles 3000 --t-max 200");
  const auto junk = fresh_dir("junk_input");
  fs::create_directories(junk);
  const std::string corrupt = (junk / "corrupt.xyz").string();
  { std::ofstream(corrupt) << "3\nProperties=species:S:1:pos:R:3 Dim=2\nX 1 1 0\n"; }
  const std::string no_velo = (junk / "no_velo.xyz").string();
  { std::ofstream(no_velo) << "1\nProperties=species:S:1:pos:R:3 Time=120 Dim=2\nX 1 1 0\n"; }
  const std::vector<std::pair<std::string, std::string>> bad = {
      {files[0] + " --color-by temperature", "scaled-speed, speed"},
      {files[0] + " " + no_velo + " " + files[1], "no_velo.xyz"},
      {files[0] + " " + three[1], "dimension"},
      {files[0] + " " + corrupt + " " + files[1], "corrupt.xyz"},
      {files[0] + " --orbit 90", "--orbit"},
      {files[0] + " --particles 10", "--particles"},
  };
  int i = 0;
  for (const auto& [args, needle] : bad) {
    const auto dir = fresh_dir("bad_stored" + std::to_string(i++));
    const Result r = movie(args + " --quiet --out " + dir.string());
    EXPECT_NE(r.exit_code, 0) << args;
    EXPECT_EQ(r.err_lines(), 1) << args << ": " << r.err;
    EXPECT_NE(r.err.find(needle), std::string::npos) << args << ": " << r.err;
    EXPECT_FALSE(fs::exists(dir)) << args << ": nothing is made";
  }
  // A bad frame in the middle of a file of three: the message names the file and the frame, and
  // a folder that existed (--force) is left as it was.
  const std::string mid = (junk / "bad_middle.xyz").string();
  {
    std::string second = slurp(files[1]);
    const auto line3 = second.find('\n', second.find('\n') + 1) + 1;  // first particle's line
    second.replace(line3 + 2, second.find(' ', line3 + 2) - line3 - 2, "abc");
    std::ofstream(mid, std::ios::binary) << slurp(files[0]) << second << slurp(files[2]);
  }
  const auto kept = fresh_dir("bad_stored_kept");
  fs::create_directories(kept);
  { std::ofstream(kept / "notes.txt") << "earlier results\n"; }
  const Result rm = movie(mid + " --keep-frames --force --quiet --out " + kept.string());
  EXPECT_NE(rm.exit_code, 0);
  EXPECT_EQ(rm.err_lines(), 1) << rm.err;
  EXPECT_NE(rm.err.find("bad_middle.xyz"), std::string::npos) << rm.err;
  EXPECT_NE(rm.err.find("frame 1 of 3"), std::string::npos) << rm.err;
  EXPECT_EQ(names_in(kept), std::vector<std::string>{"notes.txt"});
  // --orbit on a live 2D movie too.
  const auto dir = fresh_dir("bad_orbit_live");
  const Result r =
      movie(std::string(kSmallRun) + " --t-max 100 --frames 5 --orbit 45 --out " + dir.string());
  EXPECT_NE(r.exit_code, 0);
  EXPECT_EQ(r.err_lines(), 1) << r.err;
  EXPECT_NE(r.err.find("--orbit"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir));
}

TEST(MovieCommand, SigtermFinishesTheMovieWithTheFramesSoFar) {
  const auto dir = fresh_dir("sigterm");
  // A fixed camera and colour range need no first pass, so frames flow from the start; the run
  // is far longer than the test waits. A fixed camera frames the box: --medium box.
  std::vector<std::string> args = {GRAINSHOCK_BINARY,
                                   "movie",
                                   "--medium",
                                   "box",
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
  // Beside the movie so far, what `grainshock resume` goes on from: the checkpoint of the last
  // part's end (a stop between two leaves it, so the previous one is there only if a stop fell
  // on a part's end or a second checkpoint was due).
  std::vector<std::string> names = names_in(dir);
  std::erase(names, "movie.checkpoint.prev.bin");
  EXPECT_EQ(names, (std::vector<std::string>{"frames", "movie.checkpoint.bin", "movie.mp4",
                                             "movie.parts", "movie.toml"}));
  const Decoded d = decode_movie(dir / "movie.mp4");
  EXPECT_EQ(d.frames, static_cast<int>(pngs)) << "every rendered frame is in the movie";
  EXPECT_NEAR(d.duration, pngs / 30.0, 1e-3);
}

// A movie killed at random moments (the seed is printed so that a failure can be replayed) and
// resumed draws the very frames of one never stopped: its --keep-frames PNGs are the same bytes,
// in 2D and in a 3D slab, with and without the pass that finds the colour range. Its movie is
// the parts (of --keyint frames, each encoded alone) joined without encoding again: the very
// bytes of the uninterrupted movie, and of a second uninterrupted one.
TEST(MovieCommand, KilledAtRandomMomentsAndResumedDrawsTheSameFrames) {
  const unsigned seed = static_cast<unsigned>(std::random_device{}());
  std::mt19937 random(seed);
  SCOPED_TRACE("random seed " + std::to_string(seed));
  const std::string cases[] = {
      "--medium box --particles 100000 --t-max 60000 --frames 60",
      "--medium box --particles 100000 --t-max 60000 --frames 40 --color-by speed",  // range pass
      "--dim 3 --medium box --particles 60000 --t-max 10000 --frames 40 --restitution 0.5",
  };
  int n = 0;
  for (const std::string& c : cases) {
    SCOPED_TRACE(c);
    const std::string args = c + " --width 192 --height 144 --keyint 7 --keep-frames --quiet";
    const auto ref = fresh_dir("resume_ref" + std::to_string(n)),
               cut = fresh_dir("resume_cut" + std::to_string(n));
    ++n;
    ASSERT_EQ(movie(args + " --out " + ref.string()).exit_code, 0);
    test::kill_and_resume("movie", args, cut, "movie.checkpoint.bin", 2, 600, random);
    ASSERT_EQ(names_in(cut), (std::vector<std::string>{"frames", "movie.mp4", "movie.toml"}))
        << "a finished movie keeps no checkpoint or parts";
    const auto frames = names_in(ref / "frames");
    ASSERT_EQ(names_in(cut / "frames"), frames);
    for (const auto& f : frames)
      EXPECT_TRUE(test::read_file(ref / "frames" / f) == test::read_file(cut / "frames" / f))
          << f << " differs";
    const int count = static_cast<int>(frames.size());
    const Decoded b = decode_movie(cut / "movie.mp4", count - 1);
    ASSERT_EQ(b.frames, count);
    EXPECT_TRUE(test::read_file(ref / "movie.mp4") == test::read_file(cut / "movie.mp4"))
        << "the resumed movie is not the bytes of the one never stopped";
    const Result alike =
        test::grainshock("compare " + (ref / "movie.mp4").string() + " " +
                         (cut / "movie.mp4").string());
    EXPECT_EQ(alike.exit_code, 0) << alike.out << alike.err;
    if (n == 1) {  // the encode itself is the same every time
      const auto again = fresh_dir("resume_again");
      ASSERT_EQ(movie(args + " --out " + again.string()).exit_code, 0);
      EXPECT_TRUE(test::read_file(ref / "movie.mp4") == test::read_file(again / "movie.mp4"))
          << "two runs of one movie command gave different bytes";
    }
  }
}

// A part of a killed movie damaged on disk is refused by resume, in one line naming it, and the
// folder is left as it was (the parts too); the old resume joined it into the movie.
TEST(MovieCommand, ResumeRefusesADamagedPart) {
  const auto dir = fresh_dir("damaged_part");
  const pid_t pid = test::spawn_grainshock(
      "movie " + std::string(kSmallRun) +
      " --t-max 100000 --frames 20000 --frame-spacing lin --keyint 5 --width 96 --height 72 "
      "--keep-frames --checkpoint-every 0.001 --out " +
      dir.string());
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(300);
  // Frame 12 is drawn after the checkpoint at frame 10 has named two parts.
  while (!fs::exists(dir / "frames" / "frame_00012.png") &&
         std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  kill(pid, SIGKILL);
  waitpid(pid, nullptr, 0);
  const fs::path part = dir / "movie.parts" / "part_0000.mp4";
  ASSERT_TRUE(fs::exists(part));
  std::string bytes = test::read_file(part);
  bytes[bytes.size() / 2] ^= 0x20;
  std::ofstream(part, std::ios::binary | std::ios::trunc) << bytes;
  // Every file but the temporaries the killed writer left (a PNG or part being written), which
  // resume clears before it reads the checkpoint.
  auto files = [&] {
    std::vector<std::pair<std::string, std::string>> all;
    for (const auto& e : fs::recursive_directory_iterator(dir)) {
      const std::string name = e.path().filename().string();
      if (name.find(".tmp.") != std::string::npos || name.ends_with(".partial")) continue;
      if (e.is_regular_file()) all.emplace_back(e.path().string(), test::read_file(e.path()));
    }
    std::sort(all.begin(), all.end());
    return all;
  };
  const auto before = files();
  const Result r = test::grainshock("resume " + dir.string());
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_EQ(r.err_lines(), 1) << r.err;
  EXPECT_NE(r.err.find("part_0000.mp4"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("damaged"), std::string::npos) << r.err;
  EXPECT_TRUE(files() == before) << "the refused resume changed the folder";
}

// resume refuses, in one line and touching nothing: a finished movie, a checkpoint of another
// movie.toml, a corrupt checkpoint, and a movie of stored snapshots.
TEST(MovieCommand, ResumeRefusesWhatItCannotGoOnFrom) {
  const auto dir = fresh_dir("resume_bad");
  ASSERT_EQ(movie(std::string(kSmallRun) + " --frames 10 --out " + dir.string()).exit_code, 0);
  auto expect_refused = [&](const std::string& what, const std::string& says) {
    SCOPED_TRACE(what);
    const auto before = names_in(dir);
    const Result r = test::grainshock("resume " + dir.string());
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_EQ(r.err_lines(), 1) << r.err;
    EXPECT_NE(r.err.find(says), std::string::npos) << r.err;
    EXPECT_EQ(names_in(dir), before);
  };
  expect_refused("finished", "finished movie");
  // A kill after the checkpoints were removed but before the parts were: a finished movie.
  fs::create_directories(dir / "movie.parts");
  std::ofstream(dir / "movie.parts" / "part_0000.mp4") << "left by a kill";
  const Result leftover = test::grainshock("resume --quiet " + dir.string());
  EXPECT_EQ(leftover.exit_code, 0) << leftover.err;
  EXPECT_FALSE(fs::exists(dir / "movie.parts"));
  expect_refused("finished again", "finished movie");
  std::ofstream(dir / "movie.checkpoint.bin") << "not a checkpoint";
  expect_refused("corrupt", "movie.checkpoint.bin");

  // A checkpoint of this movie, then another movie.toml.
  const auto cut = fresh_dir("resume_other");
  const std::string args =
      std::string(kSmallRun) + " --t-max 100000 --frames 20000 --frame-spacing lin";
  const pid_t pid = test::spawn_grainshock("movie " + args + " --out " + cut.string());
  while (!fs::exists(cut / "movie.checkpoint.bin"))
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  kill(pid, SIGKILL);
  waitpid(pid, nullptr, 0);
  std::string other_toml = test::read_file(cut / "movie.toml");
  const auto at = other_toml.find("seed = 7");
  ASSERT_NE(at, std::string::npos);
  other_toml.replace(at, 8, "seed = 8");
  std::ofstream(cut / "movie.toml") << other_toml;
  const auto before = names_in(cut);
  const Result other = test::grainshock("resume " + cut.string());
  EXPECT_EQ(other.exit_code, 1);
  EXPECT_EQ(other.err_lines(), 1) << other.err;
  EXPECT_NE(other.err.find("another movie"), std::string::npos) << other.err;
  EXPECT_EQ(names_in(cut), before);

  const auto stored = fresh_dir("resume_stored");
  const auto files =
      stored_snapshots("resume_stored_run", "--medium box --particles 3000 --t-max 200");
  ASSERT_EQ(movie(files[0] + " " + files[1] + " --quiet --out " + stored.string()).exit_code, 0);
  const Result s = test::grainshock("resume " + stored.string());
  EXPECT_EQ(s.exit_code, 1);
  EXPECT_NE(s.err.find("stored snapshots"), std::string::npos) << s.err;
}

}  // namespace
}  // namespace gs::render
