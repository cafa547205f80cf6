#pragma once
// What `grainshock ensemble`, `grainshock merge` and `grainshock resume` share: the fit flags and
// the ending of an ensemble job on the command line.
#include <CLI/CLI.hpp>
#include <filesystem>
#include <vector>

#include "analysis/ensemble_fits.h"
#include "analysis/ensemble_output.h"
#include "analysis/ensemble_sums.h"
#include "jobs/ensemble_job.h"

namespace gs::app {

// --resamples and --window T1,T2 (checked later against the spec with fit_options()).
void add_fit_options(CLI::App& sub, int& resamples, std::vector<double>& window);

// For `grainshock resume DIR` on an ensemble folder: resumes it (jobs/ensemble_job.h), prints its
// exponents and returns the exit code.
int resume_ensemble_command(const std::filesystem::path& dir, int threads, bool quiet);

// The exit code of an ensemble job, after printing its exponents on stdout (rank 0).
int finish_ensemble_command(const jobs::EnsembleResult& r);

}  // namespace gs::app
