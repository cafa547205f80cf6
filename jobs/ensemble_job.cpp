#include "jobs/ensemble_job.h"
#include "jobs/view_job.h"

#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>

#include "analysis/ensemble_ranks.h"
#include "analysis/ensemble_runner.h"
#include "analysis/json.h"
#include "io/atomic_file.h"
#include "io/output_dir.h"
#include "sim/error.h"
#include "sim/stop.h"

namespace gs::jobs {
namespace {

namespace fs = std::filesystem;

// What a rank other than 0 ends with: the exit code rank 0 gives it.
EnsembleResult served(Ranks& ranks) {
  EnsembleResult r;
  r.served = serve_ensemble(ranks);
  return r;
}

// Runs what the folder's job still lacks (all of it for a new folder) and writes the results.
EnsembleResult run_job(const fs::path& dir, const EnsembleJob& job, int threads, bool quiet,
                       const ProgressFactory& progress_factory, const MessageSink& messages,
                       Ranks& ranks) {
  const fs::path rdir = dir / "realisations";
  const auto held = finished_realisations(rdir, job.spec).size();
  const std::uint64_t to_run = job.spec.realisations - held;
  if (!quiet && held > 0)
    tell(messages, MessageKind::Note,
         "resuming " + dir.string() + ": " + std::to_string(held) + " of " +
             std::to_string(job.spec.realisations) + " realisations finished before");
  if (!quiet && std::uint64_t(ranks.size()) > to_run)
    tell(messages, MessageKind::Note,
         std::to_string(ranks.size()) + " ranks for " + std::to_string(to_run) +
             " realisations to run: ranks " + std::to_string(to_run) + "-" +
             std::to_string(ranks.size() - 1) + " idle");

  install_stop_handlers();
  const auto progress_line = open_progress(progress_factory);
  ProgressLine& progress = *progress_line;
  RunnerOptions ro;
  ro.threads = threads;
  ro.realisations_dir = rdir;
  ro.checkpoint_interval = 60 * job.checkpoint_minutes;
  ro.ranks = &ranks;
  ro.on_warning = [&messages](const std::string& what) {
    tell(messages, MessageKind::Warning, what);
  };
  ro.on_progress = [&](std::uint64_t done, std::uint64_t total) {
    progress.update(double(done) / double(total), std::to_string(held + done) + " of " +
                                                      std::to_string(job.spec.realisations) +
                                                      " realisations");
  };
  const auto t0 = std::chrono::steady_clock::now();
  RunnerResult r = run_ensemble(job.spec, ro);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  progress.done();
  if (r.sums.count() == 0) {
    // Stopped before a realisation finished: nothing to average yet, but a stop all the same
    // (exit 130); the folder resumes from the states in flight.
    GS_CHECK(r.interrupted);
    if (!quiet)
      tell(messages, MessageKind::Note,
           "interrupted before any realisation finished (continue with: grainshock resume " +
               dir.string() + ")");
    EnsembleResult stopped;
    stopped.interrupted = true;
    return stopped;
  }
  const EnsembleTiming timing{wall, threads, ranks.size(), r.sums.count() - r.resumed};
  const EnsembleFits fits = write_ensemble_folder(dir, r.sums, job, timing);
  if (!r.interrupted && !job.keep_realisations) {
    // Renamed first, so that a kill while deleting cannot leave a folder that looks unfinished.
    const fs::path gone = dir / (".realisations.tmp." + std::to_string(::getpid()));
    std::error_code ec;
    fs::rename(rdir, gone, ec);
    if (!ec) fs::remove_all(gone, ec);
  }
  if (!quiet) {
    char line[200];
    std::snprintf(line, sizeof line,
                  "%s %llu of %llu realisations (%llu run now, in %.3g s on %s%d threads); "
                  "results in ",
                  r.interrupted ? "interrupted with" : "finished",
                  static_cast<unsigned long long>(r.sums.count()),
                  static_cast<unsigned long long>(job.spec.realisations),
                  static_cast<unsigned long long>(timing.realisations), wall,
                  ranks.size() > 1 ? (std::to_string(ranks.size()) + " ranks x ").c_str() : "",
                  threads);
    tell(messages, MessageKind::Note, line + dir.string());
  }
  return {.interrupted = r.interrupted, .exponent_table = exponent_table(r.sums, fits)};
}

}  // namespace

double checked_checkpoint_minutes(double minutes) {
  if (!(minutes >= 0) || !std::isfinite(minutes))
    throw UsageError("--checkpoint-every must be a number of seconds >= 0 (0: never)");
  return minutes;
}

FitOptions fit_options(int resamples, const std::vector<double>& window, const EnsembleSpec& spec) {
  FitOptions fit;
  fit.resamples = resamples;
  if (!window.empty()) {
    if (window.size() != 2) throw UsageError("--window needs two times T1,T2");
    fit.window = Window{window[0], window[1]};
  }
  check_fit_options(spec, fit);
  return fit;
}

EnsembleResult run_ensemble_job(const EnsembleOptions& o) {
  Ranks& ranks = Ranks::world();
  if (ranks.rank() != 0) return served(ranks);
  // Every check before the output folder is touched: bad input leaves nothing behind.
  if (o.realisations < 1) throw UsageError("--realisations must be at least 1");
  check_threads(o.threads);
  EnsembleJob job;
  job.spec.physics = o.physics;
  job.spec.realisations = static_cast<std::uint64_t>(o.realisations);
  job.spec.per_decade = o.per_decade;
  job.spec.bins = o.bins;
  job.spec.snapshot_times = o.snapshot_times;
  job.spec = checked(job.spec);
  job.fit = fit_options(o.resamples, o.window, job.spec);
  job.keep_realisations = o.per_realisation;
  job.checkpoint_minutes = checked_checkpoint_minutes(o.checkpoint_minutes);

  const fs::path dir(o.out);
  const bool resume = !o.force && holds_unfinished_ensemble(dir);
  EnsembleJob held = resume ? read_job(dir / "ensemble.toml") : job;
  held.checkpoint_minutes = job.checkpoint_minutes;  // how often it writes, not what it holds
  if (job_toml(held) != job_toml(job))
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
  }
  write_file_atomic(dir / "ensemble.toml", job_toml(job));
  EnsembleResult r = run_job(dir, job, o.threads, o.quiet, o.progress, o.messages, ranks);
  if (o.page && !r.interrupted) write_folder_page(dir.string(), "index.html", o.messages);
  return r;
}

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

