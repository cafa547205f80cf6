// `grainshock run`: one realisation into a run folder.
#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "apps/cli.h"
#include "apps/commands.h"
#include "apps/progress.h"
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
};

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

std::string snapshot_name(double t) { return "t_" + format_number(t) + ".xyz"; }

std::string summary_json(const RunOptions& o, const Simulation& sim, double setup_s, double run_s,
                         bool interrupted) {
  const auto& st = sim.stats();
  const Sample s = sim.sample();
  std::ostringstream j;
  j << "{\n"
    << "  \"version\": \"" << GRAINSHOCK_VERSION << "\",\n"
    << "  \"dim\": " << o.physics.dim << ",\n"
    << "  \"particles\": " << o.physics.particles << ",\n"
    << "  \"density\": " << format_double(o.physics.density) << ",\n"
    << "  \"restitution\": " << format_double(o.physics.restitution) << ",\n"
    << "  \"cutoff\": " << format_double(o.physics.cutoff) << ",\n"
    << "  \"seed\": " << o.physics.seed << ",\n"
    << "  \"realisation\": " << o.physics.realisation << ",\n"
    << "  \"initial\": \"" << to_string(o.physics.initial) << "\",\n"
    << "  \"t_end\": " << format_double(sim.time()) << ",\n"
    << "  \"t_end_paper\": " << format_double(o.physics.paper_time(sim.time())) << ",\n"
    << "  \"interrupted\": " << (interrupted ? "true" : "false") << ",\n"
    << "  \"setup_seconds\": " << format_double(setup_s) << ",\n"
    << "  \"run_seconds\": " << format_double(run_s) << ",\n"
    << "  \"events\": " << st.events << ",\n"
    << "  \"collisions\": " << st.collisions << ",\n"
    << "  \"inelastic_collisions\": " << st.inelastic << ",\n"
    << "  \"cell_crossings\": " << st.crossings << ",\n"
    << "  \"stale_events\": " << st.stale << ",\n"
    << "  \"overlaps\": " << st.overlaps << ",\n"
    << "  \"max_overlap\": " << format_double(st.max_overlap) << ",\n"
    << "  \"collisions_per_second\": " << format_double(run_s > 0 ? st.collisions / run_s : 0)
    << ",\n"
    << "  \"active\": " << s.active << ",\n"
    << "  \"energy\": " << format_double(s.energy) << ",\n"
    << "  \"radius_rms\": " << format_double(s.radius_rms) << ",\n"
    << "  \"speed_rms\": " << format_double(s.speed_rms) << "\n"
    << "}\n";
  return j.str();
}

int run(const RunOptions& o) {
  validate(o.physics);
  for (double t : o.snapshot_times)
    if (!(t > 0 && t <= o.physics.t_max))
      throw UserError("--snapshot-times: " + format_number(t) + " is outside (0, t-max]");
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
      write_xyz((dir / "snapshots" / snapshot_name(t)).string(), sim->snapshot());
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
  if (!o.quiet)
    std::fprintf(stderr, "grainshock: %s %s: %lld collisions in %.3g s; results in %s\n",
                 interrupted ? "interrupted" : "finished", to_string(o.physics.initial),
                 static_cast<long long>(sim->stats().collisions), run_s, dir.c_str());
  return interrupted ? 128 + std::max(0, stop_signal()) : 0;
}

}  // namespace

void add_run_command(CLI::App& app) {
  auto opt = std::make_shared<RunOptions>();
  auto* sub = app.add_subcommand("run", "Simulate one realisation and write a run folder");
  add_config_option(*sub);
  add_physics_options(*sub, opt->physics);
  sub->add_option("--out", opt->out, "Output folder (must not exist or be empty)")
      ->capture_default_str();
  sub->add_flag("--force", opt->force, "Write into an existing non-empty output folder");
  sub->add_flag("--quiet", opt->quiet, "No progress on stderr");
  sub->add_option("--per-decade", opt->per_decade, "Samples per decade of the logarithmic grid")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
  sub->add_option("--sample-every", opt->sample_every, "Also sample every DT (linear grid)")
      ->check(CLI::PositiveNumber);
  sub->add_option("--snapshot-times", opt->snapshot_times, "Write snapshots at these times")
      ->delimiter(',');
  sub->callback([opt] {
    const int rc = run(*opt);
    if (rc != 0) std::exit(rc);
  });
}

}  // namespace gs::app
