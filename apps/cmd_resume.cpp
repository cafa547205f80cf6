// `grainshock resume DIR`: continues a run folder from its last checkpoint (apps/run_job.h).
#include <CLI/CLI.hpp>
#include <memory>

#include "apps/commands.h"
#include "apps/exit_code.h"
#include "apps/run_job.h"

namespace gs::app {

void add_resume_command(CLI::App& app) {
  struct Options {
    std::string dir;
    bool quiet = false;
    double checkpoint_every = RunOptions{}.checkpoint_every;
  };
  auto opt = std::make_shared<Options>();
  auto* sub = app.add_subcommand(
      "resume", "Continue a run folder from its last checkpoint, after Ctrl-C or a kill");
  sub->add_option("DIR", opt->dir, "The run folder (as given to run --out)")->required();
  sub->add_flag("--quiet", opt->quiet, "Nothing on stderr but errors");
  add_checkpoint_option(*sub, opt->checkpoint_every);
  sub->footer(
      "The run goes on from its checkpoint with the settings of DIR/run.toml and ends with the "
      "same timeseries.csv, snapshots, pictures, movie and summary.json, byte for byte, as a "
      "run that was never stopped. Refused, with nothing in DIR touched: a folder without a "
      "checkpoint, a finished run, a run.toml that is not the checkpoint's, a checkpoint that "
      "is truncated, corrupt or from another version or build.");
  sub->callback([opt] {
    RunOptions o = read_run_file(std::filesystem::path(opt->dir) / "run.toml");
    o.out = opt->dir;
    o.quiet = opt->quiet;
    o.checkpoint_every = opt->checkpoint_every;
    const int rc = run_job(o, true);
    if (rc != 0) throw Exit{rc};
  });
}

}  // namespace gs::app
