// `grainshock ensemble`: M realisations over ranks (mpirun) and threads, averaged with errors and
// fitted. Each realisation is written into OUT/realisations/ as it finishes, so the same command
// again (or `grainshock resume OUT`) after a kill runs only the missing ones, to the same bytes.
#include <CLI/CLI.hpp>

#include <thread>

#include "apps/cli.h"
#include "apps/commands.h"
#include "apps/ensemble_cli.h"
#include "apps/exit_code.h"
#include "apps/progress.h"

namespace gs::app {

using jobs::EnsembleOptions;

void add_ensemble_command(CLI::App& app) {
  auto opt = std::make_shared<EnsembleOptions>();
  auto* sub = app.add_subcommand(
      "ensemble",
      "Run M realisations over threads (and MPI ranks under mpirun); average, fit exponents, "
      "write a folder and print the exponents on stdout");
  add_config_option(*sub);
  add_physics_options(*sub, opt->physics);
  sub->add_option("--realisations", opt->realisations,
                  "Number of realisations M (indices --realisation .. + M - 1)")
      ->transform(whole_number())
      ->capture_default_str();
  sub->add_option("--threads", opt->threads,
                  "Worker threads K per process, 1 to 1024 (results do not depend on it)")
      ->capture_default_str();
  add_output_options(*sub, opt->out, opt->force, opt->quiet);
  sub->add_flag_callback("--no-page", [opt] { opt->page = false; },
                         "Write no DIR/index.html (the page `grainshock view DIR` writes)");
  sub->add_option("--per-decade", opt->per_decade, "Samples per decade of the logarithmic grid")
      ->capture_default_str();
  sub->add_option(
         "--snapshot-times", opt->snapshot_times,
         "Times of P(R,t), P(v,t), profiles and packing (default: t-max/4, t-max/2, t-max)")
      ->delimiter(',');
  sub->add_option("--bins", opt->bins, "Bins of the distributions and profiles")
      ->capture_default_str();
  add_fit_options(*sub, opt->resamples, opt->window);
  add_checkpoint_minutes_option(*sub, opt->checkpoint_minutes);
  sub->add_flag("--per-realisation", opt->per_realisation,
                "Keep OUT/realisations/ once finished (input of grainshock merge); it is always "
                "written while the ensemble runs, so that a killed one resumes");
  sub->footer(
      "The table of exponents goes to stdout (also with --quiet). Each realisation is written "
      "into OUT/realisations/ as it finishes: the same command into a folder holding an "
      "unfinished ensemble (killed or interrupted) runs only the missing realisations, with the "
      "same bytes as an uninterrupted run; a realisation still running goes on from the state it "
      "keeps every --checkpoint-every seconds (and at Ctrl-C) in OUT/realisations/in_flight/. "
      "Under "
      "mpirun -n K the realisations are split over K ranks of --threads each; rank 0 writes and "
      "prints (and only its realisations keep a state). Results do not depend on K, --threads "
      "or resumes.");
  sub->callback([opt, sub] {
    apply_medium_default(*sub, opt->physics);
    deprecated_checkpoint_minutes(*sub, opt->quiet);
    opt->progress = terminal_progress(opt->quiet);
    opt->messages = terminal_messages();
    const int rc = finish_ensemble_command(jobs::run_ensemble_job(*opt));
    if (rc != 0) throw Exit{rc};
  });
}

}  // namespace gs::app
