#include "jobs/run_job.h"
#include "jobs/view_job.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <future>
#include <iterator>
#include <optional>
#include <sstream>
#include <string_view>
#include <vector>

#include "analysis/json.h"
#include "analysis/paper.h"
#include "io/atomic_file.h"
#include "io/output_dir.h"
#include "io/snapshot_file.h"
#include "io/trajectory.h"
#include "jobs/movie.h"
#include "jobs/progress.h"
#include "render/field.h"
#include "render/png.h"
#include "render/renderer.h"
#include "sim/error.h"
#include "sim/format.h"
#include "sim/stop.h"

namespace gs::jobs {
namespace {

namespace fs = std::filesystem;

// What a run writes; --force clears these (and nothing else) before a new run.
constexpr const char* kRunOutputs[] = {"run.toml",    "timeseries.csv", "summary.json",
                                       "timing.json", "checkpoint.bin", "checkpoint.prev.bin",
                                       "movie.mp4",   "movie.parts",    "snapshots",
                                       "frames",      "index.html"};

// The stages of a job, kept in checkpoints: a resume redoes the unfinished ones. A movie drawn
// during sampling is in place at kMovieMade; one made after it (a resumed run's) is not.
enum Stage : std::uint32_t { kSampling = 0, kAfterSampling = 1, kMovieMade = 2 };

std::string times_toml(const std::vector<double>& times) {
  std::string s = "[";
  for (std::size_t k = 0; k < times.size(); ++k) s += (k ? ", " : "") + format_double(times[k]);
  return s + "]";
}

std::string summary_json(const RunOptions& o, const Simulation& sim, bool interrupted) {
  const PhysicsConfig& p = o.plan.physics;
  const auto& st = sim.stats();
  const Sample s = sim.sample();
  Json j;
  j["version"] = GRAINSHOCK_VERSION;
  j.update(physics_json(p));
  j["realisation"] = p.realisation;
  j["initial"] = to_string(p.initial);
  j["t_end"] = sim.time();
  j["t_end_paper"] = p.paper_time(sim.time());
  j["interrupted"] = interrupted;
  j["events"] = st.events;
  j["collisions"] = st.collisions;
  j["inelastic_collisions"] = st.inelastic;
  j["cell_crossings"] = st.crossings;
  j["stale_events"] = st.stale;
  j["overlaps"] = st.overlaps;
  j["max_overlap"] = st.max_overlap;
  j["active"] = s.active;
  if (p.unbounded()) j["particles_made"] = sim.particle_count();
  j["energy"] = s.energy;
  j["radius_rms"] = s.radius_rms;
  j["speed_rms"] = s.speed_rms;
  return json_text(j);
}

// Wall times, apart from summary.json so that it is the same file on every run.
// `movie_s`: the wall time the movie took while the run went on, beside the engine's.
std::string timing_json(const RunTiming& t, double after_s, double movie_s, const Simulation& sim) {
  const double collisions = static_cast<double>(sim.stats().collisions);
  Json j;
  j["setup_seconds"] = t.setup;
  j["run_seconds"] = t.run;
  j["snapshot_seconds"] = t.snapshots;
  j["checkpoint_seconds"] = t.checkpoints;
  j["checkpoints"] = t.checkpoints_written;
  j["pictures_and_movie_seconds"] = after_s + movie_s;
  j["movie_during_run_seconds"] = movie_s;
  j["collisions_per_second"] = t.run > 0 ? collisions / t.run : 0.0;
  return json_text(j);
}

// One colour range for all pictures of a run, so that a colour means one value in every frame:
// the field's fixed range, else the union of the frames' robust (1st-99th percentile) ranges.
std::pair<double, double> common_range(const std::vector<Snapshot>& snaps,
                                       const render::Style& style) {
  if (snaps.empty()) return {0.0, 1.0};
  if (const auto fixed = render::default_range(style.field, snaps.front().info.dim)) return *fixed;
  double lo = INFINITY, hi = -INFINITY;
  for (const auto& s : snaps) {
    if (std::find(s.active.begin(), s.active.end(), 1) == s.active.end()) continue;
    const auto r = render::auto_range(render::field_values(s, style.field), s.active, style.scale,
                                      style.percentile_low, style.percentile_high);
    lo = std::min(lo, r.first);
    hi = std::max(hi, r.second);
  }
  if (!(lo < hi)) return {0.0, 1.0};
  return {lo, hi};
}

std::string png_name(const std::string& stem, double t) {
  return stem + time_stem(t) + ".png";
}

// The style of a run's pictures: scaled speed for a kick, with the profile across the band.
render::Style picture_style(const PhysicsConfig& c) {
  render::Style style;
  style.field = c.initial == Initial::Kick ? render::Field::ScaledSpeed : render::Field::Speed;
  style.scale = render::parse_scale("auto", style.field);
  style.inset = true;
  return style;
}

render::View picture_view(const RunOptions& o) {
  render::View view;
  view.width = o.width;
  view.height = o.height;
  if (o.plan.physics.dim == 3) view.slab = 6;  // a cut through the shell shows the band itself
  return view;
}

// Fig. 1-style pictures: each snapshot coloured on a shared scale, and (with two or more) the
// overlay of all times, one colour per time, as in Fig. 1(a). They are drawn from the snapshot
// files, so that a resumed run draws the same pictures. False if stopped.
bool write_pictures(const fs::path& dir, const RunOptions& o) {
  fs::create_directories(dir / "frames");
  std::vector<Snapshot> snaps;
  for (double t : snapshot_times(o.plan))
    snaps.push_back(
        read_snapshot((dir / "snapshots" / snapshot_name(t, o.plan.snapshots.format)).string()));
  render::Renderer renderer;
  render::Style style = picture_style(o.plan.physics);
  style.range = common_range(snaps, style);
  const render::View view = picture_view(o);
  for (const auto& s : snaps) {
    if (stop_requested()) return false;
    const render::Image img = renderer.render(s, style, view);
    render::write_png((dir / "frames" / png_name("", s.info.time)).string(), img,
                      render::png_text({&s}, renderer.last().disc_radius_px));
  }
  if (snaps.size() < 2 || stop_requested()) return !stop_requested();
  std::vector<const Snapshot*> all;
  for (const auto& s : snaps) all.push_back(&s);
  const render::Image img = renderer.render(all, style, view);
  render::PngText text = render::png_text(snaps.back().info, snaps.back().size());
  render::add_disc_radius(text, renderer.last().disc_radius_px);
  render::write_png((dir / "frames" / "overlay.png").string(), img, text);
  return true;
}

// Fig. 1(b): the same gas, kicked the same way, with elastic collisions, at half the final time.
// Nothing if stopped, or `abandoned` (the job ended by an error).
std::optional<Snapshot> run_elastic_comparison(const RunOptions& o,
                                               const std::atomic<bool>& abandoned) {
  PhysicsConfig c = o.plan.physics;
  c.restitution = 1.0;
  c.t_max = 0.5 * o.plan.physics.t_max;
  if (!o.quiet) {
    char line[64];
    std::snprintf(line, sizeof line, "elastic comparison (r = 1) to t = %g", c.t_max);
    tell(o.messages, MessageKind::Note, line);
  }
  try {
    auto sim = make_simulation(c);
    while (sim->time() < c.t_max) {
      sim->run_until(std::min(c.t_max, sim->time() + std::max(1.0, 0.01 * sim->time())));
      if (stop_requested() || abandoned) return std::nullopt;
    }
    return sim->snapshot();
  } catch (const UserError& e) {
    // Its own failure, not the main run's: an elastic front outruns the inelastic one and may
    // need more of the unbounded medium's --particles.
    throw UserError("the elastic comparison of --compare-elastic (r = 1, to t = " +
                    format_number(c.t_max) + "): " + e.what());
  }
}

void write_elastic_comparison(const fs::path& dir, const RunOptions& o, const Snapshot& s) {
  write_snapshot(
      (dir / "snapshots" / ("elastic_" + snapshot_name(s.info.time, o.plan.snapshots.format)))
          .string(),
      s, o.plan.snapshots);
  fs::create_directories(dir / "frames");
  render::Renderer renderer;
  const render::Image img = renderer.render(s, picture_style(o.plan.physics), picture_view(o));
  render::write_png((dir / "frames" / png_name("elastic_", s.info.time)).string(), img,
                    render::png_text({&s}, renderer.last().disc_radius_px));
}

// Every snapshot time in one file, read back from the snapshot files (so that a resumed run
// writes the same trajectory).
void write_trajectory(const fs::path& dir, const RunOptions& o) {
  const auto out = open_trajectory((dir / o.trajectory).string(), trajectory_format(o.trajectory));
  for (double t : snapshot_times(o.plan))
    out->add(
        read_snapshot((dir / "snapshots" / snapshot_name(t, o.plan.snapshots.format)).string()));
  out->finish();
}

// The names a run writes in its folder (kRunOutputs and its trajectory).
std::vector<const char*> run_outputs(const RunOptions& o) {
  std::vector<const char*> names(std::begin(kRunOutputs), std::end(kRunOutputs));
  if (!o.trajectory.empty()) names.push_back(o.trajectory.c_str());
  return names;
}

// Removes what a run wrote in `dir` but its run.toml.
void clear_run_outputs(const fs::path& dir, const RunOptions& o) {
  for (const char* name : run_outputs(o)) {
    if (std::string_view(name) == "run.toml") continue;
    std::error_code ec;
    fs::remove_all(dir / name, ec);
    if (ec) throw UserError("cannot remove '" + (dir / name).string() + "': " + ec.message());
  }
}

bool finished_run(const fs::path& dir) {
  std::ifstream f(dir / "summary.json");
  const Json j = Json::parse(f, nullptr, /*allow_exceptions=*/false);  // absent or cut: not done
  return j.is_object() && j.contains("interrupted") && j["interrupted"] == false;
}

}  // namespace

void use_fig1_job(RunOptions& o) {
  const double to_sim = 1 / o.plan.physics.paper_time(1.0);
  o.plan.physics.t_max = std::end(kFig1aPaperTimes)[-1] * to_sim;
  o.plan.snapshot_times.clear();
  for (double t : kFig1aPaperTimes) o.plan.snapshot_times.push_back(t * to_sim);
  o.png = o.compare_elastic = o.movie = o.movie_inset = true;
}

namespace {

// run.toml around the physics lines given. Unlike the files of `movie` and `figures`, which
// apps/cli.cpp writes from the flags typed, run.toml states the run's effective settings (the
// Fig. 1 rule fills in t-max, the snapshots and the pictures), and its text is also the spec a
// run's checkpoints hold (run_spec), whose bytes must not change or old checkpoints would be
// refused; CliRunFile.EveryFlagRoundTrips keeps it holding every flag of `run`.
std::string settings_toml(const RunOptions& o, const std::string& physics) {
  std::ostringstream t;
  t << "# grainshock run: every setting that shapes the results.\n"
    << "# Again: grainshock run --config run.toml --out NEW; continue: grainshock resume DIR\n"
    << physics << "per-decade = " << o.plan.per_decade << "\n"
    << "sample-every = " << format_double(o.plan.sample_every) << "\n"
    << "snapshot-format = \"" << to_string(o.plan.snapshots.format) << "\"\n"
    << "snapshot-particles = \"" << (o.plan.snapshots.active_only ? "active" : "all") << "\"\n"
    << "snapshot-times = " << times_toml(o.plan.snapshot_times) << "\n"
    << "png = " << (o.png ? "true" : "false") << "\n"
    << "compare-elastic = " << (o.compare_elastic ? "true" : "false") << "\n"
    << "movie = " << (o.movie ? "true" : "false") << "\n"
    << "movie-inset = " << (o.movie_inset ? "true" : "false") << "\n"
    << "width = " << o.width << "\n"
    << "height = " << o.height << "\n"
    << "trajectory = \"" << o.trajectory << "\"\n";
  return t.str();
}

}  // namespace

std::string run_toml(const RunOptions& o) {
  return settings_toml(o, physics_toml(o.plan.physics));
}

std::string run_spec(const RunOptions& o) {
  return settings_toml(o, to_toml(o.plan.physics));
}

namespace {

// The checks made before anything is written: the plan, the trajectory, the picture size and
// the movie. Returns the movie's options.
FrontMovieOptions check_run(const RunOptions& o) {
  check_plan(o.plan, o.png ? static_cast<int>(snapshot_times(o.plan).size()) : 1);
  if (!o.trajectory.empty() && snapshot_times(o.plan).empty())
    throw UsageError("--trajectory '" + o.trajectory +
                     "' needs snapshot times (--snapshot-times)");
  if (o.movie_inset && !o.movie)
    throw UsageError("--movie-inset draws the inset in the movie of --movie; give both or neither");
  if (o.png || o.compare_elastic) render::check_size(o.width, o.height);
  FrontMovieOptions movie;
  movie.quiet = o.quiet;
  movie.progress = o.progress;
  movie.messages = o.messages;
  movie.inset = o.movie_inset;
  if (o.movie) check_front_movie(o.plan.physics, movie);
  return movie;
}

// A run's folder and its loop; no loop: nothing to do. `from_start`: the loop starts at
// t = 0 (a new run, or a resumed one that had no checkpoint yet).
struct OpenRun {
  fs::path dir;
  std::unique_ptr<RunLoop> loop;
  bool from_start = true;
};

// A new run's folder (locked), cleared of an earlier run's files (with --force), with its
// run.toml.
OpenRun start_run(const RunOptions& o, const std::string& spec) {
  const fs::path dir = prepare_output_dir(o.out, o.force, run_outputs(o));
  remove_leftovers(dir);
  write_file_atomic(dir / "run.toml", run_toml(o));
  return {dir, std::make_unique<RunLoop>(o.plan, dir, spec)};
}

// A stopped run's loop from its checkpoint; none if the run had finished (its leftover
// checkpoints are removed).
OpenRun resume_run(const RunOptions& o, const std::string& spec) {
  const fs::path dir = o.out;
  if (finished_run(dir)) {
    // summary.json is a run's last result: a kill after it, before the checkpoints were
    // removed, leaves a finished run with checkpoints, which only need removing.
    if (!fs::exists(RunLoop::checkpoint_path(dir)) &&
        !fs::exists(RunLoop::previous_checkpoint_path(dir)))
      // (std::string("'").append: GCC 12 -Wrestrict misfires on "'" + a string here)
      throw UserError(std::string("'").append(dir.string()) +
                      "' holds a finished run (summary.json): nothing to resume");
    lock_output_dir(dir);
    fs::remove(RunLoop::checkpoint_path(dir));
    fs::remove(RunLoop::previous_checkpoint_path(dir));
    if (!o.quiet)
      tell(o.messages, MessageKind::Note,
           dir.string() + " had finished; its leftover checkpoints are removed");
    return {dir, nullptr};
  }
  lock_output_dir(dir);
  if (!fs::exists(RunLoop::checkpoint_path(dir)) &&
      !fs::exists(RunLoop::previous_checkpoint_path(dir))) {
    // Killed before its first checkpoint (in its set-up): nothing it wrote can be gone on
    // from, and its run.toml is all a run needs, so it starts again from t = 0 and ends with
    // the bytes of a run never stopped.
    clear_run_outputs(dir, o);
    remove_leftovers(dir);
    if (!o.quiet)
      tell(o.messages, MessageKind::Note,
           dir.string() +
               " holds no checkpoint (stopped during its set-up): the run starts again from t = 0");
    return {dir, std::make_unique<RunLoop>(o.plan, dir, spec)};
  }
  auto loop = RunLoop::resume(o.plan, dir, spec);
  remove_leftovers(dir);
  // The snapshot a stop wrote of its moment is not one of the run's.
  const double t = loop->simulation().time();
  const auto scheduled = snapshot_times(o.plan);
  if (std::none_of(scheduled.begin(), scheduled.end(), [&](double s) { return s == t; }))
    fs::remove(dir / "snapshots" / snapshot_name(t, o.plan.snapshots.format));
  return {dir, std::move(loop), false};
}

// Sampling while the movie is drawn at the frame times between the samples. Sets `movie_s`
// to the wall time the movie took beside the engine's. False if stopped.
bool sample_with_movie(RunLoop& loop, const fs::path& dir, const RunOptions& o,
                       const FrontMovieOptions& movie, double& movie_s) {
  if (!o.quiet) tell(o.messages, MessageKind::Note, "the run, drawing the movie of the front");
  const RunTiming before = loop.timing();
  const auto t1 = std::chrono::steady_clock::now();
  bool stopped = write_run_movie(loop, o.plan.physics, movie, dir).stopped;
  const RunTiming& after = loop.timing();
  movie_s = seconds_since(t1) - (after.run - before.run) - (after.snapshots - before.snapshots) -
            (after.checkpoints - before.checkpoints);
  if (!stopped) stopped = !loop.run();  // the frames end at t-max: its sample, if any
  if (!stopped) loop.set_stage(kMovieMade);
  return !stopped;
}

// Sampling with a progress line. False if stopped.
bool sample_with_progress(RunLoop& loop, const RunOptions& o) {
  const double t_max = o.plan.physics.t_max;
  const auto progress_line = open_progress(o.progress);
  ProgressLine& progress = *progress_line;
  const auto t1 = std::chrono::steady_clock::now();
  const auto events0 = loop.simulation().stats().events;
  loop.on_sample = [&](const Sample& s) {
    char what[160];
    std::snprintf(what, sizeof what, "t = %.4g of %.4g, %lld active, %.3g events/s", s.t, t_max,
                  static_cast<long long>(s.active),
                  static_cast<double>(s.events - events0) / std::max(1e-9, seconds_since(t1)));
    progress.update(s.t / t_max, what);
  };
  const bool stopped = !loop.run();
  progress.done();
  if (!stopped) loop.set_stage(kAfterSampling);
  return !stopped;
}

// The sampling stage, if the run is in it. A new run draws its movie as it goes; a resumed one
// has passed frames already, and replays the run for its movie after sampling. A stop writes
// a snapshot of its moment (a look at the data may want it; a resume removes it). False if
// stopped.
bool sample(RunLoop& loop, const fs::path& dir, const RunOptions& o, bool from_start,
            const FrontMovieOptions& movie, double& movie_s) {
  if (loop.stage() != kSampling) return true;
  const bool done = o.movie && from_start && movie_in_one_pass(o.plan.physics, movie)
                        ? sample_with_movie(loop, dir, o, movie, movie_s)
                        : sample_with_progress(loop, o);
  if (!done) {
    loop.write_run_snapshot(loop.simulation().time());
  } else {
    loop.write_checkpoint();
  }
  return done;
}

// What comes after sampling: the trajectory, the pictures, the movie (unless drawn during
// sampling) and the elastic comparison once its run ends. False if stopped.
bool after_sampling(const RunLoop& loop, const fs::path& dir, const RunOptions& o,
                    const FrontMovieOptions& movie, std::future<std::optional<Snapshot>>& elastic,
                    bool stopped) {
  // A stop while a file is read (io/) or a simulation set up throws Stopped: the run is then
  // stopped as anywhere else, its summary written.
  try {
    if (!stopped && !o.trajectory.empty()) write_trajectory(dir, o);
    if (!stopped && o.png) stopped = !write_pictures(dir, o);
    if (!stopped && o.movie && loop.stage() != kMovieMade) {
      // Runs are reproducible from (config, seed): the movie replays this very trajectory.
      if (!o.quiet) tell(o.messages, MessageKind::Note, "movie of the front");
      stopped = write_front_movie(o.plan.physics, movie, dir).stopped;
    }
  } catch (const Stopped&) {
    stopped = true;
  }
  if (elastic.valid()) {
    std::optional<Snapshot> s;
    try {
      s = elastic.get();
    } catch (const Stopped&) {  // in the comparison's set-up
    }
    if (!s)
      stopped = true;
    else if (!stopped)
      write_elastic_comparison(dir, o, *s);
  }
  return !stopped;
}

// timing.json, then summary.json (the last result); the checkpoints go once the run is whole.
void finish_run(RunLoop& loop, const fs::path& dir, const RunOptions& o, double after_s,
                double movie_s, bool stopped) {
  loop.finish_checkpoint();  // a run stopped in its pictures resumes from it
  const Simulation& sim = loop.simulation();
  if (!stopped && o.page) write_folder_page(dir.string(), "index.html", o.messages);  // before summary.json
  write_file_atomic(dir / "timing.json", timing_json(loop.timing(), after_s, movie_s, sim));
  write_file_atomic(dir / "summary.json", summary_json(o, sim, stopped));
  if (!stopped) loop.remove_checkpoints();
  if (o.quiet) return;
  char line[160];
  std::snprintf(line, sizeof line, "%s %s: %lld collisions in %.3g s; results in ",
                stopped ? "interrupted" : "finished", to_string(o.plan.physics.initial),
                static_cast<long long>(sim.stats().collisions), loop.timing().run);
  tell(o.messages, MessageKind::Note,
       line + dir.string() +
           (stopped ? " (continue with: grainshock resume " + dir.string() + ")" : ""));
}

}  // namespace

RunResult run_job(const RunOptions& o, bool resume) {
  const FrontMovieOptions movie = check_run(o);
  const std::string spec = run_spec(o);
  // Before the set-up, so that Ctrl-C during it stops the run at its first checkpoint.
  install_stop_handlers();
  const auto [dir, loop, from_start] = resume ? resume_run(o, spec) : start_run(o, spec);
  if (!loop) return {};
  loop->checkpoint_every = o.checkpoint_every;

  // The elastic run needs nothing of this one: it takes the second core from the start, while
  // this one samples, draws its movie and its pictures. It polls the same stop flag.
  // An error in this one abandons it: `abandon` goes before the future, whose end waits for it.
  std::atomic<bool> abandoned = false;
  std::future<std::optional<Snapshot>> elastic;
  struct Abandon {
    std::atomic<bool>& flag;
    ~Abandon() { flag = true; }
  } abandon{abandoned};
  if (o.compare_elastic)
    elastic =
        std::async(std::launch::async, run_elastic_comparison, std::cref(o), std::cref(abandoned));
  double movie_s = 0;
  bool stopped = !sample(*loop, dir, o, from_start, movie, movie_s);
  const auto t2 = std::chrono::steady_clock::now();
  stopped = !after_sampling(*loop, dir, o, movie, elastic, stopped);
  finish_run(*loop, dir, o, seconds_since(t2), movie_s, stopped);
  return {.stopped = stopped};
}

}  // namespace gs::jobs
