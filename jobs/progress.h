#pragma once
// How a job tells its caller how far it has come. Each pass of a job opens a line, updates it
// and closes it; what a line shows is the caller's: the command line's terminal line
// (apps/progress.h), a notebook's own, or nothing.
#include <chrono>
#include <functional>
#include <memory>
#include <string>

namespace gs::jobs {

class ProgressLine {
 public:
  virtual ~ProgressLine() = default;
  // `fraction` in [0, 1] of the pass; `what` is the rest of the line. Must be cheap.
  virtual void update(double fraction, const std::string& what) = 0;
  // Ends the line. Idempotent.
  virtual void done() = 0;
};

// Opens the line of one pass; empty: the job reports nothing.
using ProgressFactory = std::function<std::unique_ptr<ProgressLine>()>;

// The line `factory` makes, or one that shows nothing.
std::unique_ptr<ProgressLine> open_progress(const ProgressFactory& factory);

// Wall seconds since `t0`, for rates on the line and the time a job reports.
inline double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace gs::jobs
