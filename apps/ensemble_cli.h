#pragma once
// What `grainshock ensemble` and `grainshock merge` share: the --window flag and writing an
// ensemble folder with its timing record.
#include <CLI/CLI.hpp>
#include <filesystem>
#include <optional>
#include <vector>

#include "analysis/ensemble_fits.h"
#include "analysis/ensemble_sums.h"

namespace gs::app {

// --window T1,T2 into `values` (checked later against the spec with window_of()).
void add_window_option(CLI::App& sub, std::vector<double>& values);
// The window of the flag's values, checked against the data (UserError naming --window).
std::optional<Window> window_of(const std::vector<double>& values, const EnsembleSpec& spec);

// Fits and writes the ensemble files, plus timing.json (the only file that differs between runs).
EnsembleFits write_ensemble_folder(const std::filesystem::path& dir, const EnsembleSums& sums,
                                   const FitOptions& fit, double wall_seconds, int threads);

}  // namespace gs::app
