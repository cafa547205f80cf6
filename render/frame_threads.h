#pragma once
// The threads a big frame is built and drawn on. A frame is split into pieces whose results do
// not depend on which thread makes them (halves of the particles kept in order, bands of rows
// that partition the pixels), so the picture is the same bytes on one core or many.
#include <algorithm>
#include <atomic>
#include <cstddef>
#include <thread>
#include <utility>
#include <vector>

namespace gs::render {

// When > 0, the most threads a frame uses instead of the cores (tests set it to show that the
// pictures do not depend on it).
inline std::atomic<int> frame_thread_limit{0};

// Threads for a frame of `work` items, each thread taking at least `min_per_thread` of them:
// 1 for small frames, at most the cores (hardware_concurrency; 1 if unknown) and at most 8.
inline int frame_threads(std::size_t work, std::size_t min_per_thread) {
  const int limit = frame_thread_limit.load(std::memory_order_relaxed);
  const auto cores = std::clamp(
      limit > 0 ? limit : static_cast<int>(std::thread::hardware_concurrency()), 1, 8);
  const auto by_work = static_cast<int>(std::min<std::size_t>(work / min_per_thread, 8));
  return std::max(1, std::min(cores, by_work));
}

// Calls fn(t) for t in [0, threads): t = 0 on this thread, the others on threads of their own,
// and returns once all have.
template <class Fn>
void run_on_threads(int threads, Fn&& fn) {
  std::vector<std::thread> others;
  others.reserve(threads > 1 ? threads - 1 : 0);
  for (int t = 1; t < threads; ++t) others.emplace_back([&fn, t] { fn(t); });
  try {
    fn(0);
  } catch (...) {
    for (auto& th : others) th.join();
    throw;
  }
  for (auto& th : others) th.join();
}

// The t-th of `parts` nearly equal consecutive pieces of [0, n): [first, last).
inline std::pair<std::size_t, std::size_t> piece(std::size_t n, int parts, int t) {
  return {n * static_cast<std::size_t>(t) / static_cast<std::size_t>(parts),
          n * static_cast<std::size_t>(t + 1) / static_cast<std::size_t>(parts)};
}

}  // namespace gs::render
