// `grainshock resume DIR`: continues a run folder from its last checkpoint (jobs/run_job.h), a
// movie folder from its (jobs/movie.h), or an unfinished ensemble or figures folder from its
// finished realisations (jobs/ensemble_job.h, jobs/figures_job.h).
#include <CLI/CLI.hpp>
#include <algorithm>
#include <filesystem>
#include <memory>
#include <thread>

#include "apps/commands.h"
#include "apps/ensemble_cli.h"
#include "apps/exit_code.h"
#include "apps/progress.h"
#include "apps/run_flags.h"
#include "jobs/figures_job.h"

namespace gs::app {

using namespace jobs;

void add_resume_command(CLI::App& app) {
  struct Options {
    std::string dir;
    bool quiet = false;
    double checkpoint_every = RunOptions{}.checkpoint_every;
    int threads = default_threads();
  };
  auto opt = std::make_shared<Options>();
  auto* sub = app.add_subcommand(
      "resume",
      "Continue a run or movie folder from its last checkpoint, or an unfinished ensemble or "
      "figures folder, after Ctrl-C or a kill");
  sub->add_option("DIR", opt->dir,
                  "The run, movie, ensemble or figures folder (as given to --out)")
      ->required();
  sub->add_flag("--quiet", opt->quiet, "Nothing on stderr but errors");
  add_checkpoint_option(*sub, opt->checkpoint_every);
  sub->add_option("--threads", opt->threads, "Ensemble and figures folders: worker threads, 1 to 1024")
      ->capture_default_str();
  sub->footer(
      "The run goes on from its checkpoint with the settings of DIR/run.toml and ends with the "
      "same timeseries.csv, snapshots, pictures, movie and summary.json, byte for byte, as a "
      "run that was never stopped; a run stopped in its set-up, before its first checkpoint, "
      "starts again from t = 0. Refused, with nothing in DIR touched: a finished run, a run.toml that is not the checkpoint's, a checkpoint that "
      "is truncated, corrupt or from another version or build. An ensemble folder (with "
      "ensemble.toml) runs only its missing realisations, to the same files as an ensemble "
      "never stopped. A movie folder (with movie.toml) goes on from its checkpoint and ends "
      "with the frames of a movie never stopped (its parts joined without encoding again). An "
      "unfinished figures folder (with figures.toml) runs only the realisations its "
      "cases have not finished, then the figures and report of a job never stopped.");
  sub->callback([opt] {
    check_threads(opt->threads);  // a run folder takes no threads, but a wrong number is wrong
    const std::filesystem::path dir(opt->dir);
    if (is_movie_folder(dir)) {
      const int rc = resume_movie(dir, opt->quiet, opt->checkpoint_every);
      if (rc != 0) throw Exit{rc};
      return;
    }
    if (std::filesystem::exists(dir / "figures.toml")) {
      const int rc = resume_figures(dir, opt->threads, opt->quiet);
      if (rc != 0) throw Exit{rc};
      return;
    }
    if (std::filesystem::exists(dir / "ensemble.toml")) {
      const int rc = resume_ensemble_command(dir, opt->threads, opt->quiet);
      if (rc != 0) throw Exit{rc};
      return;
    }
    RunOptions o = read_run_file(dir / "run.toml");
    o.out = opt->dir;
    o.quiet = opt->quiet;
    o.checkpoint_every = opt->checkpoint_every;
    o.progress = terminal_progress(o.quiet);
    o.messages = terminal_messages();
    if (run_job(o, true).stopped) throw Exit{kExitInterrupted};
  });
}

}  // namespace gs::app
