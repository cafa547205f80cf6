#pragma once
// The files of an ensemble folder, written from the sums alone so that the one-shot ensemble and
// `grainshock merge` of its split parts write the same bytes:
//   ensemble.toml               the job (physics, grid, snapshot times, bins, fit); a --config
//   realisations/NNNNNN/        one realisation (analysis/realisation.h), written as it
//                               finishes; kept with --per-realisation (input of merge)
//   timeseries_mean.csv         t, t_paper, then mean c and standard error c_sem of every column
//   distributions_mean.csv      per snapshot time and bin: P(R,t), P(v,t), their scaled forms
//                               (x_R = R t^-alpha, f1 = t^alpha P; x_v = v t^(1-alpha),
//                               f2 = t^(alpha-1) P), radial profiles, packing distribution
//   snapshot_scalars_mean.csv   per snapshot time: band packing, inner-edge speeds (mean, sem)
//   summary.json                fits (analysis/ensemble_fits.h) and their definitions
// Nothing time- or machine-dependent goes into these (wall times go to timing.json).
#include <filesystem>
#include <string>

#include "analysis/ensemble_fits.h"
#include "analysis/ensemble_sums.h"

namespace gs {

inline constexpr double kCheckpointMinutes = 10;

// What an ensemble folder was asked to hold: ensemble.toml. Written before the first realisation
// runs, so that a killed ensemble can be resumed from its folder alone.
struct EnsembleJob {
  EnsembleSpec spec;
  FitOptions fit;
  bool keep_realisations = false;  // --per-realisation: keep realisations/ once finished
  // --checkpoint-minutes: wall time between two writes of a running realisation's state
  // (RunnerOptions::checkpoint_interval); how the job runs, not what it holds.
  double checkpoint_minutes = kCheckpointMinutes;
};

// UserError naming --resamples or --window if the fit cannot be made on this spec's data.
void check_fit_options(const EnsembleSpec& spec, const FitOptions& fit);

// spec_toml() plus resamples, window, per-realisation and checkpoint-minutes (when not the
// default): every key a flag of `ensemble`, so the file is its --config.
std::string job_toml(const EnsembleJob& job);
// UserError naming the file.
EnsembleJob read_job(const std::filesystem::path& file);

// The spec as held: first realisation = lowest index held, realisations = count.
EnsembleSpec held_spec(const EnsembleSums& sums);

std::string summary_json(const EnsembleSums& sums, const EnsembleFits& fits);

// The exponents as a table of text, one row per quantity (what `ensemble` and `merge` print on
// stdout): quantity, exponent, 95% interval, theory, implied alpha and its uncertainty, note.
std::string exponent_table(const EnsembleSums& sums, const EnsembleFits& fits);

// The result files (not ensemble.toml). Needs sums.count() >= 1.
void write_ensemble_outputs(const std::filesystem::path& dir, const EnsembleSums& sums,
                            const EnsembleFits& fits);

}  // namespace gs
