#pragma once
// Runs the realisations of an ensemble over ranks (analysis/ensemble_ranks.h: MPI processes, or
// this process alone) and worker threads. Rank 0 hands each rank a share of the indices; within a
// rank, workers pull the next index from a shared counter and run one engine at a time. Each
// finished realisation travels as the text of its folder (analysis/realisation.h) to the main
// thread of rank 0, which writes it (whole or not at all) and adds it into exact sums. Exact
// sums make the result independent of which rank or thread ran what, and reading a finished
// realisation back from its folder gives the same numbers as running it (docs/design.md: results do
// not depend on the split), so an ensemble killed at any moment resumes to the same bytes.
// Memory: one engine and one realisation's measures per thread.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "analysis/ensemble_ranks.h"
#include "analysis/ensemble_sums.h"
#include "analysis/realisation.h"

namespace gs {

// The most worker threads a process takes (--threads of ensemble, figures and resume). Each holds
// an engine of its own and results do not depend on the count, so threads beyond the cores only
// add memory; 1024 is above the hardware threads of the machines this runs on, and a larger
// number is a slip of the keyboard, not a plan.
inline constexpr int kMaxThreads = 1024;
// The machine's hardware threads, within [1, kMaxThreads]: the default of --threads.
int default_threads();
// UsageError naming --threads unless 1 <= threads <= kMaxThreads.
void check_threads(int threads);

struct RunnerOptions {
  int threads = 1;  // per rank
  // If not empty: each realisation is written to realisations_dir / realisation_folder(k) as it
  // finishes, and realisations found there already are read instead of run (resume).
  std::filesystem::path realisations_dir;
  // With realisations_dir: wall seconds between two writes of each running realisation's state
  // into realisations_dir / kInFlightFolder (analysis/realisation_in_flight.h), and one at a stop
  // request, from which a resumed ensemble goes on; 0: never written. Only rank 0's workers keep
  // them: the other ranks have no folder, and run a realisation they are handed from t = 0.
  double checkpoint_interval = 600;
  // A state in flight that could not be used or written, one line, from worker threads of rank 0
  // (must be thread-safe); empty: nothing is said (the job's MessageSink gives one).
  std::function<void(const std::string&)> on_warning;
  SnapshotHook on_snapshot;  // called from worker threads of rank 0 only; must be thread-safe
  // Called on rank 0's main thread after each realisation finished in this call, with
  // (finished, to run in this call).
  std::function<void(std::uint64_t, std::uint64_t)> on_progress;
  Ranks* ranks = nullptr;  // nullptr: this process alone
};

struct RunnerResult {
  EnsembleSums sums;
  bool interrupted = false;   // a stop was requested; sums hold the realisations that finished
  std::uint64_t resumed = 0;  // realisations read from realisations_dir instead of run
};

// Folder name of realisation k under realisations_dir; its state in flight is the file of that
// name in realisations_dir / kInFlightFolder, removed once the realisation is written.
std::string realisation_folder(std::uint64_t index);
inline constexpr const char* kInFlightFolder = "in_flight";

// The spec's realisations that realisations_dir holds finished.
std::vector<std::uint64_t> finished_realisations(const std::filesystem::path& realisations_dir,
                                                 const EnsembleSpec& spec);

// On rank 0. UsageError for threads outside check_threads', for a realisation folder that cannot be read, or when a
// realisation fails, naming the rank (with more than one) and the realisation; the realisations
// finished by then are written already. Ends the job for the other ranks (Ranks::finish).
RunnerResult run_ensemble(const EnsembleSpec& spec, const RunnerOptions& options);

// On every other rank: runs the share rank 0 hands out and sends the results; returns the exit
// code rank 0 gives at the end. Writes and prints nothing.
int serve_ensemble(Ranks& ranks);

}  // namespace gs
