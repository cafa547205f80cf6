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

#include "jobs/figures_plan.h"
#include "jobs/progress.h"

namespace gs::jobs {

struct FiguresOptions {
  FiguresMode mode = FiguresMode::Quick;
  bool long_3d = false;   // add the plan's Long3D cases
  bool limit = false;     // add the plan's Limit cases (r = 0.9, 0.95, unbounded medium)
  int limit_dim = 0;      // of that dimension only (2 or 3); 0: both
  bool estimate = false;  // only estimate the wall time, from `sample` realisations per case
  int sample = 2;
  std::string out = "grainshock-figures";
  bool force = false, quiet = false;
  int threads = std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
  std::uint64_t seed = 1;
  std::vector<std::string> formats{"png"};  // of the figures (the .gp scripts write any)
  ProgressFactory progress;                 // the line of the ensembles; none by default
};

struct FiguresResult {
  std::filesystem::path dir;          // the output folder
  double wall = 0;                    // seconds, ensembles and figures (or the estimate)
  std::vector<std::string> problems;  // figures that could not be drawn, for a warning each
};

// Checks the options (UserError naming the flag), prepares the folder and runs the job.
// UserError on SIGINT/SIGTERM, naming the folder that holds the ensembles finished so far.
FiguresResult run_figures_job(const FiguresOptions& o);

}  // namespace gs::jobs
