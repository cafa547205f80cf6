// grainshock: a granular gas at rest answers a single kick. See README.md.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>
#include <new>
#include <set>

#include "apps/cli.h"
#include "apps/commands.h"
#include "apps/completion.h"
#include "apps/exit_code.h"
#include "apps/suggest.h"
#include "sim/error.h"
#include "sim/escaped.h"
#include "sim/stop.h"

namespace {

// Every time a flag takes is simulation time, in diameters / v0; the help of each says so, once.
// (The paper's unit t_paper = t v0 n^(1/d) is written beside it in the outputs; no flag takes it.)
void mark_time_flags(CLI::App& app) {
  const std::set<std::string> time_flags = {"--t-max", "--t-start", "--sample-every",
                                            "--snapshot-times", "--window"};
  for (CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; }))
    for (CLI::Option* o : sub->get_options())
      if (time_flags.count(o->get_name()) &&
          o->get_description().find("simulation time") == std::string::npos)
        o->description(o->get_description() + " [simulation time]");
}

int fail(int code, const char* what) {
  std::fflush(stdout);
  // Whatever input the message quotes, no byte of it drives the terminal.
  std::fprintf(stderr, "grainshock: error: %s\n", gs::escaped(what).c_str());
  return code;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace gs::app;
  CLI::App app{
      "grainshock: event-driven simulation, analysis and rendering of a kicked granular gas"};
  app.require_subcommand(1);
  add_run_command(app);
  add_resume_command(app);
  add_render_command(app);
  add_bench_command(app);
  add_movie_command(app);
  add_ensemble_command(app);
  add_merge_command(app);
  add_figures_command(app);
  add_compare_command(app);
  add_view_command(app);
  add_completion_command(app);
  // After the subcommands, so that completion and suggestions see them all.
  app.set_version_flag("--version", GRAINSHOCK_VERSION);
  app.footer(std::string("Times: flags marked [simulation time] take units of diameter / v0; the "
                         "paper's time t_paper = t v0 n^(1/d) is printed beside it in the "
                         "outputs, and no flag takes it.\n\n") +
             kExitCodeHelp);
  mark_time_flags(app);
  check_number_text(app);
  for (CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; })) {
    sub->set_version_flag("--version", GRAINSHOCK_VERSION);
    if (sub->get_name() != "compare")
      sub->footer(sub->get_footer() + (sub->get_footer().empty() ? "" : "\n\n") +
                  "Exit codes: 0 success, 1 user error, 2 usage error, 130 interrupted "
                  "(grainshock --help).");
  }
  const std::vector<std::string> args(argv + (argc > 0), argv + argc);
  // The commands whose long loops poll the stop take SIGINT and SIGTERM from the start, so that
  // a signal before their work begins also ends them with 130; the others (compare, bench,
  // completion) keep the default, which ends them at once.
  const std::set<std::string> stoppable = {"run",      "resume",  "movie", "ensemble",
                                           "figures", "merge", "render"};
  if (!args.empty() && stoppable.count(args[0])) gs::install_stop_handlers();
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    return fail(kExitUsageError, explain_parse_error(app, args, e).c_str());
  } catch (const Exit& e) {
    std::fflush(stdout);
    return e.code;
  } catch (const CodedError& e) {
    return fail(e.code(), e.what());
  } catch (const gs::Stopped&) {
    // Stopped where there was nothing to keep yet (a run's set-up, a file being read).
    std::fflush(stdout);
    std::fprintf(stderr, "grainshock: interrupted; what was written before is whole\n");
    return kExitInterrupted;
  } catch (const gs::UsageError& e) {
    return fail(kExitUsageError, e.what());
  } catch (const gs::UserError& e) {
    return fail(kExitUserError, e.what());
  } catch (const std::bad_alloc&) {
    return fail(kExitUserError, "out of memory");
  } catch (const std::exception& e) {
    return fail(kExitUserError, e.what());
  }
  return kExitSuccess;
}
