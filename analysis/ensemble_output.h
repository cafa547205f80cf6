#pragma once
// The files of an ensemble folder, written from the sums alone so that the one-shot ensemble and
// `grainshock merge` of its split parts write the same bytes:
//   ensemble.toml               the spec (physics, grid, snapshot times, bins), --config-readable
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

// The spec as held: first realisation = lowest index held, realisations = count.
EnsembleSpec held_spec(const EnsembleSums& sums);

std::string summary_json(const EnsembleSums& sums, const EnsembleFits& fits);

// Needs sums.count() >= 1.
void write_ensemble_outputs(const std::filesystem::path& dir, const EnsembleSums& sums,
                            const EnsembleFits& fits);

}  // namespace gs
