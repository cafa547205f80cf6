#include "jobs/figures_job.h"

#include <cmath>
#include <cstdio>
#include <ctime>
#include <sstream>

#include "analysis/ensemble_output.h"
#include "analysis/ensemble_runner.h"
#include "analysis/json.h"
#include "analysis/paper.h"
#include "io/atomic_file.h"
#include "io/output_dir.h"
#include "jobs/ensemble_job.h"
#include "jobs/figures_plots.h"
#include "jobs/figures_report.h"
#include "sim/error.h"
#include "sim/stop.h"

namespace gs::jobs {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

// A sample of realisations of every case, run `threads` at a time as the real run would,
// extrapolated to the plan's realisation counts; from wall time and, beside it, from the
// process's CPU time, which another program on the machine changes least (loaded machines).
void estimate(const FiguresOptions& o, const FiguresPlan& plan, const fs::path& dir) {
  Json j;
  j["mode"] = to_string(plan.mode);
  j["threads"] = o.threads;
  j["sample_per_case"] = o.sample;
  Json& cases = j["cases"] = Json::array();
  std::ostringstream table;
  table << "| case | N | t_max | M | sample wall (s) | s per realisation per thread | estimated "
           "wall (s) | CPU s per realisation | estimated from CPU (s) |\n"
           "|---|---|---|---|---|---|---|---|---|\n";
  double total = 0, total_cpu = 0;
  for (const auto& c : plan.cases) {
    EnsembleSpec s = c.spec;
    s.realisations = static_cast<std::uint64_t>(o.sample);
    RunnerOptions ro;
    ro.threads = o.threads;
    const auto t0 = Clock::now();
    const std::clock_t c0 = std::clock();  // process CPU time, every thread
    const RunnerResult r = run_ensemble(s, ro);
    const double wall = seconds_since(t0);
    const double cpu = double(std::clock() - c0) / CLOCKS_PER_SEC / o.sample;
    if (r.interrupted) throw UserError("interrupted");
    // Each thread ran sample/threads realisations in `wall`.
    const double per = wall * std::min(o.threads, o.sample) / o.sample;
    const double est = per * double(c.spec.realisations) / o.threads;
    const double est_cpu = cpu * double(c.spec.realisations) / o.threads;
    total += est;
    total_cpu += est_cpu;
    cases.push_back({{"case", c.name},
                     {"particles", c.spec.physics.particles},
                     {"t_max", c.spec.physics.t_max},
                     {"realisations", c.spec.realisations},
                     {"sample_wall_seconds", wall},
                     {"estimated_wall_seconds", est},
                     {"cpu_seconds_per_realisation", cpu},
                     {"estimated_wall_seconds_from_cpu", est_cpu}});
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
  j["estimated_wall_seconds_from_cpu"] = total_cpu;
  j["estimated_wall_seconds"] = total;
  write_file_atomic(dir / "estimate.json", json_text(j));
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

}  // namespace

FiguresResult run_figures_job(const FiguresOptions& o) {
  if (o.threads < 1) throw UsageError("--threads must be at least 1");
  if (o.sample < 1) throw UsageError("--sample must be at least 1");
  const FiguresPlan plan = figures_plan(o.mode, o.seed, o.long_3d);
  FiguresResult out;
  out.dir = prepare_output_dir(o.out, o.force);
  const fs::path& dir = out.dir;
  install_stop_handlers();
  const auto t0 = Clock::now();
  if (o.estimate) {
    estimate(o, plan, dir);
    out.wall = seconds_since(t0);
    return out;
  }

  std::vector<CaseResult> results;
  std::uint64_t total = 0, done_before = 0;
  for (const auto& c : plan.cases) total += c.spec.realisations;
  const auto progress = open_progress(o.progress);
  std::vector<Comparison> cmp;
  for (const auto& c : plan.cases) {
    RunnerOptions ro;
    ro.threads = o.threads;
    ro.on_progress = [&](std::uint64_t done, std::uint64_t) {
      progress->update(double(done_before + done) / double(total),
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
    CaseResult cr{&c, std::move(r.sums), {}, seconds_since(tc)};
    cr.fits = write_ensemble_folder(edir, cr.sums, FitOptions{}, cr.wall, o.threads);
    if (!c.delta_scan) {
      auto more = case_comparisons(c.name, c.spec, cr.fits, slope_figure_of(c));
      if (c.superseded_for_alpha)
        for (auto& m : more)
          if (m.quantity.starts_with("alpha from")) {
            m.counted = false;
            m.note = "superseded by d3_r1_large (the same physics in a larger box); " + m.note;
          }
      cmp.insert(cmp.end(), more.begin(), more.end());
    }
    results.push_back(std::move(cr));
  }
  progress->done();
  const double sim_wall = seconds_since(t0);

  const Crossovers x = crossovers_of(results);
  for (const auto& set : x.tc1) cmp.push_back(phi1_comparison(set.d, set.fit, false));
  for (const auto& set : x.tc1_theory_b) cmp.push_back(phi1_comparison(set.d, set.fit, true));
  for (const auto& set : x.tc1) cmp.push_back(phi1_elastic_limit_comparison(set.d, set.local));
  for (const auto& set : x.tc1) {
    cmp.push_back(phi1_energy_comparison(set.d, set.energy, std::nan("")));
    for (double level : Phi1Options{}.levels)
      cmp.push_back(phi1_energy_comparison(set.d, set.energy, level));
  }
  cmp.push_back(phi2_comparison(x.tc2.front().d, 0.1, x.tc2.front().fit));
  const std::vector<std::string> problems = write_figures(plan, results, x, dir, o.formats);
  const FiguresRun run{o.mode, o.seed, o.threads, seconds_since(t0), sim_wall, plan.fig1};
  write_figures_summary(dir, run, results, cmp, problems);
  write_figures_report(dir, run, results, x, cmp, problems);
  out.wall = run.wall;
  out.problems = problems;
  return out;
}

}  // namespace gs::jobs
