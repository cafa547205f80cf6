#pragma once
// One realisation into a run folder: the sample grid, timeseries.csv, the snapshots and the
// checkpoints. What it writes depends only on its plan, so a run resumed from any of its
// checkpoints (io/checkpoint.h) ends with the same bytes as one that was never interrupted:
// a checkpoint holds the engine, the recorder, the place in the schedule and the length of
// timeseries.csv, which a resumed run cuts back to before it goes on.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <future>
#include <memory>
#include <string>
#include <vector>

#include "io/append_file.h"
#include "io/snapshot_writer.h"
#include "sim/config.h"
#include "sim/engine.h"
#include "sim/recorder.h"

namespace gs::jobs {

// Everything beside the physics that shapes what the loop writes.
struct RunPlan {
  PhysicsConfig physics;
  int per_decade = 20;                 // of the logarithmic sample grid
  double sample_every = 0;             // a linear grid too; 0: none
  std::vector<double> snapshot_times;  // t-max always gets one
  SnapshotWriteOptions snapshots;      // their format and particles
};

// At most this many rows of timeseries.csv (about 2 GB of text).
inline constexpr double kMaxSampleRows = 1e7;

// Throws UserError naming the flag if the plan cannot run (validate() of the physics, snapshot
// times outside (0, t-max], a sample grid of more than kMaxSampleRows rows, more memory than
// the machine has); touches nothing. `snapshot_copies` snapshots may be held in memory at once.
void check_plan(const RunPlan& plan, int snapshot_copies = 1);

std::vector<double> sample_times(const RunPlan& plan);
std::vector<double> snapshot_times(const RunPlan& plan);
// "tsim_<t>": the simulation time t (diameter / v0, not the paper's unit) of a snapshot or
// picture file, whole times as plain integers (tsim_100000, not tsim_1e+05) so that names sort.
std::string time_stem(double t);
// time_stem(t) + ".xyz" (or ".gsd"). One file per snapshot time, also for GSD: a resume then
// never has to cut back a multi-frame file, and each file is a whole record of its moment.
std::string snapshot_name(double t, SnapshotFormat format = SnapshotFormat::Xyz);

struct RunTiming {
  double setup = 0;        // making the initial state (or reading the checkpoint)
  double run = 0;          // the engine, the samples and timeseries.csv
  double snapshots = 0;    // taking and writing snapshots
  double checkpoints = 0;  // writing checkpoints
  std::int64_t checkpoints_written = 0;
};

class RunLoop {
 public:
  // A new run in `dir`, which exists: builds the engine, starts timeseries.csv and writes a
  // first checkpoint. `spec` is the text of the run's file (run.toml), kept in checkpoints so
  // that a resume can tell a folder whose run file has changed.
  RunLoop(const RunPlan& plan, const std::filesystem::path& dir, const std::string& spec);
  // The run of `dir` from its checkpoint. Refuses (UserError, one line) a folder without one,
  // a checkpoint refused by CheckpointReader, and one of another spec or plan; nothing in the
  // folder is changed before all of that has been checked.
  static std::unique_ptr<RunLoop> resume(const RunPlan& plan, const std::filesystem::path& dir,
                                         const std::string& spec);

  static std::filesystem::path checkpoint_path(const std::filesystem::path& dir);
  static std::filesystem::path previous_checkpoint_path(const std::filesystem::path& dir);

  // Wall seconds between checkpoints; 0: only at the start, on a stop and by write_checkpoint().
  double checkpoint_every = 300;
  // Called after each row with what the row was made of (for a progress line).
  std::function<void(const Sample&)> on_sample;

  // Processes the sample points up to simulation time `until`. Returns false if a stop was
  // requested (sim/stop.h); a checkpoint has then been written.
  bool run(double until = INFINITY);
  // run(t), then the engine on to time t, between sample points (a movie's frame: where the
  // engine pauses does not change the history). False if a stop was requested.
  bool run_to(double t);
  bool sampling_done() const { return next_ == times_.size(); }

  // What the caller has done after sampling (0: nothing yet), kept in checkpoints for resume.
  std::uint32_t stage() const { return stage_; }
  void set_stage(std::uint32_t s) { stage_ = s; }
  // Writes the state and returns; the file's sync and renames (most of a big checkpoint's
  // time, and the disk's rather than the CPU's) go on beside the run, the previous checkpoint
  // staying in place until the new one is whole on disk.
  void write_checkpoint();
  // Waits for the last checkpoint to be on disk and in place; rethrows its UserError.
  void finish_checkpoint();
  void remove_checkpoints();

  // The snapshot file of the state now (time t), as the plan says (format, particles).
  void write_run_snapshot(double t);

  const Simulation& simulation() const { return *sim_; }
  const RunTiming& timing() const { return timing_; }

 private:
  RunLoop(const RunPlan& plan, const std::filesystem::path& dir, const std::string& spec,
          std::unique_ptr<Simulation> sim, std::uint64_t csv_bytes);
  template <class Step>
  bool timed(Step step);
  bool samples(double until);
  bool advance(double t);  // the engine to time t, in slices; false if stopped
  void record();

  RunPlan plan_;
  std::filesystem::path dir_;
  std::string spec_;
  std::unique_ptr<Simulation> sim_;
  Recorder recorder_;
  std::vector<double> times_, snaps_;
  std::size_t next_ = 0, next_snap_ = 0;
  std::uint32_t stage_ = 0;
  AppendFile csv_;
  Snapshot snapshot_;  // reused
  RunTiming timing_;
  double last_checkpoint_ = 0;  // wall clock of the last one, seconds of steady_clock
  // The last checkpoint's CheckpointWriter::commit(); its destructor waits for it.
  std::future<void> committing_;
};

}  // namespace gs::jobs
