#pragma once
// A cooperative stop: SIGINT/SIGTERM only set a flag, and long loops (the engine's run loop, the
// movie frame loop) poll it and wind down properly, e.g. finish a movie with a valid trailer.
// Header-only so that every library can poll it without linking anything.
#include <atomic>
#include <csignal>

namespace gs {

namespace detail {
// Lock-free atomics are async-signal-safe; 0 means "no stop requested", else the signal number.
inline std::atomic<int> stop_signal{0};
static_assert(std::atomic<int>::is_always_lock_free);

extern "C" inline void on_stop_signal(int sig) {
  stop_signal.store(sig, std::memory_order_relaxed);
}
}  // namespace detail

// Installs the handlers for SIGINT and SIGTERM. One-shot (SA_RESETHAND): a second Ctrl-C kills the
// process at once, for the impatient user whose loop does not poll.
inline void install_stop_handlers() {
  struct sigaction sa {};
  sa.sa_handler = detail::on_stop_signal;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = SA_RESETHAND | SA_RESTART;
  sigaction(SIGINT, &sa, nullptr);
  sigaction(SIGTERM, &sa, nullptr);
}

inline bool stop_requested() {
  return detail::stop_signal.load(std::memory_order_relaxed) != 0;
}

// The signal that asked for the stop (SIGINT, SIGTERM), or 0. Exit with 128 + it, as shells expect.
inline int stop_signal() {
  return detail::stop_signal.load(std::memory_order_relaxed);
}

// For tests and for code that wants the same wind-down without a signal; -1 when not a signal.
inline void request_stop(int sig = -1) {
  detail::stop_signal.store(sig, std::memory_order_relaxed);
}
inline void clear_stop() {
  detail::stop_signal.store(0, std::memory_order_relaxed);
}

}  // namespace gs
