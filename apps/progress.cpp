#include "apps/progress.h"

#include <unistd.h>

#include <cstdio>

namespace gs::app {

Progress::Progress(bool quiet)
    : quiet_(quiet), tty_(isatty(STDERR_FILENO) == 1), start_(Clock::now()), last_(start_) {}

void Progress::update(double fraction, const std::string& what) {
  if (quiet_) return;
  const auto now = Clock::now();
  const double since_last = std::chrono::duration<double>(now - last_).count();
  if (since_last < (tty_ ? 0.2 : 5.0)) return;
  last_ = now;
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  char eta[64] = "";
  if (fraction > 1e-3 && fraction < 1)
    std::snprintf(eta, sizeof eta, ", ETA %.0f s", elapsed * (1 - fraction) / fraction);
  std::fprintf(stderr, "%s%5.1f%% %s%s%s", tty_ ? "\r\033[K" : "", 100 * fraction, what.c_str(),
               eta, tty_ ? "" : "\n");
  std::fflush(stderr);
  printed_ = true;
}

void Progress::done() {
  if (quiet_ || !printed_ || !tty_) return;
  std::fprintf(stderr, "\n");
}

}  // namespace gs::app