EnsembleResult resume_ensemble(const fs::path& dir, int threads, bool quiet,
                               const ProgressFactory& progress, const MessageSink& messages) {
  Ranks& ranks = Ranks::world();
  if (ranks.rank() != 0) return served(ranks);
  check_threads(threads);
  std::error_code ec;
  if (!fs::is_regular_file(dir / "ensemble.toml", ec))
    throw UserError(dir.string() + ": not an ensemble folder (no ensemble.toml)");
  if (!holds_unfinished_ensemble(dir))
    throw UserError(dir.string() + ": the ensemble is finished (nothing to resume)");
  const EnsembleJob job = read_job(dir / "ensemble.toml");
  lock_output_dir(dir);
  return run_job(dir, job, threads, quiet, progress, messages, ranks);
}

EnsembleFits write_ensemble_folder(const std::filesystem::path& dir, const EnsembleSums& sums,
                                   const EnsembleJob& job, const EnsembleTiming& t) {
  const EnsembleFits fits = fit_ensemble(sums, job.fit);
  write_file_atomic(dir / "ensemble.toml", job_toml(job));
  write_ensemble_outputs(dir, sums, fits);
  Json j;
  j["wall_seconds"] = t.wall_seconds;
  j["threads"] = t.threads;
  j["ranks"] = t.ranks;
  j["realisations_run"] = t.realisations;
  // null when nothing was run (a merge, a resume that found every realisation finished).
  j["wall_seconds_per_realisation"] =
      t.realisations > 0 ? t.wall_seconds / double(t.realisations) : std::nan("");
  write_file_atomic(dir / "timing.json", json_text(j));
  return fits;
}

EnsembleFits write_ensemble_folder(const std::filesystem::path& dir, const EnsembleSums& sums,
                                   const FitOptions& fit, double wall_seconds, int threads,
                                   std::uint64_t realisations_run) {
  return write_ensemble_folder(dir, sums, EnsembleJob{held_spec(sums), fit},
                               EnsembleTiming{wall_seconds, threads, 1, realisations_run});
}

}  // namespace gs::jobs
