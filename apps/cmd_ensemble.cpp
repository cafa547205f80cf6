// `grainshock ensemble`: M realisations over ranks (mpirun) and threads, averaged with errors and
// fitted. Each realisation is written into OUT/realisations/ as it finishes, so the same command
// again (or `grainshock resume OUT`) after a kill runs only the missing ones, to the same bytes.
#include <unistd.h>
#include <CLI/CLI.hpp>

#include <chrono>
#include <cstdio>
#include <thread>

#include "analysis/ensemble_runner.h"
#include "apps/cli.h"
#include "apps/commands.h"
#include "apps/ensemble_cli.h"
#include "apps/exit_code.h"
#include "apps/progress.h"
#include "io/atomic_file.h"
#include "io/output_dir.h"
#include "sim/error.h"
#include "sim/stop.h"

namespace gs::app {
namespace {

namespace fs = std::filesystem;

struct EnsembleOptions {
  PhysicsConfig physics;
  long long realisations = 8;
  int threads = std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
  std::string out = "grainshock-ensemble";
  bool force = false, quiet = false, per_realisation = false;
  int per_decade = 20, bins = 60, resamples = 1000;
  std::vector<double> snapshot_times, window;
};

// Runs what the folder's job still lacks (all of it for a new folder) and writes the results.
int run_job(const fs::path& dir, const EnsembleJob& job, int threads, bool quiet, Ranks& ranks) {
  const fs::path rdir = dir / "realisations";
  const auto held = finished_realisations(rdir, job.spec).size();
  const std::uint64_t to_run = job.spec.realisations - held;
  if (!quiet && held > 0)
    std::fprintf(stderr, "grainshock: resuming %s: %zu of %llu realisations finished before\n",
                 dir.c_str(), held, static_cast<unsigned long long>(job.spec.realisations));
  if (!quiet && std::uint64_t(ranks.size()) > to_run)
    std::fprintf(stderr, "grainshock: %d ranks for %llu realisations to run: ranks %llu-%d idle\n",
                 ranks.size(), static_cast<unsigned long long>(to_run),
                 static_cast<unsigned long long>(to_run), ranks.size() - 1);

  install_stop_handlers();
  Progress progress(quiet);
  RunnerOptions ro;
  ro.threads = threads;
  ro.realisations_dir = rdir;
  ro.ranks = &ranks;
  ro.on_progress = [&](std::uint64_t done, std::uint64_t total) {
    progress.update(double(done) / double(total), std::to_string(held + done) + " of " +
                                                      std::to_string(job.spec.realisations) +
                                                      " realisations");
  };
  const auto t0 = std::chrono::steady_clock::now();
  RunnerResult r = run_ensemble(job.spec, ro);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  progress.done();
  if (r.sums.count() == 0)
    throw UserError("interrupted before any realisation finished (resume with: grainshock resume " +
                    dir.string() + ")");
  const RunTiming timing{wall, threads, ranks.size(), r.sums.count() - r.resumed};
  const EnsembleFits fits = write_ensemble_folder(dir, r.sums, job, timing);
  if (!r.interrupted && !job.keep_realisations) {
    // Renamed first, so that a kill while deleting cannot leave a folder that looks unfinished.
    const fs::path gone = dir / (".realisations.tmp." + std::to_string(::getpid()));
    std::error_code ec;
    fs::rename(rdir, gone, ec);
    if (!ec) fs::remove_all(gone, ec);
  }
  std::fputs(exponent_table(r.sums, fits).c_str(), stdout);
  std::fflush(stdout);
  if (!quiet)
    std::fprintf(stderr,
                 "grainshock: %s %llu of %llu realisations (%llu run now, in %.3g s on %s%d "
                 "threads); results in %s\n",
                 r.interrupted ? "interrupted with" : "finished",
                 static_cast<unsigned long long>(r.sums.count()),
                 static_cast<unsigned long long>(job.spec.realisations),
                 static_cast<unsigned long long>(timing.realisations), wall,
                 ranks.size() > 1 ? (std::to_string(ranks.size()) + " ranks x ").c_str() : "",
                 threads, dir.c_str());
  return r.interrupted ? kExitInterrupted : 0;
}

int run(const EnsembleOptions& o) {
  Ranks& ranks = Ranks::world();
  if (ranks.rank() != 0) return serve_ensemble(ranks);
  // Every check before the output folder is touched: bad input leaves nothing behind.
  if (o.realisations < 1) throw UserError("--realisations must be at least 1");
  if (o.threads < 1) throw UserError("--threads must be at least 1");
  EnsembleJob job;
  job.spec.physics = o.physics;
  job.spec.realisations = static_cast<std::uint64_t>(o.realisations);
  job.spec.per_decade = o.per_decade;
  job.spec.bins = o.bins;
  job.spec.snapshot_times = o.snapshot_times;
  job.spec = checked(job.spec);
  job.fit = fit_options(o.resamples, o.window, job.spec);
  job.keep_realisations = o.per_realisation;

  const fs::path dir(o.out);
  const bool resume = !o.force && holds_unfinished_ensemble(dir);
  if (resume && job_toml(read_job(dir / "ensemble.toml")) != job_toml(job))
    throw UserError("--out " + o.out +
                    ": holds an unfinished ensemble of other settings (its ensemble.toml); "
                    "resume it with: grainshock resume " +
                    o.out + ", or use --force to start again");
  if (!resume) prepare_output_dir(o.out, o.force);
  // A second process on the folder (a requeued job, a repeated command) is refused instead of
  // running the same realisations; the kernel drops the lock even on kill -9.
  lock_output_dir(dir);
  if (!resume) {
    std::error_code ec;
    fs::remove_all(dir / "realisations", ec);  // --force starts again
    write_file_atomic(dir / "ensemble.toml", job_toml(job));
  }
  return run_job(dir, job, o.threads, o.quiet, ranks);
}

}  // namespace

bool holds_unfinished_ensemble(const fs::path& dir) {
  std::error_code ec;
  if (!fs::is_regular_file(dir / "ensemble.toml", ec)) return false;
  // Killed before the results were written (ensemble.toml is written before anything runs).
  if (!fs::exists(dir / "summary.json", ec)) return true;
  // Finished without --per-realisation (realisations/ is removed then), or merged.
  if (!fs::is_directory(dir / "realisations", ec)) return false;
  // Interrupted (SIGINT, SIGTERM) with the results of the realisations finished by then.
  const EnsembleSpec spec = read_job(dir / "ensemble.toml").spec;
  return finished_realisations(dir / "realisations", spec).size() < spec.realisations;
}

int resume_ensemble(const fs::path& dir, int threads, bool quiet) {
  Ranks& ranks = Ranks::world();
  if (ranks.rank() != 0) return serve_ensemble(ranks);
  if (threads < 1) throw UserError("--threads must be at least 1");
  std::error_code ec;
  if (!fs::is_regular_file(dir / "ensemble.toml", ec))
    throw UserError(dir.string() + ": not an ensemble folder (no ensemble.toml)");
  if (!holds_unfinished_ensemble(dir))
    throw UserError(dir.string() + ": the ensemble is finished (nothing to resume)");
  const EnsembleJob job = read_job(dir / "ensemble.toml");
  lock_output_dir(dir);
  return run_job(dir, job, threads, quiet, ranks);
}

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
                  "Worker threads K per process (results do not depend on it)")
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
  add_fit_options(*sub, opt->resamples, opt->window);
  sub->add_flag("--per-realisation", opt->per_realisation,
                "Keep OUT/realisations/ once finished (input of grainshock merge); it is always "
                "written while the ensemble runs, so that a killed one resumes");
  sub->footer(
      "The table of exponents goes to stdout (also with --quiet). Each realisation is written "
      "into OUT/realisations/ as it finishes: the same command into a folder holding an "
      "unfinished ensemble (killed or interrupted) runs only the missing realisations, with the "
      "same bytes as an uninterrupted run. Under mpirun -n K the realisations are split over K "
      "ranks of --threads each; rank 0 writes and prints. Results do not depend on K, --threads "
      "or resumes.");
  sub->callback([opt] {
    const int rc = run(*opt);
    if (rc != 0) throw Exit{rc};
  });
}

}  // namespace gs::app
