// `grainshock figures`: the paper's Figs. 1-5 (Jabeen, Rajesh, Ray, EPL 2010) and a report of
// every measured number next to the paper's, from one ensemble per (d, r). The job is
// jobs/figures_job; this is its flags.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <memory>

#include "apps/cli.h"
#include "apps/commands.h"
#include "apps/exit_code.h"
#include "apps/progress.h"
#include "jobs/figures_job.h"
#include "jobs/plot.h"
#include "sim/error.h"
#include "sim/format.h"

namespace gs::app {
namespace {

struct FiguresFlags {
  bool quick = false, full = false, tiny = false;
  std::string format = "png";
  jobs::FiguresOptions job;
};

jobs::FiguresMode mode_of(const FiguresFlags& f) {
  if (int(f.quick) + int(f.full) + int(f.tiny) > 1)
    throw UsageError("--quick, --full and --tiny exclude each other; give at most one");
  return f.full   ? jobs::FiguresMode::Full
         : f.tiny ? jobs::FiguresMode::Tiny
                  : jobs::FiguresMode::Quick;
}

void add_figures_flags(CLI::App& sub, FiguresFlags& flags) {
  jobs::FiguresOptions& o = flags.job;
  add_config_option(sub);
  sub.add_flag("--quick", flags.quick,
               "Smaller systems, fewer realisations: < 3 min on 2 cores (default)");
  sub.add_flag("--full", flags.full,
               "The paper's sizes (2.5e5 discs, 2e6 spheres) with 12-48 realisations per "
               "case, and the 3D elastic blast at 4e6 spheres: < 30 min on 2 cores (see "
               "--estimate)");
  sub.add_flag("--long", o.long_3d,
               "Add the long 3D runs (r = 0.1, 0.5; 4e6 and 8e6 spheres, delta = 1e-6, to t = 1e6, "
               "16 realisations each): about 25 min on 2 cores; see --long --estimate");
  sub.add_flag("--limit", o.limit,
               "Add phi1 nearest the elastic limit: 2D and 3D r = 0.9 and 0.95 in the unbounded "
               "medium until E_t's local slope plateaus (3D r = 0.95 only to t = 4e5, E_0/20); "
               "see --limit --estimate for its time on 2 cores");
  sub.add_flag("--snowplow", o.snowplow,
               "Add the snowplow runs: 3D r = 0.1, 0.5 to t = 1.2e6 and 2D r = 0.1, 0.5 to t = 2e6 in "
               "the unbounded medium, 20 realisations each, weighing alpha = 1/(d+1) against "
               "2/(d+4) by R_t, N_t, E_t and P_r; hours on 2 cores: see --snowplow --estimate");
  sub.add_option("--limit-dim", o.limit_dim,
                 "With --limit, only the cases of this dimension (2: about 1.2 h on 2 cores)");
  sub.add_flag("--tiny", flags.tiny,
               "Seconds-long smoke run (tests): every file, meaningless numbers");
  sub.add_flag(
      "--estimate", o.estimate,
      "Only estimate the wall time of the chosen mode from --sample realisations per case");
  sub.add_option("--sample", o.sample, "Realisations per case for --estimate")
      ->capture_default_str();
  sub.add_option("--format", flags.format,
                 "Figure formats, comma-separated: png, svg, pdf (the .gp scripts write any)")
      ->capture_default_str();
  add_output_options(sub, o.out, o.force, o.quiet);
  sub.add_flag_callback("--no-page", [&o] { o.page = false; },
                        "Write no report.html beside report.md (the page of `grainshock view`)");
  sub.add_option("--threads", o.threads, "Worker threads, 1 to 1024")->capture_default_str();
  sub.add_option("--seed", o.seed, "Master seed of every ensemble")->capture_default_str();
  add_checkpoint_minutes_option(sub, o.checkpoint_minutes);
}

// Where and how the job runs, not which ensembles it runs: left out of figures.toml.
constexpr std::string_view kNotSettings[] = {"--threads", "--estimate", "--sample"};

// figures.toml keeps the checkpoint interval as the minutes `resume` reads back, also when the
// command was given it as --checkpoint-every seconds.
std::string figures_settings(const CLI::App& sub, double checkpoint_minutes) {
  if (sub.get_option("--checkpoint-every")->count() == 0) return settings_toml(sub, kNotSettings);
  constexpr std::string_view left_out[] = {"--threads", "--estimate", "--sample",
                                           "--checkpoint-minutes"};
  return settings_toml(sub, left_out) +
         "checkpoint-minutes = " + format_double(checkpoint_minutes) + "\n";
}

int run(FiguresFlags f, const CLI::App& sub) {
  jobs::FiguresOptions& o = f.job;
  o.mode = mode_of(f);
  o.formats = jobs::parse_plot_formats(f.format);
  o.progress = terminal_progress(o.quiet);
  o.messages = terminal_messages();
  o.settings =
      "# grainshock figures: the job of this folder.\n"
      "# Again: grainshock figures --config figures.toml --out NEW; continue: grainshock resume "
      "DIR\n" +
      figures_settings(sub, o.checkpoint_minutes);
  const jobs::FiguresResult r = jobs::run_figures_job(o);
  if (r.interrupted) {
    if (!o.estimate)
      std::fprintf(stderr, "grainshock: interrupted; continue with: grainshock resume %s\n",
                   r.dir.c_str());
    return kExitInterrupted;
  }
  if (o.quiet || o.estimate) return kExitSuccess;
  std::fprintf(stderr, "grainshock: figures (%s) in %.4g s; report in %s\n", to_string(o.mode),
               r.wall, (r.dir / "report.md").c_str());
  for (const auto& p : r.problems) std::fprintf(stderr, "grainshock: warning: %s\n", p.c_str());
  return kExitSuccess;
}

}  // namespace

int resume_figures(const std::filesystem::path& dir, int threads, bool quiet) {
  const auto file = dir / "figures.toml";
  CLI::App app;
  auto* sub = app.add_subcommand("figures");
  FiguresFlags flags;
  add_figures_flags(*sub, flags);
  parse_settings_file(app, "figures", file);
  flags.job.out = dir.string();
  flags.job.resume = true;
  flags.job.threads = threads;
  flags.job.quiet = quiet;
  return run(flags, *sub);
}

void add_figures_command(CLI::App& app) {
  auto flags = std::make_shared<FiguresFlags>();
  auto* sub =
      app.add_subcommand("figures", "Reproduce the paper's Figs. 1-5 and a report with numbers");
  add_figures_flags(*sub, *flags);
  sub->footer(
      "A job stopped by Ctrl-C or killed goes on from the realisations it finished, and from the "
      "state each running one keeps every --checkpoint-every seconds (and at Ctrl-C), with "
      "grainshock "
      "resume DIR, to the same files as a job never stopped (figures.toml holds its settings).");
  sub->callback([flags, sub] {
    deprecated_checkpoint_minutes(*sub, flags->job.quiet);
    const int rc = run(*flags, *sub);
    if (rc != kExitSuccess) throw Exit{rc};
  });
}

}  // namespace gs::app
