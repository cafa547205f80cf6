#include "jobs/movie_frames.h"

#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <mutex>
#include <optional>
#include <thread>
#include <utility>
#include <vector>

#include "io/snapshot_file.h"
#include "sim/error.h"
#include "sim/stop.h"

namespace gs::jobs {
namespace {

// Advances to each frame time from frame `first` on (LiveFrames says why in slices). Returns
// false if stopped.
template <class Visit>
bool for_each_frame(Simulation& sim, const std::vector<double>& times, std::size_t first,
                    ProgressLine& progress, const char* pass, Visit visit, const PauseHook& hook) {
  const auto t0 = std::chrono::steady_clock::now();
  const auto events0 = sim.stats().events;
  auto halt = [&](std::size_t next) {
    const bool stop = stop_requested();
    if (hook.write && (stop || hook.due())) hook.write(next, sim);
    return stop;
  };
  for (std::size_t k = first; k < times.size(); ++k) {
    while (sim.time() < times[k]) {
      sim.run_until(std::min(times[k], sim.time() + std::max(1.0, 0.01 * sim.time())));
      if (halt(k)) return false;
    }
    visit(k);
    char what[160];
    std::snprintf(what, sizeof what, "%s: frame %zu of %zu, t = %.4g, %.3g events/s", pass, k + 1,
                  times.size(), times[k],
                  double(sim.stats().events - events0) / std::max(1e-9, seconds_since(t0)));
    progress.update(double(k + 1) / times.size(), what);
    if (halt(k + 1)) return false;
  }
  return true;
}

// Frame j; a reader's error (which names the file and line) also names the frame.
Snapshot read(const SnapshotFile& f, std::size_t j) {
  try {
    return f.read(j);
  } catch (const UserError& e) {
    if (f.frame_count() == 1) throw;
    throw UserError(std::string(e.what()) + " (frame " + std::to_string(j) + " of " +
                    std::to_string(f.frame_count()) + ")");
  }
}
}  // namespace

bool LiveFrames::each(ProgressLine& progress, const char* pass,
                      const std::function<void(std::size_t, const Snapshot&)>& visit) {
  auto sim = start_ ? std::move(start_) : make_simulation(physics_);
  const std::size_t first = std::exchange(first_, 0);
  return for_each_frame(
      *sim, times_, first, progress, pass,
      [&](std::size_t k) {
        sim->snapshot(snap_);
        visit(k, snap_);
      },
      hook);
}

bool RunFrames::each(ProgressLine& progress, const char* pass,
                     const std::function<void(std::size_t, const Snapshot&)>& visit) {
  const auto t0 = std::chrono::steady_clock::now();
  const Simulation& sim = loop_.simulation();
  const auto events0 = sim.stats().events;
  for (std::size_t k = 0; k < times_.size(); ++k) {
    if (!loop_.run_to(times_[k])) return false;
    // Before the first collision nothing is active, and the moving kicked particle is drawn.
    if (active_only_ && sim.stats().collisions > 0)
      sim.active_snapshot(snap_);
    else
      sim.snapshot(snap_);
    visit(k, snap_);
    char what[160];
    std::snprintf(what, sizeof what, "%s: frame %zu of %zu, t = %.4g, %.3g events/s", pass, k + 1,
                  times_.size(), times_[k],
                  double(sim.stats().events - events0) / std::max(1e-9, seconds_since(t0)));
    progress.update(double(k + 1) / times_.size(), what);
  }
  return true;  // a stop after the last frame is the loop's to notice, with its checkpoint
}

void StoredFrames::list() {
  for (std::size_t file = 0; file < paths_.size(); ++file) {
    const std::size_t n = open_snapshots(paths_[file], read_).frame_count();
    if (n == 0) throw UserError("snapshot '" + paths_[file] + "' holds no frame");
    counts_.push_back(n);
    for (std::size_t j = 0; j < n; ++j) entries_.push_back({file, j});
  }
}

std::string StoredFrames::name(std::size_t k) const {
  const Entry& e = entries_[k];
  const std::string file = "'" + paths_[e.file] + "'";
  return counts_[e.file] == 1 ? file : "frame " + std::to_string(e.frame) + " of " + file;
}

Snapshot StoredFrames::read_frame(std::size_t k) const {
  return read(open_snapshots(paths_[entries_[k].file], read_), entries_[k].frame);
}

void StoredFrames::reorder(const std::vector<std::size_t>& order) {
  std::vector<Entry> e;
  for (std::size_t k : order) e.push_back(entries_[k]);
  entries_ = std::move(e);
}

bool StoredFrames::each(ProgressLine& progress, const char* pass,
                        const std::function<void(std::size_t, const Snapshot&)>& visit) {
  // Parsing a text snapshot of 2.5e5 discs takes about as long as drawing and encoding its frame
  // (measured on the Fig. 1 job: ~40 ms of CPU against ~6 and ~30), so two readers parse the next
  // frames at once: reader j reads frames j, j + R, j + 2R ... into its own slot, and frames are
  // drawn in order from slot k % R. Each reader keeps one frame ahead; more would only hold more
  // memory.
  const std::size_t readers =
      std::clamp<std::size_t>(std::thread::hardware_concurrency(), 1, 2);
  struct Slot {
    std::optional<Snapshot> snap;
  };
  std::mutex m;
  std::condition_variable cv;
  std::vector<Slot> slots(readers);
  std::exception_ptr error;
  std::size_t error_at = 0;  // the frame whose reading failed
  bool quit = false;
  // Hands frame `k` to the drawing thread; false when the pass is over.
  auto put = [&](std::size_t k, Snapshot snap) {
    std::unique_lock lock(m);
    Slot& slot = slots[k % readers];
    cv.wait(lock, [&] { return !slot.snap || quit; });
    if (quit) return false;
    slot.snap = std::move(snap);
    cv.notify_all();
    return true;
  };
  // A file's frames as list() counted them: a file that changed since reads as an error.
  auto open = [&](std::size_t file) {
    SnapshotFile f = open_snapshots(paths_[file], read_);
    if (f.frame_count() != counts_[file])
      throw UserError("snapshot '" + paths_[file] + "' changed while the movie was made: it had " +
                      std::to_string(counts_[file]) + " frames, it has " +
                      std::to_string(f.frame_count()));
    return f;
  };
  auto read_every = [&](std::size_t first) {
    std::size_t k = first;
    try {
      std::optional<SnapshotFile> f;
      std::size_t open_file = 0;
      for (; k < entries_.size(); k += readers) {
        const Entry& e = entries_[k];
        if (!f || open_file != e.file) f.reset(), f.emplace(open(e.file)), open_file = e.file;
        if (!put(k, read(*f, e.frame))) return;
      }
    } catch (...) {
      std::lock_guard lock(m);
      if (!error || k < error_at) error = std::current_exception(), error_at = k;
      cv.notify_all();
    }
  };
  std::vector<std::thread> threads;
  struct Join {  // the readers stop and are joined however this pass ends
    std::vector<std::thread>& t;
    std::mutex& m;
    std::condition_variable& cv;
    bool& quit;
    ~Join() {
      {
        std::lock_guard lock(m);
        quit = true;
      }
      cv.notify_all();
      for (auto& r : t) r.join();
    }
  } join{threads, m, cv, quit};
  for (std::size_t j = 0; j < readers; ++j) threads.emplace_back(read_every, j);
  for (std::size_t k = 0; k < entries_.size(); ++k) {
    Snapshot snap;
    {
      std::unique_lock lock(m);
      Slot& slot = slots[k % readers];
      // A reader's error shows once the frames before it are drawn, as with one reader.
      cv.wait(lock, [&] { return slot.snap || (error && error_at == k); });
      if (!slot.snap) std::rethrow_exception(error);
      snap = std::move(*slot.snap);
      slot.snap.reset();
    }
    cv.notify_all();
    visit(k, snap);
    char what[160];
    std::snprintf(what, sizeof what, "%s: frame %zu of %zu, t = %.4g", pass, k + 1, entries_.size(),
                  snap.info.time);
    progress.update((k + 1.0) / entries_.size(), what);
    if (stop_requested()) return false;
  }
  return true;
}

}  // namespace gs::jobs
