// Nothing a user types hangs or ignores a stop: the inputs that once hung (r = 0 in 2D and 3D, a
// vanishing density in the unbounded medium) end on their own, and every kind of long work ends
// with exit 130 soon after SIGINT or SIGTERM at a random moment, its files whole.
#include <gtest/gtest.h>

#include <chrono>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "tests/apps/cli_test_util.h"

namespace gs::test {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

// Waits up to `limit` for `pid` to end: its exit code, 1000 + the signal that killed it, or -1
// after killing it when it did not end in time.
int wait_for_exit(pid_t pid, std::chrono::milliseconds limit) {
  const auto deadline = Clock::now() + limit;
  int status = 0;
  for (;;) {
    const pid_t done = waitpid(pid, &status, WNOHANG);
    if (done == pid) return WIFEXITED(status) ? WEXITSTATUS(status) : 1000 + WTERMSIG(status);
    if (Clock::now() >= deadline) {
      kill(pid, SIGKILL);
      waitpid(pid, &status, 0);
      return -1;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
}

// `grainshock ARGS` run to its end within `limit`: the exit code and stderr, or -1 (killed).
CommandResult run_with_limit(const std::string& args, std::chrono::seconds limit,
                             const fs::path& err) {
  const pid_t pid = spawn_grainshock(args, err.string());
  CommandResult r;
  r.exit_code = wait_for_exit(pid, limit);
  r.err = read_file(err);
  return r;
}

// Every file under `dir` is whole: no temporary left beside a result, text ends with its
// newline, JSON with its brace, PNG with IEND, an MP4 holds its index (moov).
void expect_whole_files(const fs::path& dir) {
  if (!fs::exists(dir)) return;
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    if (!e.is_regular_file()) continue;
    const fs::path& p = e.path();
    const std::string name = p.filename().string(), ext = p.extension().string();
    EXPECT_EQ(name.find(".tmp."), std::string::npos) << "a temporary left: " << p;
    const std::string bytes = read_file(p);
    if (ext == ".csv" || ext == ".toml" || ext == ".xyz" || ext == ".md" || ext == ".gp") {
      EXPECT_TRUE(bytes.empty() || bytes.back() == '\n') << "half-written: " << p;
    } else if (ext == ".json") {
      EXPECT_NE(bytes.find_last_of('}'), std::string::npos) << p;
      EXPECT_EQ(bytes.find_first_not_of(" \n", bytes.find_last_of('}') + 1), std::string::npos)
          << "half-written: " << p;
    } else if (ext == ".png") {
      EXPECT_TRUE(bytes.size() > 12 && bytes.compare(bytes.size() - 8, 4, "IEND") == 0)
          << "half-written: " << p;
    } else if (ext == ".mp4") {
      EXPECT_NE(bytes.find("moov"), std::string::npos) << "no index: " << p;
    }
  }
}

// r = 0 in 2D and 3D used to hang at t = 15.6 (2D) or 5.4 (3D) with a dozen active particles: a
// touching pair that r = 0 had left with no normal speed was found colliding with itself at one
// instant forever (sim/collision.h, kGrazingFraction). Each of these runs takes a few seconds;
// the limit is far above that and far below the hang.
TEST(CliStop, StickyCollisionsIn2DAnd3DFinish) {
  const fs::path dir = scratch_dir("sticky");
  fs::create_directories(dir);
  const std::vector<std::string> cases = {
      "--dim 2 --medium box --restitution 0",
      "--dim 3 --medium box --restitution 0",
      "--dim 2 --restitution 0 --cutoff 0.1",
      "--dim 3 --restitution 0 --cutoff 0",  // no collapse guard at all (1e-400 is refused)
  };
  for (std::size_t k = 0; k < cases.size(); ++k) {
    const fs::path out = dir / ("run" + std::to_string(k));
    const auto r = run_with_limit("run --particles 20000 --t-max 2000 --quiet " + cases[k] +
                                      " --out " + out.string(),
                                  std::chrono::seconds(90), dir / "err.txt");
    EXPECT_EQ(r.exit_code, 0) << cases[k] << " (-1: still running after 90 s): " << r.err;
    EXPECT_TRUE(fs::exists(out / "summary.json")) << cases[k];
  }
}

// A density the unbounded medium cannot hold is refused at once, naming the density it needs, as
// the box refuses it; it used to look for a particle to kick through a billion empty cells,
// growing 14 MB/s and deaf to signals.
TEST(CliStop, VanishingDensityInTheUnboundedMediumIsRefused) {
  const fs::path dir = scratch_dir("dilute");
  fs::create_directories(dir);
  for (const char* dim : {"2", "3"})
    for (const char* density : {"1e-9", "1e-30", "1e-320", "1e-4"}) {
      if (std::string(dim) == "2" && std::string(density) == "1e-4") continue;  // 2D takes 3.1e-4
      const std::string args = std::string("run --dim ") + dim +
                               " --particles 20000 --t-max 2000 --density " + density +
                               " --out " + (dir / "run").string();
      const auto r = run_with_limit(args, std::chrono::seconds(20), dir / "err.txt");
      EXPECT_EQ(r.exit_code, 1) << args << " (-1: still running after 20 s): " << r.err;
      EXPECT_EQ(r.err_lines(), 1) << args << ": " << r.err;
      EXPECT_NE(r.err.find(std::string("--density ") + (dim[0] == '2' ? "0.00031" : "0.005") +
                           " or more"),
                std::string::npos)
          << args << ": " << r.err;
      EXPECT_FALSE(fs::exists(dir / "run")) << args;
    }
  // The least density it takes runs (to the edge of the medium's reach or to --t-max).
  const auto r = run_with_limit("run --dim 2 --particles 20000 --t-max 200 --density 0.00031 "
                                "--quiet --out " + (dir / "least").string(),
                                std::chrono::seconds(60), dir / "err.txt");
  EXPECT_EQ(r.exit_code, 0) << r.err;
}

// Whether `pid` has a handler for `sig` yet (SigCgt of /proc/PID/status): a signal before main()
// installs it ends any program at once, which says nothing about grainshock.
bool catches(pid_t pid, int sig) {
  std::ifstream status("/proc/" + std::to_string(pid) + "/status");
  for (std::string line; std::getline(status, line);)
    if (line.rfind("SigCgt:", 0) == 0)
      return (std::stoull(line.substr(7), nullptr, 16) >> (sig - 1)) & 1;
  return false;
}

struct Work {
  std::string what, args;
  std::string ready;  // a file under the output folder whose appearance says the work is under way
  int max_delay_ms;   // the random moment after it
  // How soon it must end: 2.5 s (the couple of seconds promised, on a busy machine), more where
  // the stop writes results: an interrupted ensemble fits what finished (its summary.json), which
  // took 4 s with the machine's two cores shared by 8 builds.
  int limit_ms = 2500;
};

// Starts the work, waits for it to be under way, signals it at a random moment and expects it to
// end with 130 within the promised couple of seconds (2.5 s: the machine may be busy), its files
// whole.
void interrupt_at_random(const Work& w, int sig, const fs::path& out, std::mt19937& random) {
  const fs::path err = out.string() + ".err";
  const pid_t pid = spawn_grainshock(w.args + " --out " + out.string(), err.string());
  const auto deadline = Clock::now() + std::chrono::seconds(120);
  while (!catches(pid, sig) && Clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  while (!w.ready.empty() && !fs::exists(out / w.ready) && Clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  std::this_thread::sleep_for(std::chrono::milliseconds(
      std::uniform_int_distribution<int>(0, w.max_delay_ms)(random)));
  ASSERT_EQ(kill(pid, sig), 0);
  const auto signalled = Clock::now();
  const int code = wait_for_exit(pid, std::chrono::milliseconds(w.limit_ms));
  const double seconds = std::chrono::duration<double>(Clock::now() - signalled).count();
  EXPECT_EQ(code, 130) << w.what << " (-1: still running " << w.limit_ms << " ms after signal " << sig
                       << ", 1000 + s: killed by signal s): " << read_file(err);
  std::printf("  %s: signal %d, exit %d after %.2f s\n", w.what.c_str(), sig, code, seconds);
  expect_whole_files(out);
}

TEST(CliStop, EveryKindOfWorkStopsAtARandomMoment) {
  const fs::path dir = scratch_dir("kinds");
  fs::create_directories(dir);
  std::mt19937 random(std::random_device{}());
  const std::vector<Work> works = {
      {"engine, box", "run --dim 3 --medium box --particles 200000 --t-max 1e7 --quiet",
       "timeseries.csv", 1500},
      {"engine, unbounded medium", "run --dim 3 --particles 2000000 --t-max 1e7 --quiet",
       "timeseries.csv", 1500},
      // Near its jamming limit random sequential addition of 2e5 discs takes about a minute,
      // the melting of a dense thermal start of 1e5 discs ten seconds.
      {"random sequential addition",
       "run --dim 2 --medium box --particles 200000 --density 0.68 --t-max 10 --quiet", "", 400},
      {"thermal start melting",
       "run --dim 2 --medium box --initial thermal --density 0.85 --particles 100000 "
       "--t-max 10 --quiet",
       "", 400},
      {"movie", "movie --dim 2 --particles 20000 --t-max 1e5 --frames 100000 --width 320 "
                "--height 240 --quiet", "movie.toml", 1500},
      // Once a realisation has finished (one interrupted before that exits 1, by its own rule).
      {"ensemble", "ensemble --dim 2 --particles 20000 --t-max 2000 --realisations 1000 --quiet",
       "realisations/000000", 1500, 10000},
      {"figures", "figures --tiny --quiet", "figures.toml", 3000, 10000},
  };
  int k = 0;
  for (const Work& w : works)
    for (int sig : {SIGINT, SIGTERM}) {
      std::string name = "w";
      name += std::to_string(k++);
      interrupt_at_random(w, sig, dir / name, random);
    }
}

// A second signal while the first is honoured ends the process at once, saying so, with 130;
// the files are whole (results are written to a temporary and renamed). It used to die by the
// signal, silently.
TEST(CliStop, SecondSignalExitsAtOnceWithAMessage) {
  const fs::path dir = scratch_dir("second");
  fs::create_directories(dir);
  int at_once = 0;
  for (auto [first, second] : {std::pair{SIGINT, SIGINT}, std::pair{SIGTERM, SIGINT},
                               std::pair{SIGINT, SIGTERM}}) {
    const fs::path out = dir / ("run" + std::to_string(first) + "_" + std::to_string(second));
    const fs::path err = out.string() + ".err";
    const pid_t pid = spawn_grainshock(
        "run --dim 3 --medium box --particles 200000 --t-max 1e7 --out " + out.string(),
        err.string());
    const auto deadline = Clock::now() + std::chrono::seconds(120);
    while (!fs::exists(out / "timeseries.csv") && Clock::now() < deadline)
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    ASSERT_EQ(kill(pid, first), 0);
    ASSERT_EQ(kill(pid, second), 0);
    EXPECT_EQ(wait_for_exit(pid, std::chrono::milliseconds(2500)), 130)
        << "(1000 + s: killed by signal s) " << read_file(err);
    const std::string text = read_file(err);
    // Either the second signal came while the first was honoured, or not (two SIGINTs sent
    // back to back may arrive as one; a stop in the set-up may be over at once): then the
    // first's message. Two different signals back to back nearly always find the former, and
    // at least one of the three tries must.
    if (text.find("grainshock: interrupted again: exiting at once") != std::string::npos)
      ++at_once;
    else
      EXPECT_NE(text.find("grainshock: interrupted"), std::string::npos) << text;
    expect_whole_files(out);
  }
  EXPECT_GE(at_once, 1);
}

}  // namespace
}  // namespace gs::test
