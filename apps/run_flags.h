#pragma once
// The flags of `grainshock run` (and of run.toml, which `resume` reads back) into RunOptions.
#include <CLI/CLI.hpp>
#include <filesystem>

#include "jobs/run_job.h"

namespace gs::app {

using jobs::RunOptions;

// The flags of `run` that shape the results (run.toml holds them all), --config included.
void add_run_flags(CLI::App& sub, RunOptions& o);

// The rule for the Fig. 1 job, after parsing: unless one of the output flags (--t-max,
// --snapshot-times, --png, --compare-elastic, --movie) was given, on the command line or in
// --config, the run is the Fig. 1 job for the physics given (jobs::use_fig1_job).
bool apply_fig1_rule(const CLI::App& sub, RunOptions& o);

// Reads a run folder's run.toml as `run --config` would. Throws UserError naming the file.
RunOptions read_run_file(const std::filesystem::path& file);

}  // namespace gs::app
