// `grainshock figures`: the paper's Figs. 1-5 (Jabeen, Rajesh, Ray, EPL 2010) and a report of
// every measured number next to the paper's, from one ensemble per (d, r).
#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <sstream>
#include <thread>

#include "analysis/ensemble_output.h"
#include "analysis/ensemble_runner.h"
#include "analysis/json.h"
#include "analysis/paper.h"
#include "apps/cli.h"
#include "apps/commands.h"
#include "apps/ensemble_cli.h"
#include "apps/progress.h"
#include "io/atomic_file.h"
#include "io/output_dir.h"
#include "jobs/figures_plan.h"
#include "jobs/figures_plots.h"
#include "jobs/figures_report.h"
#include "jobs/plot.h"
#include "sim/error.h"
#include "sim/stop.h"

namespace gs::app {

using namespace jobs;
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

double since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

struct FiguresOptions {
  bool quick = false, full = false, tiny = false, estimate = false, long_3d = false;
  std::string out = "grainshock-figures";
  bool force = false, quiet = false;
  int threads = std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
  std::uint64_t seed = 1;
  int sample = 2;  // realisations per case for --estimate
  std::string format = "png";
};

FiguresMode mode_of(const FiguresOptions& o) {
  if (int(o.quick) + int(o.full) + int(o.tiny) > 1)
    throw UserError("figures: give at most one of --quick, --full, --tiny");
  return o.full ? FiguresMode::Full : o.tiny ? FiguresMode::Tiny : FiguresMode::Quick;
}

// --estimate: a sample of realisations of every case, run `threads` at a time as the real run
// would, extrapolated to the plan's realisation counts; from wall time and, beside it, from the
// process's CPU time, which another program on the machine changes least (loaded machines).
void estimate(const FiguresOptions& o, const FiguresPlan& plan, const fs::path& dir) {
  std::ostringstream j, table;
  j << "{\n  \"mode\": " << json_string(to_string(plan.mode)) << ",\n  \"threads\": " << o.threads
    << ",\n  \"sample_per_case\": " << o.sample << ",\n  \"cases\": [\n";
  table << "| case | N | t_max | M | sample wall (s) | s per realisation per thread | estimated "
           "wall (s) | CPU s per realisation | estimated from CPU (s) |\n"
           "|---|---|---|---|---|---|---|---|---|\n";
  double total = 0, total_cpu = 0;
  for (std::size_t k = 0; k < plan.cases.size(); ++k) {
    const auto& c = plan.cases[k];
    EnsembleSpec s = c.spec;
    s.realisations = static_cast<std::uint64_t>(o.sample);
    RunnerOptions ro;
    ro.threads = o.threads;
    const auto t0 = Clock::now();
    const std::clock_t c0 = std::clock();  // process CPU time, every thread
    const RunnerResult r = run_ensemble(s, ro);
    const double wall = since(t0);
    const double cpu = double(std::clock() - c0) / CLOCKS_PER_SEC / o.sample;
    if (r.interrupted) throw UserError("interrupted");
    // Each thread ran sample/threads realisations in `wall`.
    const double per = wall * std::min(o.threads, o.sample) / o.sample;
    const double est = per * double(c.spec.realisations) / o.threads;
    const double est_cpu = cpu * double(c.spec.realisations) / o.threads;
    total += est;
    total_cpu += est_cpu;
    j << "    {\"case\": " << json_string(c.name) << ", \"particles\": " << c.spec.physics.particles
      << ", \"t_max\": " << json_number(c.spec.physics.t_max)
      << ", \"realisations\": " << c.spec.realisations
      << ", \"sample_wall_seconds\": " << json_number(wall)
      << ", \"estimated_wall_seconds\": " << json_number(est)
      << ", \"cpu_seconds_per_realisation\": " << json_number(cpu)
      << ", \"estimated_wall_seconds_from_cpu\": " << json_number(est_cpu) << "}"
      << (k + 1 < plan.cases.size() ? "," : "") << "\n";
    table << "| " << c.name << " | " << c.spec.physics.particles << " | "
          << figure_number(c.spec.physics.t_max) << " | " << c.spec.realisations << " | "
          << figure_number(wall) << " | " << figure_number(per) << " | " << figure_number(est)
          << " | " << figure_number(cpu) << " | " << figure_number(est_cpu) << " |\n";
    if (!o.quiet)
      std::fprintf(stderr,
                   "grainshock: estimate %s: %d realisations in %.3g s -> %.4g s for %llu\n",
                   c.name.c_str(), o.sample, wall, est,
                   static_cast<unsigned long long>(c.spec.realisations));
  }
  j << "  ],\n  \"estimated_wall_seconds_from_cpu\": " << json_number(total_cpu)
    << ",\n  \"estimated_wall_seconds\": " << json_number(total) << "\n}\n";
  write_file_atomic(dir / "estimate.json", j.str());
  std::ostringstream md;
  md << "# Wall-time estimate of `grainshock figures --" << to_string(plan.mode)
     << (o.long_3d ? " --long" : "") << "`\n\n"
     << "From " << o.sample << " realisations per case run on " << o.threads
     << " threads, scaled to the plan's realisation counts (the renderer and plots add "
        "seconds).\n\n"
     << table.str() << "\n**Total: " << figure_number(total) << " s ("
     << figure_number(total / 60, 3) << " min); from CPU time " << figure_number(total_cpu)
     << " s (" << figure_number(total_cpu / 60, 3) << " min).**\n";
  write_file_atomic(dir / "estimate.md", md.str());
  if (!o.quiet)
    std::fprintf(stderr,
                 "grainshock: estimated wall time %.4g s (%.3g min), from CPU time %.4g s\n", total,
                 total / 60, total_cpu);
}

void run(const FiguresOptions& o) {
  const FiguresMode mode = mode_of(o);
  if (o.threads < 1) throw UsageError("--threads must be at least 1");
  if (o.sample < 1) throw UsageError("--sample must be at least 1");
  const std::vector<std::string> formats = parse_plot_formats(o.format);
  const FiguresPlan plan = figures_plan(mode, o.seed, o.long_3d);
  const auto dir = prepare_output_dir(o.out, o.force);
  install_stop_handlers();
  if (o.estimate) return estimate(o, plan, dir);

  const auto t0 = Clock::now();
  std::vector<CaseResult> results;
  std::uint64_t total = 0, done_before = 0;
  for (const auto& c : plan.cases) total += c.spec.realisations;
  Progress progress(o.quiet);
  std::vector<Comparison> cmp;
  for (const auto& c : plan.cases) {
    RunnerOptions ro;
    ro.threads = o.threads;
    ro.on_progress = [&](std::uint64_t done, std::uint64_t) {
      progress.update(double(done_before + done) / double(total),
                      c.name + ": " + std::to_string(done) + " of " +
                          std::to_string(c.spec.realisations) + " realisations");
    };
    const auto tc = Clock::now();
    RunnerResult r = run_ensemble(c.spec, ro);
    if (r.interrupted)
      throw UserError("interrupted; the ensembles finished so far are in " + dir.string());
    done_before += c.spec.realisations;
    const auto edir = dir / "ensembles" / c.name;
    fs::create_directories(edir);
    CaseResult cr{&c, std::move(r.sums), {}, since(tc)};
    cr.fits = jobs::write_ensemble_folder(edir, cr.sums, FitOptions{}, cr.wall, o.threads);
    if (!c.delta_scan) {
      const auto more = case_comparisons(c.name, c.spec, cr.fits, slope_figure_of(c));
      cmp.insert(cmp.end(), more.begin(), more.end());
    }
    results.push_back(std::move(cr));
  }
  progress.done();
  const double sim_wall = since(t0);

  const Crossovers x = crossovers_of(results);
  for (const auto& set : x.tc1) cmp.push_back(phi1_comparison(set.d, set.fit, false));
  for (const auto& set : x.tc1_theory_b) cmp.push_back(phi1_comparison(set.d, set.fit, true));
  for (const auto& set : x.tc1) cmp.push_back(phi1_elastic_limit_comparison(set.d, set.local));
  cmp.push_back(phi2_comparison(x.tc2.front().d, 0.1, x.tc2.front().fit));
  const std::vector<std::string> problems = write_figures(plan, results, x, dir, formats);
  const FiguresRun run{mode, o.seed, o.threads, since(t0), sim_wall};
  write_figures_summary(dir, run, results, cmp, problems);
  write_figures_report(dir, run, results, x, cmp, problems);
  if (!o.quiet) {
    std::fprintf(stderr, "grainshock: figures (%s) in %.4g s; report in %s\n", to_string(mode),
                 run.wall, (dir / "report.md").c_str());
    for (const auto& p : problems) std::fprintf(stderr, "grainshock: warning: %s\n", p.c_str());
  }
}

}  // namespace

