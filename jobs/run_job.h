#pragma once
// The job of `grainshock run` and `grainshock resume`: a RunLoop (jobs/run_loop.h) into a run
// folder, then the pictures, the elastic comparison and the movie it asks for. Its run.toml
// holds every setting that shapes the results, so `run --config DIR/run.toml --out NEW` writes
// the same bytes, and `resume DIR` reads it back.
#include <filesystem>
#include <string>

#include "jobs/progress.h"
#include "jobs/run_loop.h"
#include "sim/messages.h"

namespace gs::jobs {

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
  bool page = true;  // DIR/index.html, the page of `grainshock view`
  double checkpoint_every = 300;
  ProgressFactory progress;  // the line of each pass; none by default
  MessageSink messages;      // notes (what the run is doing, where its results are); none
};

// The paper's Fig. 1 set for the physics given: t-max = paper time 50000, snapshots and
// pictures at paper times 5000, 10000, 20000 and 50000, their overlay, the elastic comparison
// and the movie.
void use_fig1_job(RunOptions& o);

// run.toml: the physics and the output keys, in flag names.
std::string run_toml(const RunOptions& o);
// What a run's checkpoints know it by (RunLoop's spec): run.toml with the box left unstated, as
// to_toml() leaves it and as every checkpoint held before kicks defaulted to the unbounded
// medium, so that those resume with no special case.
std::string run_spec(const RunOptions& o);

struct RunResult {
  bool stopped = false;  // by SIGINT/SIGTERM (sim/stop.h); a resume goes on from the checkpoint
};

// Runs the job into o.out (a new folder; with `resume`, the existing run folder continues from
// its checkpoint).
RunResult run_job(const RunOptions& o, bool resume);

}  // namespace gs::jobs
