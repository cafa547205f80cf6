#pragma once
// The job of `grainshock ensemble` (and of `resume` on an ensemble folder): M realisations over
// ranks (mpirun) and threads into a folder, averaged with errors and fitted. Each realisation is
// written into OUT/realisations/ as it finishes, so the same job again after a kill runs only the
// missing ones, to the same bytes.
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

#include "analysis/ensemble_fits.h"
#include "analysis/ensemble_output.h"
#include "analysis/ensemble_runner.h"
#include "analysis/ensemble_sums.h"
#include "jobs/progress.h"
#include "sim/config.h"
#include "sim/messages.h"

namespace gs::jobs {

struct EnsembleOptions {
  PhysicsConfig physics;
  long long realisations = 8;
  int threads = default_threads();
  std::string out = "grainshock-ensemble";
  bool force = false, quiet = false, per_realisation = false;
  bool page = true;  // DIR/index.html, the page of `grainshock view`
  ProgressFactory progress;  // the line of the run; none by default
  MessageSink messages;      // notes and warnings (a state in flight skipped); none by default
  int per_decade = 20, bins = 60, resamples = 1000;
  // Wall minutes between two writes of each running realisation's state into OUT/realisations/
  // (and one at Ctrl-C), from which a resumed ensemble goes on; 0: never.
  double checkpoint_minutes = kCheckpointMinutes;
  std::vector<double> snapshot_times, window;
};

// --checkpoint-every (or --checkpoint-minutes) of `ensemble` and `figures` in minutes, checked
// (UsageError naming the flag).
double checked_checkpoint_minutes(double minutes);

// The fit of --resamples and --window, checked against the spec (UserError naming the flag).
FitOptions fit_options(int resamples, const std::vector<double>& window, const EnsembleSpec& spec);

struct EnsembleResult {
  bool interrupted = false;    // by SIGINT/SIGTERM: the folder resumes from what finished
  std::string exponent_table;  // rank 0: the fitted exponents, as the command prints them
  int served = -1;             // ranks other than 0: the exit code rank 0 gave them
};

// Checks every option before the folder is touched (UserError naming it), then runs what the
// folder still lacks: all of it for a new folder, the missing realisations of an unfinished one
// with the same settings (UserError for one of other settings, unless --force; the checkpoint
// interval may differ, and the new one is kept).
EnsembleResult run_ensemble_job(const EnsembleOptions& o);

// Whether `dir` holds an ensemble that can be resumed (ensemble.toml, with the results not
// written or realisations missing), and resuming it with the settings of its ensemble.toml
// (UserError if it holds none). Under mpirun every rank calls it; ranks other than 0 serve.
bool holds_unfinished_ensemble(const std::filesystem::path& dir);
EnsembleResult resume_ensemble(const std::filesystem::path& dir, int threads, bool quiet,
                               const ProgressFactory& progress, const MessageSink& messages = {});

// timing.json: the only file that differs between runs.
struct EnsembleTiming {
  double wall_seconds = 0;
  int threads = 1, ranks = 1;
  std::uint64_t realisations = 0;  // run in this call (a resumed ensemble read the others)
};

// Fits and writes the ensemble files with ensemble.toml = job_toml(job), plus timing.json.
EnsembleFits write_ensemble_folder(const std::filesystem::path& dir, const EnsembleSums& sums,
                                   const EnsembleJob& job, const EnsembleTiming& timing);
// The same for an ensemble made of what the sums hold (merge, figures), of which
// `realisations_run` were run in this call (merge runs none).
EnsembleFits write_ensemble_folder(const std::filesystem::path& dir, const EnsembleSums& sums,
                                   const FitOptions& fit, double wall_seconds, int threads,
                                   std::uint64_t realisations_run);

}  // namespace gs::jobs
