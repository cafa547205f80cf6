// `grainshock run`: one realisation into a run folder (jobs/run_job.h).
#include <CLI/CLI.hpp>
#include <memory>

#include "apps/cli.h"
#include "apps/commands.h"
#include "apps/exit_code.h"
#include "apps/progress.h"
#include "apps/run_flags.h"

namespace gs::app {

using namespace jobs;

void add_checkpoint_option(CLI::App& sub, double& every) {
  sub.add_option("--checkpoint-every", every,
                 "Wall seconds between checkpoints (0: only at the start and on Ctrl-C); "
                 "`grainshock resume DIR` continues from the last")
      ->check(non_negative())
      ->capture_default_str();
}

void add_run_command(CLI::App& app) {
  auto opt = std::make_shared<RunOptions>();
  auto* sub = app.add_subcommand("run", "Simulate one realisation and write a run folder");
  add_run_flags(*sub, *opt);
  add_output_options(*sub, opt->out, opt->force, opt->quiet);
  sub->add_flag_callback("--no-page", [opt] { opt->page = false; },
                         "Write no DIR/index.html (the page `grainshock view DIR` writes)");
  add_checkpoint_option(*sub, opt->checkpoint_every);
  sub->footer(
      "Unless one of --t-max, --snapshot-times, --png, --compare-elastic or --movie is given "
      "(on the command line or in --config), runs the paper's Fig. 1 job with the physics "
      "given (defaults: the paper's box of 2.5e5 discs, r = 0.1; any other kick in 2D or 3D "
      "runs in --medium unbounded unless told): t-max = paper time 50000, snapshots and pictures "
      "at paper times 5000, 10000, 20000, 50000, their overlay, the elastic comparison and a "
      "movie of the front. So `--seed 2` is the Fig. 1 job with seed 2. DIR/run.toml holds "
      "every setting that shapes the results: `grainshock run --config DIR/run.toml --out NEW` "
      "writes the same files.");
  sub->callback([opt, sub] {
    // The Fig. 1 job is the paper's box of 2.5e5 discs, framed on the box, unless --medium says.
    apply_medium_default(*sub, opt->plan.physics, apply_fig1_rule(*sub, *opt));
    opt->progress = terminal_progress(opt->quiet);
    opt->messages = terminal_messages();
    if (run_job(*opt, false).stopped) throw Exit{kExitInterrupted};
  });
}

}  // namespace gs::app
