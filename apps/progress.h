#pragma once
// Progress of long work on stderr: a live line when stderr is a terminal, a plain line every few
// seconds otherwise, nothing when quiet. A ticker thread prints, so the first line comes within
// half a second however rarely the work reports, and the ETA counts down between reports.
//
// The ETA extrapolates the measured progress, not the elapsed time scaled by the fraction: over
// the last half of the elapsed wall time, the fraction (simulated time / t_max, or finished
// realisations) is fitted as f ~ wall^beta through its two ends and followed to f = 1. For a
// steady rate (beta = 1) that is the usual linear estimate; a kick whose front gathers more and
// more particles advances simulated time ever more slowly (beta < 1), which a linear estimate
// from t / t_max misses by a factor of several. Below beta = 1/4 the fraction is not one run's
// (unequal realisations): the linear estimate is used then.
#include <chrono>
#include <condition_variable>
#include <deque>
#include <mutex>
#include <string>
#include <thread>
#include <utility>

#include "jobs/progress.h"
#include "sim/messages.h"

namespace gs::app {

class Progress final : public jobs::ProgressLine {
 public:
  explicit Progress(bool quiet);
  ~Progress() override;
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  // `fraction` in [0, 1] of the work; `what` is the rest of the line. Cheap: only records.
  void update(double fraction, const std::string& what) override;
  // Stops the ticker and ends a live line. Idempotent.
  void done() override;

  // Seconds left after `wall` seconds, from progress `fraction` at `wall` and `ref_fraction` at
  // `ref_wall` < `wall` (beta as above; ref_fraction = 0 means the linear estimate from the
  // start). Negative when no estimate can be made.
  static double eta(double ref_wall, double ref_fraction, double wall, double fraction);

 private:
  using Clock = std::chrono::steady_clock;
  void tick();
  void print_locked();

  const bool quiet_, tty_;
  const Clock::time_point start_;
  std::mutex mutex_;
  std::condition_variable wake_;
  bool stopping_ = false, printed_ = false, have_ = false;
  double fraction_ = 0, wall_ = 0;  // the last report
  std::string what_;
  std::deque<std::pair<double, double>> history_;  // (wall, fraction), geometrically spaced
  std::thread ticker_;
};

// The factory that gives every pass of a job its own terminal line (none when quiet).
jobs::ProgressFactory terminal_progress(bool quiet);

// The sink that prints a job's notes and warnings on stderr, one line each ("grainshock: ...",
// "grainshock: warning: ..."). The jobs leave out their notes when quiet, not their warnings.
MessageSink terminal_messages();

}  // namespace gs::app
