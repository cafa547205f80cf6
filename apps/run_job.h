#pragma once
// The job of `grainshock run` and `grainshock resume`: a RunLoop (sim/run_loop.h) into a run
// folder, then the pictures, the elastic comparison and the movie it asks for. Its run.toml
// holds every setting that shapes the results, so `run --config DIR/run.toml --out NEW` writes
// the same bytes, and `resume DIR` reads it back.
#include <CLI/CLI.hpp>
#include <filesystem>
#include <string>

#include "sim/run_loop.h"

namespace gs::app {

struct RunOptions {
  RunPlan plan;
  bool png = false;              // a PNG of every snapshot, and the Fig. 1(a) overlay
  bool compare_elastic = false;  // the Fig. 1(b) frame: the same gas with r = 1
  bool movie = false;            // movie.mp4 of the front, as `grainshock movie` makes it
  bool movie_inset = false;      // with the profile inset (the Fig. 1 job's movie has it)
  int width = 1920, height = 1080;
  // A file in the run folder (name.gsd or name.xyz) holding every snapshot time as one
  // trajectory; empty: none.
  std::string trajectory;
  // Neither of these shapes the results.
  std::string out = "grainshock-run";
  bool force = false, quiet = false;
  double checkpoint_every = 300;
};

// The flags of `run` that shape the results (run.toml holds them all), --config included.
void add_run_flags(CLI::App& sub, RunOptions& o);

// The rule for the Fig. 1 job, after parsing: unless one of the output flags (--t-max,
// --snapshot-times, --png, --compare-elastic, --movie) was given, on the command line or in
// --config, the run writes the Fig. 1 set for the physics given: t-max = paper time 50000,
// snapshots and pictures at paper times 5000, 10000, 20000 and 50000, their overlay, the
// elastic comparison and the movie.
void apply_fig1_rule(const CLI::App& sub, RunOptions& o);

// run.toml: the physics and the output keys, in flag names.
std::string run_toml(const RunOptions& o);

// Reads a run folder's run.toml as `run --config` would. Throws UserError naming the file.
RunOptions read_run_file(const std::filesystem::path& file);

// Runs the job into o.out (a new folder; with `resume`, the existing run folder continues from
// its checkpoint). Returns the exit code: 0, or kExitInterrupted (apps/exit_code.h) if stopped.
int run_job(const RunOptions& o, bool resume);

}  // namespace gs::app
