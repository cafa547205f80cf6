#pragma once
// The physical memory that the unbounded media of one process may fill, shared by all its
// engines (an ensemble runs one per worker thread). How many particles a front will have made by
// --t-max depends on t_c1 and the exponents the run is there to measure, so an unbounded run is
// not refused on a guess: each engine takes the bytes of a cell's particles from the budget
// before making them, and ends its run with a UserError naming the memory when the budget cannot
// give them: a run ends at --t-max, or with a clear message when memory would run out. Its
// engine gives everything back when it is destroyed.
#include <atomic>
#include <cstdint>

namespace gs {

class MemoryBudget {
 public:
  // The budget of this process: the machine's physical memory.
  static MemoryBudget& process();

  explicit MemoryBudget(std::int64_t bytes) : capacity_(bytes) {}
  // Takes `bytes` if they fit with what is taken already; false (taking nothing) if not.
  bool take(std::int64_t bytes);
  void give(std::int64_t bytes) { taken_.fetch_sub(bytes, std::memory_order_relaxed); }
  std::int64_t capacity() const { return capacity_.load(std::memory_order_relaxed); }
  std::int64_t taken() const { return taken_.load(std::memory_order_relaxed); }
  // For tests: a machine of `bytes`.
  void set_capacity(std::int64_t bytes) { capacity_.store(bytes, std::memory_order_relaxed); }

 private:
  std::atomic<std::int64_t> capacity_;
  std::atomic<std::int64_t> taken_{0};
};

// Bytes one engine holds of the process's budget, given back when it is destroyed (also when
// the engine's constructor throws after taking some).
class BudgetShare {
 public:
  BudgetShare() = default;
  BudgetShare(const BudgetShare&) = delete;
  BudgetShare& operator=(const BudgetShare&) = delete;
  ~BudgetShare() {
    if (bytes_ > 0) MemoryBudget::process().give(bytes_);
  }
  bool take(std::int64_t bytes) {
    if (!MemoryBudget::process().take(bytes)) return false;
    bytes_ += bytes;
    return true;
  }
  std::int64_t bytes() const { return bytes_; }

 private:
  std::int64_t bytes_ = 0;
};

// This machine's physical memory in bytes (0 if the system does not say).
double physical_memory_bytes();

}  // namespace gs
