// The contract of `grainshock ensemble` and `grainshock merge`: results independent of the thread
// count, of the MPI ranks, of how the ensemble was split and of kills and resumes; the exponents
// on stdout; bad input refused in one line with nothing written.
#include <gtest/gtest.h>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <regex>
#include <thread>

#include "analysis/table.h"
#include "tests/apps/cli_test_util.h"

namespace gs {
namespace {

using test::grainshock;
using test::read_file;
using test::scratch_dir;
using test::spawn_grainshock;
namespace fs = std::filesystem;

// Small enough for a fraction of a second per realisation, long enough for a band to form.
// A box: these tests read the folders, not the medium (tests/sim/test_unbounded_engine.cpp).
const std::string kPhysics = "--medium box --particles 6000 --restitution 0.5 --t-max 1500 --quiet";
const std::vector<std::string> kFiles = {"ensemble.toml", "timeseries_mean.csv",
                                         "distributions_mean.csv", "snapshot_scalars_mean.csv",
                                         "summary.json"};

void expect_same_files(const fs::path& a, const fs::path& b) {
  for (const auto& f : kFiles) {
    ASSERT_TRUE(fs::exists(a / f)) << a / f;
    ASSERT_TRUE(fs::exists(b / f)) << b / f;
    EXPECT_EQ(read_file(a / f), read_file(b / f)) << f;
  }
}

TEST(CliEnsemble, ThreadCountDoesNotChangeTheBytes) {
  const auto one = scratch_dir("k1"), two = scratch_dir("k2"), other = scratch_dir("seed2");
  auto r =
      grainshock("ensemble " + kPhysics + " --realisations 4 --threads 1 --out " + one.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = grainshock("ensemble " + kPhysics + " --realisations 4 --threads 2 --out " + two.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  expect_same_files(one, two);
  // The comparison can fail: another master seed gives other numbers.
  r = grainshock("ensemble " + kPhysics + " --realisations 4 --threads 2 --seed 2 --out " +
                 other.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(read_file(one / "timeseries_mean.csv"), read_file(other / "timeseries_mean.csv"));
  EXPECT_NE(read_file(one / "distributions_mean.csv"), read_file(other / "distributions_mean.csv"));
}

TEST(CliEnsemble, MergeOfSplitJobsEqualsTheOneShotEnsemble) {
  const auto whole = scratch_dir("whole"), a = scratch_dir("a"), b = scratch_dir("b"),
             merged = scratch_dir("merged");
  ASSERT_EQ(
      grainshock("ensemble " + kPhysics + " --realisations 5 --threads 2 --out " + whole.string())
          .exit_code,
      0);
  auto r = grainshock("ensemble " + kPhysics +
                      " --realisations 2 --threads 1 --per-realisation --out " + a.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = grainshock("ensemble " + kPhysics +
                 " --realisation 2 --realisations 3 --threads 2 --per-realisation --out " +
                 b.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // Folders in either order.
  r = grainshock("merge --quiet " + b.string() + " " + a.string() + " --out " + merged.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  expect_same_files(whole, merged);
  // A part alone is not the whole.
  const auto part = scratch_dir("part");
  ASSERT_EQ(grainshock("merge --quiet " + a.string() + " --out " + part.string()).exit_code, 0);
  EXPECT_NE(read_file(whole / "timeseries_mean.csv"), read_file(part / "timeseries_mean.csv"));
}

// Two merges into one new folder started together: the first to lock the folder writes it, the
// other is refused, whether it finds the lock held or the first one's files already there.
TEST(CliEnsemble, TwoMergesIntoOneFolderDoNotBothSucceed) {
  const auto a = scratch_dir("a"), out = scratch_dir("out");
  ASSERT_EQ(
      grainshock("ensemble " + kPhysics + " --realisations 2 --per-realisation --out " + a.string())
          .exit_code,
      0);
  const std::string args = "merge --quiet " + a.string() + " --out " + out.string();
  for (int attempt = 0; attempt < 5; ++attempt) {
    fs::remove_all(out);
    const fs::path err[2] = {out.string() + ".err0", out.string() + ".err1"};
    const pid_t pids[2] = {spawn_grainshock(args, err[0]), spawn_grainshock(args, err[1])};
    int codes[2];
    for (int k = 0; k < 2; ++k) {
      int status = 0;
      ASSERT_EQ(waitpid(pids[k], &status, 0), pids[k]);
      ASSERT_TRUE(WIFEXITED(status));
      codes[k] = WEXITSTATUS(status);
    }
    EXPECT_EQ((codes[0] == 0) + (codes[1] == 0), 1) << "attempt " << attempt;
    const int loser = codes[0] == 0 ? 1 : 0;
    EXPECT_EQ(codes[loser], 1);
    const std::string message = read_file(err[loser]);
    EXPECT_TRUE(message.find("in use by another grainshock process") != std::string::npos ||
                message.find("another grainshock process wrote") != std::string::npos ||
                message.find("not empty") != std::string::npos)
        << message;
    EXPECT_TRUE(fs::exists(out / "summary.json"));
  }
}

TEST(CliEnsemble, DistributionsAreNormalisedAndSummaryHasTheFits) {
  const auto dir = scratch_dir("norm");
  auto r =
      grainshock("ensemble " + kPhysics + " --realisations 3 --threads 2 --out " + dir.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Table d = read_csv(dir / "distributions_mean.csv");
  const Table s = read_csv(dir / "snapshot_scalars_mean.csv");
  ASSERT_EQ(s.rows(), 3u);  // default snapshot times t-max/4, /2, 1
  for (std::size_t k = 0; k < s.rows(); ++k) {
    const double t = s.column("t")[k];
    double pr = 0, pv = 0, width_r = 0, width_v = 0;
    std::size_t bins = 0;
    for (std::size_t i = 0; i < d.rows(); ++i) {
      if (d.column("t")[i] != t) continue;
      ++bins;
      pr += d.column("P_R")[i];
      pv += d.column("P_v")[i];
      if (d.column("bin")[i] == 1) {  // uniform bins: centre spacing is the width
        width_r = d.column("R")[i] - d.column("R")[i - 1];
        width_v = d.column("v")[i] - d.column("v")[i - 1];
      }
    }
    ASSERT_GT(bins, 1u);
    // Each realisation's histogram integrates to its fraction inside the range; so does the mean.
    EXPECT_NEAR(pr * width_r, 1 - s.column("R_outside_fraction")[k], 1e-9) << "t = " << t;
    EXPECT_NEAR(pv * width_v, 1 - s.column("v_outside_fraction")[k], 1e-9) << "t = " << t;
  }
  const std::string summary = read_file(dir / "summary.json");
  for (const char* key : {"\"exponents\"", "\"N_t\"", "\"E_t\"", "\"R_t\"", "\"v_t\"", "\"ci_lo\"",
                          "\"t_c1\"", "\"collapse_quality_radius\"", "\"packing_typical\"",
                          "\"packing_upper\"", "\"anisotropy_last\""})
    EXPECT_NE(summary.find(key), std::string::npos) << key;
}

// One line on stderr, a non-zero exit, and the output folder as it was.
void expect_refused(const std::string& args, const fs::path& out, const std::string& before) {
  const auto r = grainshock(args);
  EXPECT_NE(r.exit_code, 0) << args;
  EXPECT_EQ(r.err_lines(), 1) << args << "\n" << r.err;
  if (before.empty())
    EXPECT_FALSE(fs::exists(out)) << args;
  else
    EXPECT_EQ(read_file(out / "summary.json"), before) << args;
}

TEST(CliEnsemble, BadInputIsRefusedInOneLineAndWritesNothing) {
  const auto out = scratch_dir("out");
  const std::string to = " --out " + out.string();
  expect_refused("ensemble " + kPhysics + " --realisations 0" + to, out, "");
  expect_refused("ensemble " + kPhysics + " --realisations -2" + to, out, "");
  expect_refused("ensemble " + kPhysics + " --threads 0" + to, out, "");
  expect_refused("ensemble " + kPhysics + " --window 2000,5000" + to, out, "");  // beyond t-max
  expect_refused("ensemble " + kPhysics + " --window 0.001,100" + to, out, "");  // before the grid
  expect_refused("ensemble " + kPhysics + " --window 800,400" + to, out, "");    // reversed

  // Merging folders of different physics.
  const auto a = scratch_dir("a"), b = scratch_dir("b"), c = scratch_dir("c");
  ASSERT_EQ(
      grainshock("ensemble " + kPhysics + " --realisations 2 --per-realisation --out " + a.string())
          .exit_code,
      0);
  ASSERT_EQ(
      grainshock("ensemble --medium box --particles 6000 --restitution 0.8 --t-max 1500 --quiet "
                 "--realisation 2 --realisations 2 --per-realisation --out " +
                 b.string())
          .exit_code,
      0);
  expect_refused("merge " + a.string() + " " + b.string() + to, out, "");
  // The same realisations twice, and a folder without per-realisation data.
  expect_refused("merge " + a.string() + " " + a.string() + to, out, "");
  ASSERT_EQ(grainshock("ensemble " + kPhysics + " --realisations 2 --out " + c.string()).exit_code,
            0);
  expect_refused("merge " + c.string() + to, out, "");

  // An existing output folder is left alone.
  const std::string before = read_file(a / "summary.json");
  expect_refused("ensemble " + kPhysics + " --realisations 1 --out " + a.string(), a, before);
  expect_refused("merge " + a.string() + " --out " + a.string(), a, before);

  // Merging into one of the inputs, even with --force and through another spelling, or inside it.
  expect_refused(
      "merge " + a.string() + " --force --out " + a.string() + "/../" + a.filename().string(), a,
      before);
  expect_refused("merge " + a.string() + " --force --out " + (a / "realisations").string(), a,
                 before);
  EXPECT_EQ(read_file(a / "realisations/000000/timeseries.csv").empty(), false);
  // The same bound on the bootstrap for both commands.
  expect_refused("ensemble " + kPhysics + " --resamples 0" + to, out, "");
  expect_refused("merge " + a.string() + " --resamples 0" + to, out, "");
  expect_refused("merge " + a.string() + " --resamples 9" + to, out, "");
}

// The last column of the stdout table's row for `quantity`.
double table_exponent(const std::string& out, const std::string& quantity) {
  std::smatch m;
  const std::regex row("\\n" + quantity + " +(-?[0-9.]+) ");
  if (!std::regex_search(out, m, row)) return NAN;
  return std::stod(m[1]);
}

TEST(CliEnsemble, ExponentsGoToStdoutEvenWhenQuiet) {
  const auto dir = scratch_dir("e"), merged = scratch_dir("m"), again = scratch_dir("again");
  auto r = grainshock("ensemble " + kPhysics +
                      " --realisations 3 --per-realisation --resamples 200 --out " + dir.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err, "");  // --quiet: no progress, no notes
  ASSERT_NE(r.out.find("quantity"), std::string::npos) << r.out;
  const std::string summary = read_file(dir / "summary.json");
  // Three realisations to t = 1500 give a plateau of a decade to R_t and C_t only (the rule in
  // analysis/effective_exponent.h); the others print nan and say why.
  for (const char* q : {"R_t", "C_t"}) {
    const double e = table_exponent(r.out, q);
    ASSERT_TRUE(std::isfinite(e)) << q << "\n" << r.out;
    // The table rounds summary.json's exponent to 4 decimals.
    std::smatch m;
    ASSERT_TRUE(std::regex_search(
        summary, m,
        std::regex("\"quantity\": \"" + std::string(q) + "\"[^}]*\"exponent\": (-?[0-9.e-]+)")));
    EXPECT_NEAR(e, std::stod(m[1]), 5e-5) << q;
  }
  // merge prints the same table; ensemble.toml holds the fit flags, so it is a --config that
  // reproduces the folder.
  const std::string table = r.out;
  r = grainshock("merge --quiet " + dir.string() + " --resamples 200 --out " + merged.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out, table);
  r = grainshock("ensemble --quiet --config " + (dir / "ensemble.toml").string() + " --out " +
                 again.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  expect_same_files(dir, again);
  EXPECT_TRUE(fs::is_directory(again / "realisations/000002"));
}

// Realisation folders are named by their index; beside them are temporaries (".NAME.tmp.PID")
// and in_flight/, the states of running ones.
std::size_t finished_count(const fs::path& rdir) {
  std::size_t n = 0;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(rdir, ec)) {
    const std::string name = e.path().filename().string();
    n += e.is_directory() && name.find_first_not_of("0123456789") == std::string::npos;
  }
  return n;
}

// Slower realisations than kPhysics (about 0.15 s each), so that a kill lands between them.
const std::string kSlow = "--medium box --particles 20000 --restitution 0.5 --t-max 20000 --quiet";

TEST(CliEnsemble, KilledEnsembleResumesToTheSameBytes) {
  const auto whole = scratch_dir("whole"), killed = scratch_dir("killed"),
             partial = scratch_dir("partial");
  const std::string job = "ensemble " + kSlow + " --realisations 8 --threads 1 --out ";
  auto r = grainshock(job + whole.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_FALSE(fs::exists(whole / "realisations"));  // removed once finished without the flag

  const pid_t pid = spawn_grainshock(job + killed.string());
  ASSERT_GT(pid, 0);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (finished_count(killed / "realisations") == 0 &&
         std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  ::kill(pid, SIGKILL);
  int status = 0;
  ::waitpid(pid, &status, 0);
  ASSERT_TRUE(WIFSIGNALED(status)) << "the ensemble finished before the kill: make it slower";
  const std::size_t held = finished_count(killed / "realisations");
  ASSERT_GE(held, 1u);
  ASSERT_LT(held, 8u);
  EXPECT_FALSE(fs::exists(killed / "summary.json"));
  // A writer killed mid-folder leaves a temporary; the resume removes it.
  fs::create_directories(killed / "realisations/.000007.tmp.1");

  // The killed folder is usable by merge: it holds what finished.
  r = grainshock("merge " + killed.string() + " --out " + partial.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("of 8 realisations finished"), std::string::npos) << r.err;
  EXPECT_NE(read_file(partial / "summary.json").find("\"realisations\": " + std::to_string(held)),
            std::string::npos);

  // Other settings into the killed folder are refused, and leave it as it was.
  r = grainshock("ensemble " + kSlow + " --realisations 9 --out " + killed.string());
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.err_lines(), 1) << r.err;
  EXPECT_EQ(finished_count(killed / "realisations"), held);

  // The same command again (another thread count is the same job) runs the rest.
  r = grainshock("ensemble " + kSlow + " --realisations 8 --threads 2 --out " + killed.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  expect_same_files(whole, killed);
  EXPECT_FALSE(fs::exists(killed / "realisations"));
  // Finished now: running it again is refused as for any folder with results.
  r = grainshock(job + killed.string());
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.err_lines(), 1) << r.err;
}

TEST(CliEnsemble, InterruptedEnsembleKeepsWhatFinishedAndResumes) {
  const auto whole = scratch_dir("whole"), stopped = scratch_dir("stopped");
  // Realisations of about 0.7 s, so that one is caught running.
  const std::string job =
      "ensemble --medium box --particles 50000 --restitution 0.5 --t-max 1e5 "
      "--quiet --realisations 6 --threads 1 --checkpoint-every 30 --out ";
  ASSERT_EQ(grainshock(job + whole.string()).exit_code, 0);
  const auto start = std::chrono::steady_clock::now();
  const pid_t pid = spawn_grainshock(job + stopped.string());
  ASSERT_GT(pid, 0);
  const auto deadline = start + std::chrono::seconds(60);
  while (finished_count(stopped / "realisations") == 0 &&
         std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  // Halfway through the next realisation, timed by the first on this machine at its load: past
  // its set-up (random sequential addition, 0.05 s), which a stop ends with no state to keep. A
  // fixed 300 ms landed between realisations once the engine ran one in 0.3 s.
  std::this_thread::sleep_for((std::chrono::steady_clock::now() - start) / 2);
  ::kill(pid, SIGINT);
  int status = 0;
  ::waitpid(pid, &status, 0);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 130);  // interrupted, with the files of what finished
  const std::size_t held = finished_count(stopped / "realisations");
  ASSERT_LT(held, 6u) << "the ensemble finished before the interrupt: make it slower";
  EXPECT_NE(read_file(stopped / "summary.json").find("\"realisations\": " + std::to_string(held)),
            std::string::npos);
  // The realisation running at the interrupt kept its state in flight, for the resume to go on
  // from; the interval between two is in ensemble.toml, so that the resume keeps it.
  EXPECT_TRUE(fs::is_regular_file(
      stopped / "realisations/in_flight" /
      (std::string(6 - std::to_string(held).size(), '0') + std::to_string(held))));
  EXPECT_NE(read_file(stopped / "ensemble.toml").find("\ncheckpoint-minutes = 0.5\n"),
            std::string::npos);
  // `grainshock resume` continues it (the same command again would too: the test above).
  const auto r = grainshock("resume --quiet --threads 1 " + stopped.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  expect_same_files(whole, stopped);
}

// Stopped before any realisation finished is a stop like any other, exit 130 with the folder to
// continue (it exited 1, as a failure).
TEST(CliEnsemble, InterruptedBeforeTheFirstRealisationExits130) {
  const auto dir = scratch_dir("early");
  const fs::path err = dir.string() + ".err";
  const pid_t pid = spawn_grainshock("ensemble --dim 3 --medium box --particles 20000 --t-max 1e7 "
                                     "--realisations 2 --threads 1 --out " + dir.string(),
                                     err.string());
  ASSERT_GT(pid, 0);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (!fs::exists(dir / "realisations") && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  ::kill(pid, SIGINT);
  int status = 0;
  ::waitpid(pid, &status, 0);
  ASSERT_TRUE(WIFEXITED(status));
  ASSERT_EQ(finished_count(dir / "realisations"), 0u) << "a realisation finished: make it slower";
  EXPECT_EQ(WEXITSTATUS(status), 130) << read_file(err);
  EXPECT_NE(read_file(err).find("interrupted before any realisation finished (continue with: "
                                "grainshock resume " + dir.string() + ")"),
            std::string::npos)
      << read_file(err);
}

// A realisation changed by hand is named itself: checked against the ensemble's own time grid,
// realisation 0 edited was blamed on realisation 1, the first compared with it.
TEST(CliEnsemble, AnEditedRealisationIsNamedItself) {
  const auto dir = scratch_dir("edited");
  const std::string job = "ensemble " + kPhysics + " --realisations 3 --per-realisation --out ";
  ASSERT_EQ(grainshock(job + dir.string()).exit_code, 0);
  fs::remove(dir / "summary.json");
  fs::remove_all(dir / "realisations/000002");
  const fs::path csv = dir / "realisations/000000/timeseries.csv";
  std::string text = read_file(csv);
  const std::size_t row2 = text.find('\n', text.find('\n') + 1) + 1;  // the header, row 1
  text.replace(row2, text.find(',', row2) - row2, "0.125");
  std::ofstream(csv, std::ios::binary) << text;
  const auto r = grainshock(job + dir.string());
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_EQ(r.err_lines(), 1) << r.err;
  EXPECT_NE(r.err.find("realisations/000000: row 2 has t = 0.125, the ensemble's time grid "),
            std::string::npos)
      << r.err;
}

// A folder killed before realisations 1 and 2 finished, with a file in the way of 2's folder (it
// cannot be written); `prefix` runs the command (mpirun for several ranks).
test::CommandResult resume_with_realisation_2_blocked(const fs::path& dir,
                                                      const std::string& prefix) {
  const std::string job = "ensemble " + kPhysics + " --realisations 4 --per-realisation --out ";
  EXPECT_EQ(grainshock(job + dir.string()).exit_code, 0);
  fs::remove(dir / "summary.json");
  fs::remove_all(dir / "realisations/000001");
  fs::remove_all(dir / "realisations/000002");
  std::ofstream(dir / "realisations/000002") << "in the way\n";
  return test::run_program(prefix + GRAINSHOCK_BINARY, job + dir.string());
}

// A realisation that cannot be kept is reported by its index (and rank, under MPI), the others
// are kept, and the exit code is that of a user error.
TEST(CliEnsemble, AFailedRealisationIsNamedAndTheOthersAreKept) {
  const auto dir = scratch_dir("failed");
  const auto r = resume_with_realisation_2_blocked(dir, "");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.err_lines(), 1) << r.err;
  EXPECT_NE(r.err.find("realisation 2: cannot write"), std::string::npos) << r.err;
  EXPECT_TRUE(fs::is_directory(dir / "realisations/000001"));  // ran and kept
  EXPECT_FALSE(fs::exists(dir / "summary.json"));
}

#ifdef GRAINSHOCK_MPIEXEC
// More ranks than cores (--oversubscribe), as root in CI containers, and without the shared-memory
// single copy that containers without ptrace rights refuse (Open MPI's vader CMA). In sanitizer
// builds the ranks skip leak checking: Open MPI 4.1's plugins leak at MPI_Finalize and are
// unloaded before LeakSanitizer looks, so no suppression can name them; the same ensemble code is
// leak-checked on the threaded path. (The variable means nothing to other builds.)
std::string mpirun(int ranks) {
  std::string cmd = "ASAN_OPTIONS=detect_leaks=0 OMPI_MCA_btl_vader_single_copy_mechanism=none " +
                    std::string(GRAINSHOCK_MPIEXEC) + " -n " + std::to_string(ranks) +
                    " --oversubscribe";
  if (::geteuid() == 0) cmd += " --allow-run-as-root";
  return cmd + " ";
}
#endif

TEST(CliEnsemble, MpiRanksGiveTheBytesOfThreads) {
#ifndef GRAINSHOCK_MPIEXEC
  GTEST_SKIP() << "built without MPI (GRAINSHOCK_MPI off or no MPI found by CMake)";
#else
  const auto threads = scratch_dir("threads"), ranks = scratch_dir("ranks"),
             idle = scratch_dir("idle"), two = scratch_dir("two");
  const std::string job = "ensemble " + kPhysics + " --realisations 5 ";
  auto r = grainshock(job + "--threads 2 --out " + threads.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = test::run_program(mpirun(2) + GRAINSHOCK_BINARY, job + "--threads 1 --out " + ranks.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  expect_same_files(threads, ranks);
  EXPECT_EQ(r.out, grainshock(job + "--threads 1 --out " + scratch_dir("t1").string()).out);

  // More ranks than realisations: allowed, and rank 0 says which ranks stay idle.
  r = grainshock("ensemble " + kPhysics + " --realisations 2 --threads 1 --out " + two.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = test::run_program(mpirun(3) + GRAINSHOCK_BINARY,
                        "ensemble " + kPhysics.substr(0, kPhysics.find(" --quiet")) +
                            " --realisations 2 --threads 1 --out " + idle.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("ranks 2-2 idle"), std::string::npos) << r.err;
  expect_same_files(two, idle);

  // A failure on rank 1 is reported by rank and realisation, once.
  const auto failed = scratch_dir("failed");
  r = resume_with_realisation_2_blocked(failed, mpirun(2));
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find("grainshock: error: rank 1, realisation 2: cannot write"), std::string::npos)
      << r.err;
  EXPECT_TRUE(fs::is_directory(failed / "realisations/000001"));
#endif
}

}  // namespace
}  // namespace gs
