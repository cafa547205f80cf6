#include "sim/memory_budget.h"

#include <unistd.h>

namespace gs {

double physical_memory_bytes() {
  const long pages = ::sysconf(_SC_PHYS_PAGES), page = ::sysconf(_SC_PAGE_SIZE);
  return pages > 0 && page > 0 ? static_cast<double>(pages) * static_cast<double>(page) : 0;
}

MemoryBudget& MemoryBudget::process() {
  // A system that does not say how much it has is not limited here, as check_memory does.
  static MemoryBudget budget(physical_memory_bytes() > 0
                                 ? static_cast<std::int64_t>(physical_memory_bytes())
                                 : INT64_MAX);
  return budget;
}

bool MemoryBudget::take(std::int64_t bytes) {
  std::int64_t now = taken_.load(std::memory_order_relaxed);
  do {
    if (bytes > capacity() - now) return false;
  } while (!taken_.compare_exchange_weak(now, now + bytes, std::memory_order_relaxed));
  return true;
}

}  // namespace gs
