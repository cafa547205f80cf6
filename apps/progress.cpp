#include "apps/progress.h"

#include <unistd.h>

#include <cmath>
#include <cstdio>

namespace gs::app {
namespace {

// First line after half a second; a terminal line is redrawn 5 times a second, a log gets a line
// every 5 s.
constexpr double kFirst = 0.5, kTtyEvery = 0.2, kLogEvery = 5.0;

std::string duration_text(double s) {
  char buf[32];
  if (s < 99.5)
    std::snprintf(buf, sizeof buf, "%.0f s", s);
  else if (s < 99.5 * 60)
    std::snprintf(buf, sizeof buf, "%.0f min", s / 60);
  else
    std::snprintf(buf, sizeof buf, "%.1f h", s / 3600);
  return buf;
}

}  // namespace

Progress::Progress(bool quiet)
    : quiet_(quiet), tty_(isatty(STDERR_FILENO) == 1), start_(Clock::now()) {
  if (!quiet_) ticker_ = std::thread([this] { tick(); });
}

Progress::~Progress() {
  done();
}

double Progress::eta(double ref_wall, double ref_fraction, double wall, double fraction) {
  if (!(fraction > 0 && fraction < 1 && wall > 0)) return -1;
  double end = wall / fraction;  // steady rate since the start
  if (ref_fraction > 0 && ref_wall > 0 && ref_wall < wall && fraction > ref_fraction) {
    const double beta = std::log(fraction / ref_fraction) / std::log(wall / ref_wall);
    // A single run slows to beta ~ 1/g >= 0.5 (its collisions grow as t^g, g <= 2). Slower
    // means the fraction counts unequal pieces (a figures job's quick realisations, then its
    // long ones), and following it would promise thousands of hours: the steady rate since
    // the start is all there is then, as when the work has stalled.
    if (beta >= 0.25) end = wall * std::pow(1 / fraction, 1 / beta);
  }
  return std::isfinite(end) && end - wall < 1e8 ? end - wall : -1;
}

void Progress::update(double fraction, const std::string& what) {
  if (quiet_) return;
  const double wall = std::chrono::duration<double>(Clock::now() - start_).count();
  std::lock_guard lock(mutex_);
  fraction_ = fraction;
  wall_ = wall;
  what_ = what;
  have_ = true;
  if (history_.empty() || wall >= 1.02 * history_.back().first + 0.01)
    history_.emplace_back(wall, fraction);
  // Keep the newest sample at or before half the elapsed time as the front.
  while (history_.size() > 1 && history_[1].first <= wall / 2) history_.pop_front();
}

void Progress::print_locked() {
  const double now = std::chrono::duration<double>(Clock::now() - start_).count();
  std::string line = "  0.0% starting";
  if (have_) {
    char pct[16];
    std::snprintf(pct, sizeof pct, "%5.1f%% ", 100 * fraction_);
    line = pct + what_;
    const auto& [ref_wall, ref_fraction] = history_.front();
    const double left = eta(ref_wall, ref_fraction, wall_, fraction_);
    if (left >= 0) line += ", ETA " + duration_text(std::max(0.0, left - (now - wall_)));
  }
  line += ", " + duration_text(now) + " elapsed";
  std::fprintf(stderr, "%s%s%s", tty_ ? "\r\033[K" : "", line.c_str(), tty_ ? "" : "\n");
  std::fflush(stderr);
  printed_ = true;
}

void Progress::tick() {
  std::unique_lock lock(mutex_);
  auto next =
      start_ + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(kFirst));
  const auto every = std::chrono::duration_cast<Clock::duration>(
      std::chrono::duration<double>(tty_ ? kTtyEvery : kLogEvery));
  while (!wake_.wait_until(lock, next, [this] { return stopping_; })) {
    print_locked();
    next += every;
  }
}

void Progress::done() {
  {
    std::lock_guard lock(mutex_);
    if (stopping_) return;
    stopping_ = true;
  }
  wake_.notify_all();
  if (ticker_.joinable()) ticker_.join();
  if (printed_ && tty_) std::fprintf(stderr, "\n");
}

jobs::ProgressFactory terminal_progress(bool quiet) {
  return [quiet] { return std::make_unique<Progress>(quiet); };
}

MessageSink terminal_messages() {
  return [](MessageKind kind, const std::string& text) {
    std::fprintf(stderr, "grainshock: %s%s\n", kind == MessageKind::Warning ? "warning: " : "",
                 text.c_str());
  };
}

}  // namespace gs::app
