#include "analysis/ensemble_runner.h"

#include <atomic>
#include <cstdio>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

#include "sim/error.h"
#include "sim/stop.h"

namespace gs {

std::string realisation_folder(std::uint64_t index) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%06llu", static_cast<unsigned long long>(index));
  return buf;
}

RunnerResult run_ensemble(const EnsembleSpec& spec, const RunnerOptions& o) {
  if (o.threads < 1) throw UserError("--threads must be at least 1");
  const std::uint64_t first = spec.physics.realisation, total = spec.realisations;
  const int workers = static_cast<int>(std::min<std::uint64_t>(o.threads, total));
  std::atomic<std::uint64_t> next{0};
  std::atomic<bool> stopped{false}, failed{false};
  std::mutex mutex;  // guards finished, error and on_progress
  std::uint64_t finished = 0;
  std::exception_ptr error;
  std::vector<EnsembleSums> partial(workers, EnsembleSums(spec));

  auto work = [&](int w) {
    try {
      Realisation r;
      for (;;) {
        const std::uint64_t k = next.fetch_add(1);
        if (k >= total || failed.load()) return;
        const std::uint64_t index = first + k;
        if (!simulate_realisation(spec, index, r, o.on_snapshot)) {
          stopped = true;
          return;
        }
        if (!o.per_realisation_dir.empty())
          write_realisation(o.per_realisation_dir / realisation_folder(index), r);
        partial[w].add(r, "realisation " + std::to_string(index));
        std::lock_guard lock(mutex);
        ++finished;
        if (o.on_progress) o.on_progress(finished, total);
      }
    } catch (...) {
      std::lock_guard lock(mutex);
      if (!error) error = std::current_exception();
      failed = true;
    }
  };
  std::vector<std::thread> pool;
  for (int w = 1; w < workers; ++w) pool.emplace_back(work, w);
  work(0);
  for (auto& th : pool) th.join();
  if (error) std::rethrow_exception(error);

  RunnerResult result{EnsembleSums(spec), stopped.load() || stop_requested()};
  for (const auto& p : partial) result.sums.merge(p);
  return result;
}

}  // namespace gs
