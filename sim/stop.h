#pragma once
// A cooperative stop: SIGINT/SIGTERM only set a flag, and long loops (the engine's run loop, the
// movie frame loop) poll it and wind down properly, e.g. finish a movie with a valid trailer.
// Header-only so that every library can poll it without linking anything.
#include <unistd.h>

#include <atomic>
#include <csignal>
#include <cstdlib>
#include <exception>

namespace gs {

namespace detail {
// Lock-free atomics are async-signal-safe; 0 means "no stop requested", else the signal number.
inline std::atomic<int> stop_signal{0};
static_assert(std::atomic<int>::is_always_lock_free);

// A second signal while the first is being honoured ends the process at once, for the impatient
// user: with a line that says so (write and _exit are async-signal-safe), and 130 as for any
// stop. What is on disk is what a kill leaves: every result file is whole or absent
// (io/atomic_file.h), the last checkpoint stays, and the next command clears the leftovers.
extern "C" inline void on_stop_signal(int sig) {
  if (stop_signal.exchange(sig, std::memory_order_relaxed) != 0) {
    static constexpr char kLine[] =
        "\ngrainshock: interrupted again: exiting at once; the files written so far are whole, "
        "the last checkpoint stays\n";
    [[maybe_unused]] const auto n = ::write(STDERR_FILENO, kLine, sizeof kLine - 1);
    ::_exit(130);
  }
}
}  // namespace detail

// Installs the handlers for SIGINT and SIGTERM. The first asks for a stop; a second (either)
// exits at once with a message (detail::on_stop_signal).
inline void install_stop_handlers() {
  struct sigaction sa {};
  sa.sa_handler = detail::on_stop_signal;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = SA_RESTART;
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

// What a loop with nothing of its own to save (the set-up of a run: random sequential addition,
// a thermal start's melting, the unbounded medium around the kick; reading a file) throws when a
// stop is asked for: the stack unwinds, result files being written are removed, and the command
// line exits 130.
class Stopped : public std::exception {
 public:
  const char* what() const noexcept override { return "interrupted"; }
};
inline void throw_if_stopped() {
  if (stop_requested()) throw Stopped();
}

}  // namespace gs
