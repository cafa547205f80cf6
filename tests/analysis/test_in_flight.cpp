// A realisation stopped or killed mid-way goes on from its state in flight
// (analysis/realisation_in_flight.h) to the very files of an ensemble never stopped.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "analysis/ensemble_fits.h"
#include "analysis/ensemble_output.h"
#include "analysis/ensemble_runner.h"
#include "analysis/realisation_in_flight.h"
#include "sim/recorder.h"
#include "sim/stop.h"

namespace gs {
namespace {

namespace fs = std::filesystem;

class InFlight : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = fs::temp_directory_path() / ("gs_in_flight_" + std::to_string(::getpid()));
    fs::remove_all(root_);
    fs::create_directories(root_);
  }
  void TearDown() override {
    clear_stop();
    fs::remove_all(root_);
  }
  fs::path root_;
};

// Two realisations with the default snapshot times t_max / 4, t_max / 2, t_max.
EnsembleSpec small_spec(int dim, Medium medium) {
  EnsembleSpec spec;
  spec.physics.dim = dim;
  spec.physics.medium = medium;
  spec.physics.particles = dim == 2 ? 2000 : 3000;
  spec.physics.restitution = 0.5;
  spec.physics.t_max = dim == 2 ? 200 : 60;
  spec.physics.seed = 7;
  spec.realisations = 2;
  spec.per_decade = 10;
  spec.bins = 20;
  return checked(spec);
}

constexpr std::uint64_t kStopped = 1;  // the realisation stopped or killed in flight

// Every file under `dir` (realisations included) by its path relative to `dir`.
std::map<std::string, std::string> files_under(const fs::path& dir) {
  std::map<std::string, std::string> out;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.is_regular_file()) {
      std::ifstream in(e.path(), std::ios::binary);
      std::ostringstream text;
      text << in.rdbuf();
      out[fs::relative(e.path(), dir).string()] = text.str();
    }
  return out;
}

// The ensemble's result files beside its realisations, as `ensemble --per-realisation` leaves.
void write_results(const fs::path& dir, const RunnerResult& r) {
  FitOptions fit;
  fit.resamples = 20;
  write_ensemble_outputs(dir, r.sums, fit_ensemble(r.sums, fit));
}

struct Outcome {
  std::optional<RunnerResult> result;
  std::vector<double> snapshot_times_seen;  // of realisation kStopped
  std::vector<std::string> warnings;
};

// Runs (or resumes) the ensemble into dir/realisations, keeping states in flight at every slice
// unless `interval` says otherwise; `at_snapshot` is called at each snapshot of kStopped with
// how many it has seen before in this call.
Outcome run(const EnsembleSpec& spec, const fs::path& dir, double interval = 1e-9,
            const std::function<void(std::size_t)>& at_snapshot = {}) {
  Outcome out;
  RunnerOptions o;
  o.realisations_dir = dir / "realisations";
  o.checkpoint_interval = interval;
  o.on_warning = [&](const std::string& w) { out.warnings.push_back(w); };
  o.on_snapshot = [&](std::uint64_t index, const Snapshot& s) {
    if (index != kStopped) return;
    if (at_snapshot) at_snapshot(out.snapshot_times_seen.size());
    out.snapshot_times_seen.push_back(s.info.time);
  };
  out.result = run_ensemble(spec, o);
  return out;
}

fs::path state_of(const fs::path& dir) {
  return dir / "realisations" / kInFlightFolder / realisation_folder(kStopped);
}

// The ensemble never stopped (no state in flight ever written): its files.
std::map<std::string, std::string> reference(const EnsembleSpec& spec, const fs::path& dir) {
  const Outcome r = run(spec, dir, 0);
  EXPECT_FALSE(r.result->interrupted);
  EXPECT_EQ(r.snapshot_times_seen.size(), 3u);
  write_results(dir, *r.result);
  EXPECT_TRUE(fs::is_empty(dir / "realisations" / kInFlightFolder));
  return files_under(dir);
}

