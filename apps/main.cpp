// grainshock: a granular gas at rest answers a single kick. See README.md.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>

#include "apps/commands.h"
#include "sim/error.h"

int main(int argc, char** argv) {
  CLI::App app{
      "grainshock: event-driven simulation, analysis and rendering of a kicked granular gas"};
  app.set_version_flag("--version", GRAINSHOCK_VERSION);
  app.require_subcommand(1);
  gs::app::add_run_command(app);
  gs::app::add_render_command(app);
  gs::app::add_bench_command(app);
  gs::app::add_movie_command(app);
  gs::app::add_ensemble_command(app);
  gs::app::add_merge_command(app);
  gs::app::add_figures_command(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::fprintf(stderr, "grainshock: error: %s\n", e.what());
    return e.get_exit_code() ? e.get_exit_code() : 2;
  } catch (const gs::UserError& e) {
    std::fprintf(stderr, "grainshock: error: %s\n", e.what());
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "grainshock: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
