// `grainshock ensemble`: M realisations on K threads, averaged with errors and fitted.
#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdio>
#include <mutex>
#include <thread>

#include "analysis/ensemble_runner.h"
#include "apps/cli.h"
#include "apps/commands.h"
#include "apps/ensemble_cli.h"
#include "apps/progress.h"
#include "sim/error.h"
#include "sim/stop.h"

namespace gs::app {
namespace {

struct EnsembleOptions {
  PhysicsConfig physics;
  long long realisations = 8;
  int threads = std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
  std::string out = "grainshock-ensemble";
  bool force = false, quiet = false, per_realisation = false;
  int per_decade = 20, bins = 60, resamples = 1000;
  std::vector<double> snapshot_times, window;
};

int run(const EnsembleOptions& o) {
  // Every check before the output folder is touched: bad input leaves nothing behind.
  if (o.realisations < 1) throw UserError("--realisations must be at least 1");
  if (o.threads < 1) throw UserError("--threads must be at least 1");
  if (o.resamples < 10) throw UserError("--resamples must be at least 10");
  EnsembleSpec spec;
  spec.physics = o.physics;
  spec.realisations = static_cast<std::uint64_t>(o.realisations);
  spec.per_decade = o.per_decade;
  spec.bins = o.bins;
  spec.snapshot_times = o.snapshot_times;
  spec = checked(spec);
  FitOptions fit;
  fit.window = window_of(o.window, spec);
  fit.resamples = o.resamples;
  const auto dir = prepare_output_dir(o.out, o.force);

  install_stop_handlers();
  Progress progress(o.quiet);
  RunnerOptions ro;
  ro.threads = o.threads;
  if (o.per_realisation) ro.per_realisation_dir = dir / "realisations";
  ro.on_progress = [&](std::uint64_t done, std::uint64_t total) {
    progress.update(double(done) / double(total),
                    std::to_string(done) + " of " + std::to_string(total) + " realisations");
  };
  const auto t0 = std::chrono::steady_clock::now();
  RunnerResult r = run_ensemble(spec, ro);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  progress.done();
  if (r.sums.count() == 0) throw UserError("interrupted before any realisation finished");
  const EnsembleFits fits = write_ensemble_folder(dir, r.sums, fit, wall, o.threads);
  if (!o.quiet) {
    std::fprintf(stderr,
                 "grainshock: %s %llu realisations in %.3g s on %d threads; results in %s\n",
                 r.interrupted ? "interrupted after" : "finished",
                 static_cast<unsigned long long>(r.sums.count()), wall, o.threads, dir.c_str());
    for (const auto& e : fits.exponents)
      std::fprintf(stderr, "  %s ~ t^%.4f [%.4f, %.4f]  theory %.4f  (alpha %.4f +- %.4f)%s%s\n",
                   e.quantity.c_str(), e.fit.exponent, e.fit.ci_lo, e.fit.ci_hi, e.theory, e.alpha,
                   e.alpha_uncertainty, e.note.empty() ? "" : "  ", e.note.c_str());
  }
  return r.interrupted ? 128 + std::max(0, stop_signal()) : 0;
}

}  // namespace

void add_ensemble_command(CLI::App& app) {
  auto opt = std::make_shared<EnsembleOptions>();
  auto* sub = app.add_subcommand(
      "ensemble", "Run M realisations on K threads; average, fit exponents, write a folder");
  add_config_option(*sub);
  add_physics_options(*sub, opt->physics);
  sub->add_option("--realisations", opt->realisations,
                  "Number of realisations M (indices --realisation .. + M - 1)")
      ->capture_default_str();
  sub->add_option("--threads", opt->threads, "Worker threads K (results do not depend on it)")
      ->capture_default_str();
  add_output_options(*sub, opt->out, opt->force, opt->quiet);
  sub->add_option("--per-decade", opt->per_decade, "Samples per decade of the logarithmic grid")
      ->capture_default_str();
  sub->add_option(
         "--snapshot-times", opt->snapshot_times,
         "Times of P(R,t), P(v,t), profiles and packing (default: t-max/4, t-max/2, t-max)")
      ->delimiter(',');
  sub->add_option("--bins", opt->bins, "Bins of the distributions and profiles")
      ->capture_default_str();
  sub->add_option("--resamples", opt->resamples, "Bootstrap resamples of the exponent intervals")
      ->capture_default_str();
  add_window_option(*sub, opt->window);
  sub->add_flag("--per-realisation", opt->per_realisation,
                "Also write each realisation into OUT/realisations/ (input of grainshock merge)");
  sub->callback([opt] {
    const int rc = run(*opt);
    if (rc != 0) std::exit(rc);
  });
}

}  // namespace gs::app
