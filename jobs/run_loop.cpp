#include "jobs/run_loop.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>

#include "io/checkpoint.h"
#include "sim/error.h"
#include "sim/format.h"
#include "sim/stop.h"

namespace gs::jobs {
namespace {

double wall_now() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

std::string csv_line(const std::vector<double>& row) {
  std::string line;
  for (std::size_t k = 0; k < row.size(); ++k) {
    if (k) line += ',';
    line += format_number(row[k]);
  }
  return line + '\n';
}

std::string header_line(const Recorder& r) {
  std::string line;
  for (std::size_t k = 0; k < r.columns().size(); ++k) line += (k ? "," : "") + r.columns()[k];
  return line + '\n';
}

}  // namespace

void check_plan(const RunPlan& plan, int snapshot_copies) {
  const PhysicsConfig& c = plan.physics;
  validate(c);
  if (plan.snapshots.format == SnapshotFormat::Gsd && c.dim == 1)
    throw UsageError("--snapshot-format gsd holds 2D and 3D systems only; use xyz in 1D");
  for (double t : plan.snapshot_times)
    if (!(t > 0 && t <= c.t_max))
      throw UsageError("--snapshot-times: " + format_number(t) + " is outside (0, t-max]");
  if (plan.per_decade < 1 || plan.per_decade > 1000)
    throw UsageError("--per-decade " + std::to_string(plan.per_decade) + ": must be in [1, 1000]");
  if (plan.sample_every != 0) {
    if (!(plan.sample_every > 0) || !std::isfinite(plan.sample_every))
      throw UsageError("--sample-every " + format_number(plan.sample_every) + ": must be positive");
    // Counted before the grid is made: 1e-7 to t-max 1e5 would be 1e12 rows.
    const double rows = c.t_max / plan.sample_every;
    if (rows > kMaxSampleRows)
      throw UsageError("--sample-every " + format_number(plan.sample_every) + ": " +
                       format_number(rows) + " rows to t-max " + format_number(c.t_max) +
                       ", more than " + format_number(kMaxSampleRows) + "; use --sample-every " +
                       format_number(c.t_max / kMaxSampleRows) + " or more");
  }
  check_memory(c, snapshot_copies);
}

std::vector<double> sample_times(const RunPlan& plan) {
  std::vector<double> times = log_times(0.1, plan.physics.t_max, plan.per_decade);
  if (plan.sample_every > 0)
    times = merge_times(times, linear_times(plan.sample_every, plan.physics.t_max));
  return merge_times(times, snapshot_times(plan));
}

std::vector<double> snapshot_times(const RunPlan& plan) {
  return merge_times(plan.snapshot_times, {plan.physics.t_max});
}

std::string time_stem(double t) {
  char buf[32];
  if (t == std::floor(t) && t < 1e15) {
    std::snprintf(buf, sizeof buf, "%.0f", t);
    return std::string("tsim_") + buf;
  }
  return "tsim_" + format_number(t);
}

std::string snapshot_name(double t, SnapshotFormat format) {
  return time_stem(t) + snapshot_extension(format);
}

std::filesystem::path RunLoop::checkpoint_path(const std::filesystem::path& dir) {
  return dir / "checkpoint.bin";
}

std::filesystem::path RunLoop::previous_checkpoint_path(const std::filesystem::path& dir) {
  return dir / "checkpoint.prev.bin";
}

RunLoop::RunLoop(const RunPlan& plan, const std::filesystem::path& dir, const std::string& spec,
                 std::unique_ptr<Simulation> sim, std::uint64_t csv_bytes)
    : plan_(plan),
      dir_(dir),
      spec_(spec),
      sim_(std::move(sim)),
      recorder_(plan.physics),
      times_(sample_times(plan)),
      snaps_(snapshot_times(plan)),
      csv_(dir / "timeseries.csv", csv_bytes) {}

RunLoop::RunLoop(const RunPlan& plan, const std::filesystem::path& dir, const std::string& spec)
    : RunLoop(plan, dir, spec, nullptr, 0) {
  std::filesystem::create_directories(dir / "snapshots");
  csv_.append(header_line(recorder_));
  const double t0 = wall_now();
  sim_ = make_simulation(plan.physics);
  timing_.setup = wall_now() - t0;
  write_checkpoint();
}

std::unique_ptr<RunLoop> RunLoop::resume(const RunPlan& plan, const std::filesystem::path& dir,
                                         const std::string& spec) {
  const double t0 = wall_now();
  const std::filesystem::path file =
      checkpoint_to_resume(checkpoint_path(dir), previous_checkpoint_path(dir), "checkpoint");
  CheckpointReader in(file);
  if (in.string() != spec)
    throw UserError("the checkpoint '" + file.string() + "' is of another run than '" +
                    (dir / "run.toml").string() + "' describes");
  const auto next = in.value<std::uint64_t>(), next_snap = in.value<std::uint64_t>();
  const auto stage = in.value<std::uint32_t>();
  const auto csv_bytes = in.value<std::uint64_t>();
  const auto count = in.value<std::uint64_t>();
  RunTiming timing = in.value<RunTiming>();
  const std::vector<double> times = sample_times(plan);
  in.expect(count == times.size() && next <= count && next_snap <= snapshot_times(plan).size());
  Recorder recorder(plan.physics);
  recorder.load(in);
  auto sim = load_simulation(plan.physics, in);
  in.finish();
  auto loop = std::unique_ptr<RunLoop>(new RunLoop(plan, dir, spec, std::move(sim), csv_bytes));
  loop->recorder_ = recorder;
  loop->next_ = next;
  loop->next_snap_ = next_snap;
  loop->stage_ = stage;
  loop->timing_ = timing;
  loop->timing_.setup += wall_now() - t0;
  loop->last_checkpoint_ = wall_now();
  return loop;
}

void RunLoop::write_checkpoint() {
  const double t0 = wall_now();
  finish_checkpoint();  // one in flight at a time: each commit moves the last one to previous
  auto out = std::make_unique<CheckpointWriter>(
      checkpoint_path(dir_), previous_checkpoint_path(dir_),
      StateIdentity{plan_.physics.dim, static_cast<std::uint64_t>(plan_.physics.particles)});
  out->string(spec_);
  out->value(static_cast<std::uint64_t>(next_));
  out->value(static_cast<std::uint64_t>(next_snap_));
  out->value(stage_);
  out->value(csv_.size());
  out->value(static_cast<std::uint64_t>(times_.size()));
  RunTiming timing = timing_;
  ++timing.checkpoints_written;
  out->value(timing);
  recorder_.save(*out);
  sim_->save(*out);
  out->finish();
  committing_ = std::async(std::launch::async, [out = std::move(out)] { out->commit(); });
  timing_.checkpoints_written = timing.checkpoints_written;
  last_checkpoint_ = wall_now();
  timing_.checkpoints += last_checkpoint_ - t0;
}

void RunLoop::finish_checkpoint() {
  if (committing_.valid()) committing_.get();
}

void RunLoop::remove_checkpoints() {
  finish_checkpoint();
  std::error_code ec;
  std::filesystem::remove(checkpoint_path(dir_), ec);
  std::filesystem::remove(previous_checkpoint_path(dir_), ec);
}

bool RunLoop::run(double until) {
  return timed([&] { return samples(until); });
}

bool RunLoop::run_to(double t) {
  return timed([&] { return samples(t) && advance(t); });
}

template <class Step>
bool RunLoop::timed(Step step) {
  // The engine's and the samples' wall time: less the checkpoints and snapshots taken inside.
  const double t0 = wall_now(), c0 = timing_.checkpoints, s0 = timing_.snapshots;
  const bool go_on = step();
  timing_.run += wall_now() - t0 - (timing_.checkpoints - c0) - (timing_.snapshots - s0);
  return go_on;
}

bool RunLoop::samples(double until) {
  while (next_ < times_.size() && times_[next_] <= until) {
    const double t = times_[next_];
    if (!advance(t)) return false;
    record();
    if (next_snap_ < snaps_.size() &&
        std::abs(snaps_[next_snap_] - t) <= 1e-12 * std::max(1.0, t)) {
      const double s0 = wall_now();
      write_run_snapshot(t);
      ++next_snap_;
      timing_.snapshots += wall_now() - s0;
    }
    ++next_;
  }
  return true;
}

void RunLoop::write_run_snapshot(double t) {
  // --snapshot-particles active takes the moving particles alone from the engine: a copy of
  // every particle first would cost more than the engine holds for those at rest (65 B a
  // sphere against 36 B).
  SnapshotWriteOptions options = plan_.snapshots;
  if (options.active_only) {
    sim_->active_snapshot(snapshot_);
    options.active_only = false;  // it is the active subset already, to the bit
  } else {
    sim_->snapshot(snapshot_);
  }
  write_snapshot((dir_ / "snapshots" / snapshot_name(t, options.format)).string(), snapshot_,
                 options);
}

bool RunLoop::advance(double t) {
  // Slices of simulated time, so that a stop request and a checkpoint falling due are seen
  // within a fraction of a second. Where a slice ends does not change the history.
  while (sim_->time() < t) {
    sim_->run_until(std::min(t, sim_->time() + std::max(1.0, 0.01 * sim_->time())));
    const bool stop = stop_requested();
    if (stop || (checkpoint_every > 0 && wall_now() - last_checkpoint_ >= checkpoint_every)) {
      write_checkpoint();
      if (stop) {
        finish_checkpoint();  // what the stop leaves behind is on disk before the exit
        return false;
      }
    }
  }
  return true;
}

void RunLoop::record() {
  Sample s;
  csv_.append(csv_line(recorder_.row(*sim_, &s)));
  if (on_sample) on_sample(s);
}

}  // namespace gs::jobs
