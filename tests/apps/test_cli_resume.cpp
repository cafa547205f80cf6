// `grainshock resume`: a run killed (-9) at random moments and resumed ends with the same files,
// byte for byte, as one never interrupted; what cannot be resumed is refused in one line with
// nothing touched. And the run files: run.toml reproduces its run, flag by flag.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <set>
#include <sstream>
#include <thread>

#include "tests/apps/cli_test_util.h"

namespace gs {
namespace {

using test::grainshock;
using test::read_file;
using test::scratch_dir;
using test::spawn_grainshock;
using test::words;
namespace fs = std::filesystem;

// Every file of a folder, by relative path, with its bytes; timing.json holds wall times.
std::map<std::string, std::string> files_of(const fs::path& dir) {
  std::map<std::string, std::string> out;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.is_regular_file() && e.path().filename() != "timing.json")
      out[fs::relative(e.path(), dir).string()] = read_file(e.path());
  return out;
}

void expect_same_folder(const fs::path& a, const fs::path& b) {
  const auto fa = files_of(a), fb = files_of(b);
  std::set<std::string> na, nb;
  for (const auto& [name, bytes] : fa) na.insert(name);
  for (const auto& [name, bytes] : fb) nb.insert(name);
  ASSERT_EQ(na, nb);
  for (const auto& [name, bytes] : fa) EXPECT_TRUE(bytes == fb.at(name)) << name << " differs";
}

// The kill moments are drawn at random (seeded from the clock, printed so that a failure can be
// replayed); each case runs for about a second, so a kill lands anywhere in it.
TEST(CliResume, KilledAtRandomMomentsAndResumedGivesTheSameFiles) {
  const unsigned seed = static_cast<unsigned>(std::random_device{}());
  std::mt19937 random(seed);
  SCOPED_TRACE("random seed " + std::to_string(seed));
  const std::string cases[] = {
      "--dim 2 --medium box --particles 20000 --t-max 60000 --restitution 0.5 --snapshot-times "
      "100,10000",
      "--dim 3 --medium box --particles 20000 --t-max 20000 --restitution 0.3 --snapshot-times 500",
      "--dim 2 --particles 3000 --t-max 300 --initial thermal --restitution 0.95",
      "--dim 3 --particles 3000 --t-max 150 --initial thermal --restitution 0.95 --per-decade 40",
      // One GSD file per snapshot time, whose bytes depend only on the state written.
      "--dim 2 --medium box --particles 20000 --t-max 60000 --restitution 0.5 --snapshot-times "
      "100,10000 --snapshot-format gsd --snapshot-particles active",
      // The unbounded medium: its checkpoints hold the cells made so far.
      "--dim 2 --medium unbounded --particles 40000 --t-max 60000 --restitution 0.5 "
      "--snapshot-times 100,10000",
  };
  int n = 0;
  for (const std::string& c : cases) {
    SCOPED_TRACE(c);
    const auto ref = scratch_dir("ref" + std::to_string(n)),
               cut = scratch_dir("cut" + std::to_string(n));
    ++n;
    ASSERT_EQ(grainshock("run " + c + " --quiet --out " + ref.string()).exit_code, 0);
    test::kill_and_resume("run", c + " --quiet", cut, "checkpoint.bin", 2, 400, random);
    expect_same_folder(ref, cut);
    EXPECT_FALSE(fs::exists(cut / "checkpoint.bin")) << "a finished run keeps no checkpoint";
  }
}

// A new run with --movie draws its movie as it goes. Killed then, it resumes by replaying the run
// for its movie after sampling; killed after sampling, its movie is in place and is kept; either
// way it ends with the files, movie.mp4 included, of a run never interrupted. The kills land
// anywhere in a run of a few seconds.
TEST(CliResume, ARunWithItsMovieKilledAndResumedGivesTheSameFiles) {
  const unsigned seed = static_cast<unsigned>(std::random_device{}());
  std::mt19937 random(seed);
  SCOPED_TRACE("random seed " + std::to_string(seed));
  const std::string c =
      "--dim 2 --medium box --particles 20000 --t-max 20000 --restitution 0.5 --snapshot-times "
      "500 --png --width 320 --height 180 --movie --movie-inset --quiet";
  const auto ref = scratch_dir("movie_ref");
  const auto r = grainshock("run " + c + " --out " + ref.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  ASSERT_TRUE(fs::exists(ref / "movie.mp4"));
  for (int trial = 0; trial < 2; ++trial) {
    const auto cut = scratch_dir("movie_cut" + std::to_string(trial));
    test::kill_and_resume("run", c, cut, "checkpoint.bin", 2, 2500, random);
    expect_same_folder(ref, cut);
  }
}

// Ctrl-C writes a checkpoint; the stopped run says so, and resumes to the same files.
TEST(CliResume, StoppedBySigintAndResumed) {
  const std::string c =
      "--dim 2 --medium box --particles 20000 --t-max 60000 --restitution 0.5 --quiet";
  const auto ref = scratch_dir("ref"), cut = scratch_dir("cut");
  ASSERT_EQ(grainshock("run " + c + " --out " + ref.string()).exit_code, 0);
  const pid_t pid = spawn_grainshock("run " + c + " --out " + cut.string());
  while (!fs::exists(cut / "checkpoint.bin"))
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  std::this_thread::sleep_for(std::chrono::milliseconds(150));
  kill(pid, SIGINT);
  int status = 0;
  ASSERT_EQ(waitpid(pid, &status, 0), pid);
  ASSERT_TRUE(WIFEXITED(status));
  if (WEXITSTATUS(status) == 0) GTEST_SKIP() << "the run finished before the signal came";
  EXPECT_EQ(WEXITSTATUS(status), 128 + SIGINT);
  EXPECT_NE(read_file(cut / "summary.json").find("\"interrupted\": true"), std::string::npos);
  const auto r = grainshock("resume --quiet " + cut.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  expect_same_folder(ref, cut);
}

// A kill after summary.json (the last result) but before the checkpoints are removed leaves a
// finished run: resume removes them, changes nothing else, and succeeds (a kill at that moment
// once made this resume fail, so that the random kills above were flaky).
TEST(CliResume, AKillAfterTheLastResultLeavesAFinishedRun) {
  const auto dir = scratch_dir("done");
  ASSERT_EQ(grainshock("run --dim 2 --medium box --particles 2000 --t-max 300 --quiet --out " +
                       dir.string())
                .exit_code,
            0);
  const auto before = files_of(dir);
  std::ofstream(dir / "checkpoint.bin") << "left by a kill";
  std::ofstream(dir / "checkpoint.prev.bin") << "left by a kill";
  const auto r = grainshock("resume --quiet " + dir.string());
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(files_of(dir), before);
  // Without checkpoints it is still refused: there is nothing to resume.
  EXPECT_EQ(grainshock("resume --quiet " + dir.string()).exit_code, 1);
}

// Refusals: one line, exit 1, and the folder exactly as it was.
TEST(CliResume, WhatCannotBeResumedIsRefused) {
  const std::string c = "--dim 2 --medium box --particles 2000 --quiet";
  const auto done = scratch_dir("done"), cut = scratch_dir("cut"), empty = scratch_dir("empty");
  ASSERT_EQ(grainshock("run " + c + " --t-max 300 --out " + done.string()).exit_code, 0);
  fs::create_directories(empty);
  // A run stopped by a signal keeps its checkpoint: the material for the damaged cases. It
  // replaces a finished run (--force).
  ASSERT_EQ(
      grainshock("run " + c + " --t-max 300 --snapshot-times 100 --out " + cut.string()).exit_code,
      0);
  ASSERT_EQ(grainshock("run " + c + " --force --t-max 1e9 --out " + cut.string(),
                       "timeout --preserve-status -s INT 1")
                .exit_code,
            128 + SIGINT);
  ASSERT_TRUE(fs::exists(cut / "checkpoint.bin"));
  EXPECT_FALSE(fs::exists(cut / "snapshots/tsim_100.xyz")) << "--force left the old run's files";
  const std::string good = read_file(cut / "checkpoint.bin"), toml = read_file(cut / "run.toml");
  auto refused = [&](const fs::path& dir, const std::string& says) {
    const bool exists = fs::exists(dir);
    const auto before = exists ? files_of(dir) : std::map<std::string, std::string>{};
    const auto r = grainshock("resume " + dir.string());
    EXPECT_EQ(r.exit_code, 1) << says << ": " << r.err;
    EXPECT_EQ(r.err_lines(), 1) << r.err;
    EXPECT_NE(r.err.find(says), std::string::npos) << r.err;
    EXPECT_EQ(fs::exists(dir), exists);
    if (exists) {
      EXPECT_TRUE(files_of(dir) == before) << says << ": the folder was touched";
    }
  };
  refused(done, "finished run");
  refused(empty, "not a run folder");
  refused(cut / "nowhere", "not a run folder");
  std::ofstream(cut / "checkpoint.bin", std::ios::binary | std::ios::trunc)
      << good.substr(0, good.size() / 2);
  refused(cut, "truncated");
  std::string flipped = good;
  flipped[good.size() - 3] ^= 1;
  std::ofstream(cut / "checkpoint.bin", std::ios::binary | std::ios::trunc) << flipped;
  refused(cut, "checksum");
  std::ofstream(cut / "checkpoint.bin", std::ios::binary | std::ios::trunc) << good;
  std::ofstream(cut / "run.toml", std::ios::trunc)
      << toml.substr(0, toml.find("restitution")) << "restitution = 0.7\n"
      << toml.substr(toml.find("cutoff"));
  refused(cut, "another run");
  std::ofstream(cut / "run.toml", std::ios::trunc) << toml;
}

// A run killed in its set-up, before its first checkpoint, leaves run.toml, the header of
// timeseries.csv, an empty snapshots/ and a checkpoint being written: resume starts it again
// from t = 0 and ends with the files of a run never stopped; `run` without --force says how.
TEST(CliResume, KilledBeforeItsFirstCheckpointStartsAgain) {
  const std::string c =
      "--dim 2 --medium box --particles 3000 --restitution 0.5 --t-max 400 --snapshot-times 100 "
      "--png --width 64 --height 48 --quiet";
  const auto whole = scratch_dir("whole"), cut = scratch_dir("cut");
  ASSERT_EQ(grainshock("run " + c + " --out " + whole.string()).exit_code, 0);
  fs::create_directories(cut / "snapshots");
  fs::copy_file(whole / "run.toml", cut / "run.toml");
  const std::string csv = read_file(whole / "timeseries.csv");
  std::ofstream(cut / "timeseries.csv", std::ios::binary) << csv.substr(0, csv.find('\n') + 1);
  std::ofstream(cut / "checkpoint.bin.tmp.4242", std::ios::binary) << "cut by the kill";
  const auto again = grainshock("run " + c + " --out " + cut.string());
  EXPECT_EQ(again.exit_code, 1);
  EXPECT_NE(again.err.find("--force"), std::string::npos) << again.err;
  const auto r = grainshock("resume " + cut.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("starts again from t = 0"), std::string::npos) << r.err;
  expect_same_folder(whole, cut);
}

std::vector<std::string> run_flags() {
  // Every long flag `run --help` lists.
  const auto help = fs::path(GRAINSHOCK_TEST_OUTPUT_DIR) / "run_help.txt";
  EXPECT_EQ(std::system((std::string(GRAINSHOCK_BINARY) + " run --help >" + help.string()).c_str()),
            0);
  std::vector<std::string> flags;
  for (const std::string& w : words(read_file(help)))
    if (w.starts_with("--") && w.size() > 2) {
      const std::string f = w.substr(0, w.find_first_not_of("abcdefghijklmnopqrstuvwxyz-", 2));
      if (std::find(flags.begin(), flags.end(), f) == flags.end()) flags.push_back(f);
    }
  return flags;
}

// run.toml holds every flag that shapes the results, and `run --config run.toml` makes the same
// files (a run file of every flag set away from its default: 2D with pictures, and 1D).
TEST(CliRunFile, EveryFlagRoundTrips) {
  // --no-page leaves out index.html, a view of the results and not one of them.
  const std::set<std::string> not_results = {"--help",    "--config", "--out",
                                             "--force",   "--quiet",  "--checkpoint-every",
                                             "--version", "--no-page"};
  const std::string runs[] = {
      "--dim 2 --medium box --particles 600 --density 0.3 --restitution 0.7 --cutoff 0.001 "
      "--speed 2 --seed 5 --realisation 3 --t-max 60 --initial kick --kick-site centre "
      "--temperature 2 --per-decade 7 --sample-every 5 --snapshot-times 10,20 --png "
      "--compare-elastic --width 64 --height 48",
      "--dim 1 --particles 300 --lattice 2 --restitution 0 --t-max 400 --sample-every 50",
      "--dim 3 --particles 1000 --initial thermal --temperature 0.5 --restitution 0.9 "
      "--t-max 2 --snapshot-times 1 --snapshot-format gsd --snapshot-particles active",
      "--dim 2 --medium box --particles 400 --t-max 30 --snapshot-times 10 --snapshot-format "
      "ovito-xyz --png "
      "--width 32 --height 32",
      "--dim 3 --medium unbounded --particles 20000 --t-max 50 --restitution 0.5",
  };
  for (int n = 0; const std::string& args : runs) {
    const std::string tag = std::to_string(n++);
    const auto a = scratch_dir("a" + tag), b = scratch_dir("b" + tag);
    ASSERT_EQ(grainshock("run " + args + " --quiet --out " + a.string()).exit_code, 0) << args;
    const std::string toml = read_file(a / "run.toml");
    // The physics keys are to_toml's, which writes `medium` only for the unbounded medium (box
    // runs' run.toml and checkpoints stay those of the runs made before it existed).
    const bool box = args.find("--medium unbounded") == std::string::npos;
    for (const std::string& flag : run_flags())
      if (!not_results.contains(flag) && !(box && flag == "--medium")) {
        const std::string line = flag.substr(2) + " = ";
        EXPECT_NE(toml.find("\n" + line), std::string::npos) << flag;
      }
    const auto r =
        grainshock("run --quiet --config " + (a / "run.toml").string() + " --out " + b.string());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    expect_same_folder(a, b);
  }
}

// The Fig. 1 job is the default of the outputs: physics flags keep it (with that physics), an
// output flag replaces it. Seen in run.toml, written before the run starts.
TEST(CliRunFile, PhysicsFlagsKeepTheFig1Job) {
  auto toml_of = [](const std::string& args) {
    const auto dir = scratch_dir("fig1");
    const pid_t pid = spawn_grainshock("run --quiet " + args + " --out " + dir.string());
    while (!fs::exists(dir / "run.toml") && waitpid(pid, nullptr, WNOHANG) == 0)
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
    kill(pid, SIGKILL);
    waitpid(pid, nullptr, 0);
    return read_file(dir / "run.toml");
  };
  const std::string seed2 = toml_of("--seed 2");
  EXPECT_NE(seed2.find("seed = 2\n"), std::string::npos);
  // Paper times 5000 ... 50000 at n = 0.25 in 2D are simulation times 10000 ... 100000.
  EXPECT_NE(seed2.find("snapshot-times = [10000.0, 20000.0, 40000.0, 1e+05]"), std::string::npos)
      << seed2;
  EXPECT_NE(seed2.find("png = true\ncompare-elastic = true\nmovie = true\nmovie-inset = true"),
            std::string::npos);
  const std::string dense = toml_of("--density 0.16 --width 800");
  EXPECT_NE(dense.find("t-max = 125000.0"), std::string::npos) << dense;  // 50000 / 0.4
  EXPECT_NE(dense.find("width = 800"), std::string::npos);
  const std::string own = toml_of("--t-max 500");
  EXPECT_NE(own.find("snapshot-times = []\npng = false\ncompare-elastic = false\nmovie = false"),
            std::string::npos)
      << own;
}

}  // namespace
}  // namespace gs