void add_figures_command(CLI::App& app) {
  auto opt = std::make_shared<FiguresOptions>();
  auto* sub =
      app.add_subcommand("figures", "Reproduce the paper's Figs. 1-5 and a report with numbers");
  sub->add_flag("--quick", opt->quick,
                "Smaller systems, fewer realisations: < 3 min on 2 cores (default)");
  sub->add_flag("--full", opt->full,
                "The paper's sizes (2.5e5 discs, 2e6 spheres) with 12-48 realisations per "
                "case, and the 3D elastic blast at 4e6 spheres: < 30 min on 2 cores (see "
                "--estimate)");
  sub->add_flag("--long", opt->long_3d,
                "Add the long 3D runs (r = 0.1, 0.5; 4e6 spheres, delta = 1e-6, to t = 1e6, 16 "
                "realisations each): about an hour on 2 cores; see --long --estimate");
  sub->add_flag("--tiny", opt->tiny,
                "Seconds-long smoke run (tests): every file, meaningless numbers");
  sub->add_flag(
      "--estimate", opt->estimate,
      "Only estimate the wall time of the chosen mode from --sample realisations per case");
  sub->add_option("--sample", opt->sample, "Realisations per case for --estimate")
      ->capture_default_str();
  sub->add_option("--format", opt->format,
                  "Figure formats, comma-separated: png, svg, pdf (the .gp scripts write any)")
      ->capture_default_str();
  add_output_options(*sub, opt->out, opt->force, opt->quiet);
  sub->add_option("--threads", opt->threads, "Worker threads")->capture_default_str();
  sub->add_option("--seed", opt->seed, "Master seed of every ensemble")->capture_default_str();
  sub->callback([opt] { run(*opt); });
}

}  // namespace gs::app
