// `grainshock run`: one realisation into a run folder.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "analysis/json.h"
#include "apps/cli.h"
#include "apps/commands.h"
#include "apps/exit_code.h"
#include "apps/front_movie.h"
#include "apps/progress.h"
#include "render/field.h"
#include "render/png.h"
#include "render/renderer.h"
#include "sim/config.h"
#include "sim/engine.h"
#include "sim/error.h"
#include "sim/format.h"
#include "sim/recorder.h"
#include "sim/stop.h"
#include "sim/xyz.h"

namespace gs::app {
namespace {

struct RunOptions {
  PhysicsConfig physics;
  std::string out = "grainshock-run";
  bool force = false;
  bool quiet = false;
  int per_decade = 20;
  double sample_every = 0;  // 0: logarithmic grid only
  std::vector<double> snapshot_times;
  bool png = false;              // a PNG of every snapshot, and the Fig. 1(a) overlay
  bool compare_elastic = false;  // the Fig. 1(b) frame: the same gas with r = 1
  bool movie = false;            // movie.mp4 of the front, as `grainshock movie` makes it
  bool movie_inset = false;      // the Fig. 1 job's movie has the profile inset
  int width = 1920, height = 1080;
};

// Fig. 1 of the paper, in its time unit 1/(v0 n^(1/d)): r = 0.1 at t = 5000, 10000, 20000 and
// 50000 (a), and r = 1 at t = 25000 (b).
constexpr double kFig1Times[] = {5000, 10000, 20000, 50000};
constexpr double kFig1ElasticTime = 25000;

// `grainshock run` with no flags: the paper's Fig. 1 job.
RunOptions demo_options() {
  RunOptions o;
  const double to_sim = 1 / o.physics.paper_time(1.0);
  o.physics.t_max = kFig1Times[3] * to_sim;
  for (double t : kFig1Times) o.snapshot_times.push_back(t * to_sim);
  o.png = true;
  o.compare_elastic = true;
  o.movie = true;
  o.movie_inset = true;
  return o;
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Whole times print as plain integers (t_100000, not t_1e+05) so that names sort and read well.
std::string time_tag(double t) {
  char buf[32];
  if (t == std::floor(t) && t < 1e15) {
    std::snprintf(buf, sizeof buf, "%.0f", t);
    return buf;
  }
  return format_number(t);
}

std::string snapshot_name(double t) {
  return "t_" + time_tag(t) + ".xyz";
}

std::string summary_json(const RunOptions& o, const Simulation& sim, double setup_s, double run_s,
                         bool interrupted) {
  const auto& st = sim.stats();
  const Sample s = sim.sample();
  std::ostringstream j;
  j << "{\n"
    << "  \"version\": \"" << GRAINSHOCK_VERSION << "\",\n"
    << "  \"dim\": " << o.physics.dim << ",\n"
    << "  \"particles\": " << o.physics.particles << ",\n"
    << "  \"density\": " << json_number(o.physics.density) << ",\n"
    << "  \"restitution\": " << json_number(o.physics.restitution) << ",\n"
    << "  \"cutoff\": " << json_number(o.physics.cutoff) << ",\n"
    << "  \"seed\": " << o.physics.seed << ",\n"
    << "  \"realisation\": " << o.physics.realisation << ",\n"
    << "  \"initial\": \"" << to_string(o.physics.initial) << "\",\n"
    << "  \"t_end\": " << json_number(sim.time()) << ",\n"
    << "  \"t_end_paper\": " << json_number(o.physics.paper_time(sim.time())) << ",\n"
    << "  \"interrupted\": " << (interrupted ? "true" : "false") << ",\n"
    << "  \"setup_seconds\": " << json_number(setup_s) << ",\n"
    << "  \"run_seconds\": " << json_number(run_s) << ",\n"
    << "  \"events\": " << st.events << ",\n"
    << "  \"collisions\": " << st.collisions << ",\n"
    << "  \"inelastic_collisions\": " << st.inelastic << ",\n"
    << "  \"cell_crossings\": " << st.crossings << ",\n"
    << "  \"stale_events\": " << st.stale << ",\n"
    << "  \"overlaps\": " << st.overlaps << ",\n"
    << "  \"max_overlap\": " << json_number(st.max_overlap) << ",\n"
    << "  \"collisions_per_second\": " << json_number(run_s > 0 ? st.collisions / run_s : 0)
    << ",\n"
    << "  \"active\": " << s.active << ",\n"
    << "  \"energy\": " << json_number(s.energy) << ",\n"
    << "  \"radius_rms\": " << json_number(s.radius_rms) << ",\n"
    << "  \"speed_rms\": " << json_number(s.speed_rms) << "\n"
    << "}\n";
  return j.str();
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
  return stem + "t_" + time_tag(t) + ".png";
}

// The style of a run's pictures: scaled speed for a kick, with the profile across the band.
render::Style picture_style(const PhysicsConfig& c) {
  render::Style style;
  style.field = c.initial == Initial::Kick ? render::Field::ScaledSpeed : render::Field::Speed;
  style.scale = render::parse_scale("auto", style.field);
  style.inset = true;
  return style;
}

// Fig. 1-style pictures: each snapshot coloured on a shared scale, and (with two or more) the
// overlay of all times, one colour per time, as in Fig. 1(a).
void write_pictures(const std::filesystem::path& dir, const std::vector<Snapshot>& snaps,
                    const RunOptions& o) {
  std::filesystem::create_directories(dir / "frames");
  render::Renderer renderer;
  render::Style style = picture_style(o.physics);
  style.range = common_range(snaps, style);
  render::View view;
  view.width = o.width;
  view.height = o.height;
  if (o.physics.dim == 3) view.slab = 6;  // a cut through the shell shows the band itself
  for (const auto& s : snaps)
    render::write_png((dir / "frames" / png_name("", s.info.time)).string(),
                      renderer.render(s, style, view), render::png_text(s.info, s.size()));
  if (snaps.size() < 2) return;
  std::vector<const Snapshot*> all;
  for (const auto& s : snaps) all.push_back(&s);
  render::write_png((dir / "frames" / "overlay.png").string(), renderer.render(all, style, view),
                    render::png_text(snaps.back().info, snaps.back().size()));
}

// Fig. 1(b): the same gas, kicked the same way, with elastic collisions, at half the final time.
void write_elastic_comparison(const std::filesystem::path& dir, const RunOptions& o) {
  PhysicsConfig c = o.physics;
  c.restitution = 1.0;
  c.t_max = 0.5 * o.physics.t_max;
  if (!o.quiet) std::fprintf(stderr, "grainshock: elastic comparison (r = 1) to t = %g\n", c.t_max);
  auto sim = make_simulation(c);
  sim->run_until(c.t_max);
  const Snapshot s = sim->snapshot();
  write_xyz((dir / "snapshots" / ("elastic_" + snapshot_name(c.t_max))).string(), s);
  render::Renderer renderer;
  const render::Style style = picture_style(c);
  render::View view;
  view.width = o.width;
  view.height = o.height;
  if (c.dim == 3) view.slab = 6;
  render::write_png((dir / "frames" / png_name("elastic_", c.t_max)).string(),
                    renderer.render(s, style, view), render::png_text(s.info, s.size()));
}

int run(const RunOptions& o) {
  validate(o.physics);
  for (double t : o.snapshot_times)
    if (!(t > 0 && t <= o.physics.t_max))
      throw UserError("--snapshot-times: " + format_number(t) + " is outside (0, t-max]");
  if (o.png || o.compare_elastic) render::check_size(o.width, o.height, 16384);
  FrontMovieOptions movie;
  movie.quiet = o.quiet;
  movie.inset = o.movie_inset;
  if (o.movie) check_front_movie(o.physics, movie);
  const auto dir = prepare_output_dir(o.out, o.force);
  std::filesystem::create_directories(dir / "snapshots");
  write_file_atomic(dir / "run.toml", to_toml(o.physics));

  const auto t0 = std::chrono::steady_clock::now();
  auto sim = make_simulation(o.physics);
  const double setup_s = seconds_since(t0);

  std::vector<double> times = log_times(0.1, o.physics.t_max, o.per_decade);
  if (o.sample_every > 0) times = merge_times(times, linear_times(o.sample_every, o.physics.t_max));
  const std::vector<double> snaps = merge_times(o.snapshot_times, {o.physics.t_max});
  times = merge_times(times, snaps);

  Recorder recorder(o.physics);
  std::ofstream csv(dir / "timeseries.csv", std::ios::trunc);
  if (!csv) throw UserError((dir / "timeseries.csv").string() + ": cannot write");
  for (std::size_t k = 0; k < recorder.columns().size(); ++k)
    csv << (k ? "," : "") << recorder.columns()[k];
  csv << "\n";

  install_stop_handlers();
  Progress progress(o.quiet);
  const auto t1 = std::chrono::steady_clock::now();
  std::size_t next_snap = 0;
  bool interrupted = false;
  std::vector<Snapshot> kept;  // for the pictures
  for (double t : times) {
    // Advance in slices so that a stop request is seen within a fraction of a second.
    while (sim->time() < t && !interrupted) {
      const double slice = std::min(t, sim->time() + std::max(1.0, 0.01 * sim->time()));
      sim->run_until(slice);
      interrupted = stop_requested();
    }
    if (interrupted) break;
    const auto row = recorder.row(*sim);
    for (std::size_t k = 0; k < row.size(); ++k) csv << (k ? "," : "") << format_number(row[k]);
    csv << "\n" << std::flush;
    if (next_snap < snaps.size() && std::abs(snaps[next_snap] - t) <= 1e-12 * std::max(1.0, t)) {
      Snapshot snap = sim->snapshot();
      write_xyz((dir / "snapshots" / snapshot_name(t)).string(), snap);
      if (o.png) kept.push_back(std::move(snap));
      ++next_snap;
    }
    char what[160];
    std::snprintf(what, sizeof what, "t = %.4g of %.4g, %lld active, %.3g events/s", t,
                  o.physics.t_max, static_cast<long long>(sim->sample().active),
                  static_cast<double>(sim->stats().events) / std::max(1e-9, seconds_since(t1)));
    progress.update(t / o.physics.t_max, what);
  }
  const double run_s = seconds_since(t1);
  progress.done();
  if (interrupted) {  // keep what a restart or a look at the data needs
    write_xyz((dir / "snapshots" / snapshot_name(sim->time())).string(), sim->snapshot());
  }
  write_file_atomic(dir / "summary.json", summary_json(o, *sim, setup_s, run_s, interrupted));
  if (!interrupted && o.png) write_pictures(dir, kept, o);
  if (!interrupted && o.compare_elastic) write_elastic_comparison(dir, o);
  if (!interrupted && o.movie) {
    // Runs are reproducible from (config, seed): the movie replays this very trajectory.
    if (!o.quiet) std::fprintf(stderr, "grainshock: movie of the front\n");
    interrupted = write_front_movie(o.physics, movie, dir).stopped;
  }
  if (!o.quiet)
    std::fprintf(stderr, "grainshock: %s %s: %lld collisions in %.3g s; results in %s\n",
                 interrupted ? "interrupted" : "finished", to_string(o.physics.initial),
                 static_cast<long long>(sim->stats().collisions), run_s, dir.c_str());
  return interrupted ? kExitInterrupted : 0;
}

}  // namespace

void add_run_command(CLI::App& app) {
  auto opt = std::make_shared<RunOptions>();
  auto* sub = app.add_subcommand("run", "Simulate one realisation and write a run folder");
  add_config_option(*sub);
  add_physics_options(*sub, opt->physics);
  add_output_options(*sub, opt->out, opt->force, opt->quiet);
  sub->add_option("--per-decade", opt->per_decade, "Samples per decade of the logarithmic grid")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
  sub->add_option("--sample-every", opt->sample_every, "Also sample every DT (linear grid)")
      ->check(CLI::PositiveNumber);
  sub->add_option("--snapshot-times", opt->snapshot_times, "Write snapshots at these times")
      ->delimiter(',');
  sub->add_flag("--png", opt->png,
                "Draw every snapshot into frames/*.png (colour = speed) and overlay them all");
  sub->add_flag("--compare-elastic", opt->compare_elastic,
                "Also run the same kick with r = 1 to half of t-max, like the paper's Fig. 1(b)");
  sub->add_flag("--movie", opt->movie,
                "Also write movie.mp4 of the front (the defaults of `grainshock movie`)");
  sub->add_option("--width", opt->width, "Width of the pictures in pixels")->capture_default_str();
  sub->add_option("--height", opt->height, "Height of the pictures in pixels")
      ->capture_default_str();
  sub->footer(
      "With no flags but --out, --force and --quiet, runs the paper's Fig. 1 job: 2.5e5 discs, "
      "r = 0.1, snapshots and pictures at paper times 5000, 10000, 20000, 50000, their overlay, "
      "the elastic comparison and a movie of the front.");
  sub->callback([opt, sub] {
    // Where the results go and how loud the run is do not change what is run.
    bool any_flag = false;
    for (const CLI::Option* option : sub->get_options())
      if (option->get_name() != "--out" && option->get_name() != "--force" &&
          option->get_name() != "--quiet")
        any_flag |= option->count() > 0;
    if (!any_flag) {
      RunOptions demo = demo_options();
      demo.out = opt->out;
      demo.force = opt->force;
      demo.quiet = opt->quiet;
      *opt = demo;
    }
    const int rc = run(*opt);
    if (rc != 0) throw Exit{rc};
  });
}

}  // namespace gs::app
