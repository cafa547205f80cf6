#pragma once
// `grainshock figures` as a job: every ensemble of the mode's plan, then the paper's figures and
// the report of every measured number beside the paper's (Jabeen, Rajesh, Ray, EPL 2010); or,
// with `estimate`, only the time that would take.
#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

#include "analysis/ensemble_output.h"
#include "analysis/ensemble_runner.h"
#include "jobs/figures_plan.h"
#include "jobs/progress.h"
#include "sim/messages.h"

namespace gs::jobs {

struct FiguresOptions {
  FiguresMode mode = FiguresMode::Quick;
  bool long_3d = false;   // add the plan's Long3D cases
  bool limit = false;     // add the plan's Limit cases (r = 0.9, 0.95, unbounded medium)
  int limit_dim = 0;      // of that dimension only (2 or 3); 0: both
  bool snowplow = false;  // add the plan's Snowplow cases
  bool estimate = false;  // only estimate the wall time, from `sample` realisations per case
  int sample = 2;
  std::string out = "grainshock-figures";
  bool force = false, quiet = false;
  bool page = true;  // report.html beside report.md, the page of `grainshock view`
  int threads = default_threads();
  std::uint64_t seed = 1;
  // Wall minutes between two writes of each running realisation's state beside the case's
  // finished realisations (and one at Ctrl-C), from which `resume` goes on; 0: never.
  double checkpoint_minutes = kCheckpointMinutes;
  std::vector<std::string> formats{"png"};  // of the figures (the .gp scripts write any)
  ProgressFactory progress;                 // the line of the ensembles; none by default
  MessageSink messages;                     // notes and warnings; none by default
  // The command's settings as TOML, written to figures.toml (not by --estimate) so that the
  // job can be resumed after a kill; the command line rereads it (`grainshock resume`).
  std::string settings;
  // Go on with the unfinished job in `out`: the realisations it finished are read, not run.
  bool resume = false;
};

struct FiguresResult {
  std::filesystem::path dir;          // the output folder
  double wall = 0;                    // seconds, ensembles and figures (or the estimate)
  std::vector<std::string> problems;  // figures that could not be drawn, for a warning each
  bool interrupted = false;           // SIGINT/SIGTERM: resume the folder to finish it
};

// Checks the options (UserError naming the flag), prepares the folder and runs the job. Each
// case keeps its finished realisations in DIR/ensembles/NAME/realisations until the report is
// written, so that a job stopped (interrupted) or killed goes on from them with `resume`: the
// same files as a job never stopped (the ensembles' exact sums do not depend on which process
// ran a realisation), the --limit runs of days included. Refused: a new job into a folder that
// holds an unfinished one (unless `force`), a resume of a folder that does not, and a resume
// whose cases this build plans otherwise than the build that started it.
FiguresResult run_figures_job(const FiguresOptions& o);

// Whether `dir` holds a figures job that has not written its report.
bool is_unfinished_figures_folder(const std::filesystem::path& dir);

}  // namespace gs::jobs
