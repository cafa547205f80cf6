#pragma once
// What `grainshock ensemble`, `grainshock merge` and `grainshock resume` share: the fit flags and
// writing an ensemble folder with its timing record.
#include <CLI/CLI.hpp>
#include <filesystem>
#include <vector>

#include "analysis/ensemble_fits.h"
#include "analysis/ensemble_output.h"
#include "analysis/ensemble_sums.h"

namespace gs::app {

// --resamples and --window T1,T2 (checked later against the spec with fit_options()).
void add_fit_options(CLI::App& sub, int& resamples, std::vector<double>& window);
// The fit of the flags' values, checked against the data (UserError naming the flag).
FitOptions fit_options(int resamples, const std::vector<double>& window, const EnsembleSpec& spec);

// timing.json: the only file that differs between runs.
struct RunTiming {
  double wall_seconds = 0;
  int threads = 1, ranks = 1;
  std::uint64_t realisations = 0;  // run in this call (a resumed ensemble read the others)
};

// Fits and writes the ensemble files with ensemble.toml = job_toml(job), plus timing.json.
EnsembleFits write_ensemble_folder(const std::filesystem::path& dir, const EnsembleSums& sums,
                                   const EnsembleJob& job, const RunTiming& timing);
// The same for an ensemble made of what the sums hold (merge, figures).
EnsembleFits write_ensemble_folder(const std::filesystem::path& dir, const EnsembleSums& sums,
                                   const FitOptions& fit, double wall_seconds, int threads);

// For `grainshock resume DIR`: whether DIR holds an ensemble that can be resumed (ensemble.toml,
// with the results not written or realisations missing), and resuming it with the settings of
// its ensemble.toml. resume_ensemble returns the exit code; UserError if DIR holds no unfinished
// ensemble. Under mpirun every rank calls it; ranks other than 0 serve rank 0.
bool holds_unfinished_ensemble(const std::filesystem::path& dir);
int resume_ensemble(const std::filesystem::path& dir, int threads, bool quiet);

}  // namespace gs::app
