#pragma once
// Runs the realisations of an ensemble on worker threads. Each worker pulls the next index from
// an atomic counter, runs one engine at a time and adds the result into its own exact sums;
// the workers' sums are merged at the end. Exact sums make the result independent of which
// worker ran what (DESIGN.md: results do not depend on the split). Memory: one engine and one
// realisation's measures per thread.
#include <cstdint>
#include <filesystem>
#include <functional>

#include "analysis/ensemble_sums.h"
#include "analysis/realisation.h"

namespace gs {

struct RunnerOptions {
  int threads = 1;
  // If not empty, each realisation is also written to per_realisation_dir / "NNNNNN" (for merge).
  std::filesystem::path per_realisation_dir;
  SnapshotHook on_snapshot;  // called from worker threads; must be thread-safe
  // Called (serialised) after each finished realisation with (finished, total).
  std::function<void(std::uint64_t, std::uint64_t)> on_progress;
};

struct RunnerResult {
  EnsembleSums sums;
  bool interrupted = false;  // a stop was requested; sums hold the realisations that finished
};

// Folder name of realisation k under per_realisation_dir.
std::string realisation_folder(std::uint64_t index);

// UserError if threads < 1 (or for an impossible spec, from the engine).
RunnerResult run_ensemble(const EnsembleSpec& spec, const RunnerOptions& options);

}  // namespace gs