// Stopped (Ctrl-C) after kStopped's second snapshot, the state is written as it stops; then
// killed (a state written on the way put back after the realisation finished), which tests the
// periodic writes. Both resume from the state, not from t = 0, to the reference's files.
void stop_and_kill(const EnsembleSpec& spec, const fs::path& root) {
  const auto ref = reference(spec, root / "reference");

  const fs::path stopped = root / "stopped";
  Outcome first = run(spec, stopped, 1e-9, [&](std::size_t k) {
    if (k == 1) request_stop();
  });
  EXPECT_TRUE(first.result->interrupted);
  EXPECT_EQ(first.result->sums.count(), 1u);
  ASSERT_TRUE(fs::is_regular_file(state_of(stopped)));
  clear_stop();
  Outcome second = run(spec, stopped);
  EXPECT_FALSE(second.result->interrupted);
  EXPECT_TRUE(second.warnings.empty()) << second.warnings.front();
  // Only the snapshot after the stop: it went on from the state.
  EXPECT_EQ(second.snapshot_times_seen.size(), 1u);
  EXPECT_FALSE(fs::exists(state_of(stopped)));
  write_results(stopped, *second.result);
  EXPECT_EQ(files_under(stopped), ref);

  // A kill: the state last written before the last snapshot, kept aside then. Writes are spaced
  // by 50 times their duration, so how far it got depends on the machine: it is read here.
  const fs::path killed = root / "killed";
  const fs::path aside = root / "aside";
  Outcome whole = run(spec, killed, 1e-9, [&](std::size_t k) {
    if (k == 2) fs::copy_file(state_of(killed), aside);
  });
  EXPECT_FALSE(whole.result->interrupted);
  EXPECT_FALSE(fs::exists(state_of(killed)));  // removed once the realisation was written
  Recorder recorder(spec.physics);
  Realisation partial;
  std::size_t next = 0;
  ASSERT_TRUE(load_in_flight(aside, spec, kStopped, recorder, partial, next));
  fs::remove_all(killed / "realisations" / realisation_folder(kStopped));
  fs::copy_file(aside, state_of(killed));
  Outcome after = run(spec, killed, 0);
  EXPECT_EQ(after.result->resumed, 1u);
  EXPECT_EQ(after.snapshot_times_seen.size(), 3 - partial.snapshots.size());
  write_results(killed, *after.result);
  EXPECT_EQ(files_under(killed), ref);
}

TEST_F(InFlight, StoppedAndKilledBoxRealisationResumesToTheSameFiles) {
  stop_and_kill(small_spec(2, Medium::Box), root_);
}

TEST_F(InFlight, StoppedAndKilledUnboundedRealisationResumesToTheSameFiles) {
  stop_and_kill(small_spec(2, Medium::Unbounded), root_);
}

TEST_F(InFlight, StoppedAndKilledUnbounded3dRealisationResumesToTheSameFiles) {
  stop_and_kill(small_spec(3, Medium::Unbounded), root_);
}

// A state that is not whole is not used: one warning naming it, and the realisation runs from
// t = 0 to the same files.
TEST_F(InFlight, TruncatedOrCorruptStateRunsTheRealisationAgain) {
  const EnsembleSpec spec = small_spec(2, Medium::Box);
  const auto ref = reference(spec, root_ / "reference");
  for (const bool truncate : {true, false}) {
    const fs::path dir = root_ / (truncate ? "truncated" : "corrupt");
    run(spec, dir, 1e-9, [&](std::size_t k) {
      if (k == 1) request_stop();
    });
    clear_stop();
    const fs::path state = state_of(dir);
    ASSERT_TRUE(fs::is_regular_file(state));
    if (truncate) {
      fs::resize_file(state, fs::file_size(state) / 2);
    } else {
      std::fstream f(state, std::ios::in | std::ios::out | std::ios::binary);
      const auto at = std::streamoff(fs::file_size(state) - 100);
      f.seekg(at);
      const char byte = static_cast<char>(f.get());
      f.seekp(at);
      f.put(static_cast<char>(~byte));
    }
    const Outcome again = run(spec, dir);
    ASSERT_EQ(again.warnings.size(), 1u);
    const std::string& w = again.warnings.front();
    EXPECT_NE(w.find(state.string()), std::string::npos) << w;
    EXPECT_NE(w.find(truncate ? "truncated" : "checksum"), std::string::npos) << w;
    EXPECT_NE(w.find("runs again from t = 0"), std::string::npos) << w;
    EXPECT_EQ(w.find('\n'), std::string::npos) << w;
    EXPECT_EQ(again.snapshot_times_seen.size(), 3u);  // from t = 0
    write_results(dir, *again.result);
    EXPECT_EQ(files_under(dir), ref);
  }
}

}  // namespace
// A realisation folder written with other columns is refused in one line naming it, whether it
// predates the format file or states another format; its own format reads back.
TEST_F(InFlight, RealisationOfAnotherFormatIsRefusedInOneLine) {
  const EnsembleSpec spec = small_spec(2, Medium::Box);
  Realisation r;
  ASSERT_TRUE(simulate_realisation(spec, 0, r));
  const fs::path dir = root_ / "000000";
  write_realisation(dir, realisation_files(r));
  const Realisation back = read_realisation(dir, 0);
  ASSERT_EQ(back.snapshots.size(), r.snapshots.size());
  EXPECT_TRUE(std::isfinite(back.snapshots.back().measures.voronoi_median));
  auto refusal = [&] {
    try {
      read_realisation(dir, 0);
    } catch (const UserError& e) {
      return std::string(e.what());
    }
    return std::string("read");
  };
  {
    std::ofstream(dir / "format") << "grainshock realisation 1\n";
    const std::string why = refusal();
    EXPECT_NE(why.find("000000: realisation of another format ('grainshock realisation 1'"),
              std::string::npos)
        << why;
    EXPECT_EQ(why.find('\n'), std::string::npos);
  }
  fs::remove(dir / "format");
  const std::string why = refusal();
  EXPECT_NE(why.find("000000: realisation of an older grainshock (no format file"),
            std::string::npos)
      << why;
  EXPECT_EQ(why.find('\n'), std::string::npos);
}

}  // namespace gs
