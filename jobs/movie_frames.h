#pragma once
// Where a movie's frames come from, visited in order as often as its passes need them: a running
// simulation (replayed from the start on each pass, or from a checkpoint's state), a run loop's
// engine as the run reaches each frame, or the frames of stored snapshot files, read one ahead on
// a second thread.
#include <cstddef>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "io/snapshot_file.h"
#include "jobs/progress.h"
#include "jobs/run_loop.h"
#include "sim/config.h"
#include "sim/engine.h"
#include "sim/snapshot.h"

namespace gs::jobs {

// Where a live movie keeps checkpoints: `due` says when one is; `write` takes it, `next` being
// the frame to draw next. Without `write`, none.
struct PauseHook {
  std::function<bool()> due;
  std::function<void(std::size_t next, const Simulation& sim)> write;
};

// The frames of a movie, visited in order, as often as the passes need them.
class Frames {
 public:
  virtual ~Frames() = default;
  virtual std::size_t size() const = 0;
  // Calls visit(k, snapshot) for k = 0, 1, ...; false if a stop request ended the pass.
  virtual bool each(ProgressLine& progress, const char* pass,
                    const std::function<void(std::size_t, const Snapshot&)>& visit) = 0;
};

// A running simulation, replayed from the start on each pass, or from a checkpoint's state. It
// advances in slices that depend only on the simulated time (where a slice ends does not change
// the history), so that both passes and a resumed movie see the same trajectory, and a stop
// request or a checkpoint falling due is noticed within a fraction of a second. A stop writes a
// checkpoint first.
class LiveFrames final : public Frames {
 public:
  LiveFrames(const PhysicsConfig& physics, std::vector<double> times)
      : physics_(physics), times_(std::move(times)) {}
  std::size_t size() const override { return times_.size(); }
  // The next pass goes on from `sim`, whose next frame is `next`.
  void start_at(std::unique_ptr<Simulation> sim, std::size_t next) {
    start_ = std::move(sim);
    first_ = next;
  }
  bool each(ProgressLine& progress, const char* pass,
            const std::function<void(std::size_t, const Snapshot&)>& visit) override;
  PauseHook hook;  // the checkpoints of the next pass

 private:
  PhysicsConfig physics_;
  std::vector<double> times_;
  std::unique_ptr<Simulation> start_;
  std::size_t first_ = 0;
  Snapshot snap_;  // reused frame after frame
};

// The frames of a run as its loop reaches their times (jobs/run_loop.h, run_to): one pass, with
// the run's samples, snapshots and checkpoints between them, so that the run's files are the
// bytes they are without a movie. A stop ends the pass, the loop having written its checkpoint.
// With `active_only` (for pictures that draw nothing else), a frame holds only the active
// particles once there are any (Simulation::active_snapshot, in snapshot()'s order): the same
// picture, without copying the gas at rest (2.5e5 discs: 4.6 ms a frame).
class RunFrames final : public Frames {
 public:
  RunFrames(RunLoop& loop, std::vector<double> times, bool active_only)
      : loop_(loop), times_(std::move(times)), active_only_(active_only) {}
  std::size_t size() const override { return times_.size(); }
  bool each(ProgressLine& progress, const char* pass,
            const std::function<void(std::size_t, const Snapshot&)>& visit) override;

 private:
  RunLoop& loop_;
  std::vector<double> times_;
  bool active_only_;
  Snapshot snap_;  // reused frame after frame
};

// Every frame of stored snapshot files in a chosen order. list() opens the files (which indexes
// their frames without parsing them) and takes the frames in the order given; reorder() changes
// it. A second thread reads frame k + 1 while frame k is drawn; it waits for the slot to empty
// first, so at most two frames are in memory at once. The last file opened stays open for the
// frames after it.
class StoredFrames final : public Frames {
 public:
  StoredFrames(std::vector<std::string> paths, const ReadOptions& read)
      : paths_(std::move(paths)), read_(read) {}
  std::size_t size() const override { return entries_.size(); }
  // UserError naming a file that cannot be opened or holds no frame.
  void list();
  // "'file'", or "frame 3 of 'file'" for a file of several frames (frames count from 0).
  std::string name(std::size_t k) const;
  Snapshot read_frame(std::size_t k) const;
  // Reorders the frames: frame k becomes the one that was frame `order[k]`.
  void reorder(const std::vector<std::size_t>& order);
  bool each(ProgressLine& progress, const char* pass,
            const std::function<void(std::size_t, const Snapshot&)>& visit) override;

 private:
  struct Entry {
    std::size_t file, frame;
  };
  std::vector<std::string> paths_;
  ReadOptions read_;
  std::vector<Entry> entries_;       // frame k of the movie is frame entries_[k].frame of a file
  std::vector<std::size_t> counts_;  // frames in each file
};

}  // namespace gs::jobs
