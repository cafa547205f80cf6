#include <CLI/CLI.hpp>

#include "apps/cli.h"
#include "apps/commands.h"
#include "sim/config.h"

namespace gs::app {

void add_run_command(CLI::App& app) {
  struct Options {
    PhysicsConfig physics;
    std::string out = "grainshock-run";
    bool force = false;
  };
  auto opt = std::make_shared<Options>();
  auto* sub = app.add_subcommand("run", "Simulate one realisation and write a run folder");
  add_config_option(*sub);
  add_physics_options(*sub, opt->physics);
  sub->add_option("--out", opt->out, "Output folder (must not exist or be empty)")
      ->capture_default_str();
  sub->add_flag("--force", opt->force, "Write into an existing non-empty output folder");
  sub->callback([opt] {
    validate(opt->physics);
    const auto dir = prepare_output_dir(opt->out, opt->force);
    write_file_atomic(dir / "run.toml", to_toml(opt->physics));
  });
}

}  // namespace gs::app
