#pragma once
// Progress of long work on stderr: a live line when stderr is a terminal, a plain line every few
// seconds otherwise, nothing when quiet.
#include <chrono>
#include <string>

namespace gs::app {

class Progress {
 public:
  explicit Progress(bool quiet);
  // `fraction` in [0, 1] drives the ETA; `what` is the rest of the line.
  void update(double fraction, const std::string& what);
  void done();

 private:
  using Clock = std::chrono::steady_clock;
  bool quiet_, tty_;
  Clock::time_point start_, last_;
  bool printed_ = false;
};

}  // namespace gs::app
