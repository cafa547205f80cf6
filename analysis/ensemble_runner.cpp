#include "analysis/ensemble_runner.h"

#include <algorithm>
#include <atomic>
#include <charconv>
#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <deque>
#include <exception>
#include <mutex>
#include <optional>
#include <thread>
#include <vector>

#include "analysis/realisation_in_flight.h"
#include "sim/error.h"
#include "sim/stop.h"

namespace gs {
namespace {

// Tags of the runner's messages between ranks (Ranks::kFinishTag ends the job).
enum Tag : int {
  kJob = 1,     // rank 0 -> rank: spec, threads, indices
  kResult = 2,  // rank -> 0: a finished realisation's files
  kFailed = 3,  // rank -> 0: a realisation that threw
  kDone = 4,    // rank -> 0: the rank's share is over (interrupted or not)
  kStop = 5,    // rank 0 -> rank: take no further index (and abort running ones on a signal)
};

// Payloads of kJob, kResult and kFailed: fields as "length:bytes", so any text travels unescaped.
// kDone carries "0" or "1" (interrupted), kStop the signal number (0: after a failure).
void put(std::string& out, std::string_view field) {
  out += std::to_string(field.size());
  out += ':';
  out += field;
}

std::string_view take(std::string_view& in) {
  std::size_t n = 0;
  const auto [end, ec] = std::from_chars(in.data(), in.data() + in.size(), n);
  GS_CHECK_MSG(ec == std::errc() && end < in.data() + in.size() && *end == ':',
               "malformed message between ranks");
  const std::size_t start = std::size_t(end - in.data()) + 1;
  GS_CHECK_MSG(start + n <= in.size(), "truncated message between ranks");
  const std::string_view field = in.substr(start, n);
  in.remove_prefix(start + n);
  return field;
}

std::uint64_t take_number(std::string_view& in) {
  const std::string_view f = take(in);
  std::uint64_t v = 0;
  const auto [end, ec] = std::from_chars(f.data(), f.data() + f.size(), v);
  GS_CHECK_MSG(ec == std::errc() && end == f.data() + f.size(), "malformed number between ranks");
  return v;
}

// What a worker hands to its rank's main thread.
struct Finished {
  std::uint64_t index = 0;
  std::vector<RealisationFile> files;  // empty if it failed
  std::string error;
  bool user_error = false;
};

// The worker threads of one rank over its share of the indices. Only the main thread talks to
// other ranks and to the disk; workers only simulate.
class LocalWork {
 public:
  // `in_flight.file` is the folder of the states in flight (empty: none), the rest as given to
  // each realisation.
  LocalWork(const EnsembleSpec& spec, std::vector<std::uint64_t> indices, int threads,
            SnapshotHook hook, InFlightOptions in_flight)
      : spec_(spec),
        indices_(std::move(indices)),
        hook_(std::move(hook)),
        in_flight_(std::move(in_flight)) {
    const std::size_t n = std::min<std::size_t>(std::size_t(threads), indices_.size());
    running_ = n;
    for (std::size_t w = 0; w < n; ++w) pool_.emplace_back([this] { work(); });
  }
  ~LocalWork() {
    stop_pulling();
    for (auto& t : pool_) t.join();
  }

  // Takes no further index; running realisations finish (or stop at a requested stop).
  void stop_pulling() { pulling_ = false; }
  bool interrupted() const { return interrupted_; }

  // The next finished realisation, waiting up to `wait`; nullopt if none came. `over` is set
  // when every worker has ended and nothing is left to take.
  std::optional<Finished> next(std::chrono::milliseconds wait, bool& over) {
    std::unique_lock lock(mutex_);
    cv_.wait_for(lock, wait, [&] { return !queue_.empty() || running_ == 0; });
    over = queue_.empty() && running_ == 0;
    if (queue_.empty()) return std::nullopt;
    Finished f = std::move(queue_.front());
    queue_.pop_front();
    return f;
  }

 private:
  void work() {
    Realisation r;
    for (;;) {
      const std::size_t k = next_.fetch_add(1);
      if (k >= indices_.size() || !pulling_) break;
      Finished f;
      f.index = indices_[k];
      InFlightOptions in_flight = in_flight_;
      if (!in_flight.file.empty()) in_flight.file /= realisation_folder(f.index);
      try {
        if (!simulate_realisation(spec_, f.index, r, hook_, in_flight)) {
          interrupted_ = true;
          break;
        }
        f.files = realisation_files(r);
      } catch (const Stopped&) {  // stopped in a realisation's set-up
        interrupted_ = true;
        break;
      } catch (const UserError& e) {
        f.error = e.what();
        f.user_error = true;
      } catch (const std::exception& e) {
        f.error = e.what();
      }
      const bool failed = f.files.empty();
      push(std::move(f));
      if (failed) {
        pulling_ = false;
        break;
      }
    }
    std::lock_guard lock(mutex_);
    --running_;
    cv_.notify_all();
  }

  void push(Finished f) {
    std::lock_guard lock(mutex_);
    queue_.push_back(std::move(f));
    cv_.notify_all();
  }

  const EnsembleSpec spec_;
  const std::vector<std::uint64_t> indices_;
  const SnapshotHook hook_;
  const InFlightOptions in_flight_;
  std::atomic<std::size_t> next_{0};
  std::atomic<bool> pulling_{true}, interrupted_{false};
  std::mutex mutex_;
  std::condition_variable cv_;
  std::deque<Finished> queue_;
  std::size_t running_ = 0;
  std::vector<std::thread> pool_;
};

// How long a rank's main thread waits for its workers before looking for messages again.
constexpr std::chrono::milliseconds kPollEvery{5};

void remove_stale_temporaries(const std::filesystem::path& dir) {
  namespace fs = std::filesystem;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    const std::string name = e.path().filename().string();
    if (name.starts_with(".") && name.find(".tmp.") != std::string::npos) fs::remove_all(e, ec);
  }
}

// Makes the folder of the states in flight and leaves in it only those of realisations still to
// run: a kill can leave the state of one written since, and temporaries of a write.
void keep_in_flight_of(const std::filesystem::path& in_flight,
                       const std::vector<std::uint64_t>& todo) {
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::create_directories(in_flight, ec);
  if (ec) throw UserError("cannot create '" + in_flight.string() + "': " + ec.message());
  std::vector<std::string> keep;
  for (auto index : todo) {
    keep.push_back(realisation_folder(index));
    keep.push_back(realisation_folder(index) + ".previous");
  }
  for (const auto& e : fs::directory_iterator(in_flight, ec))
    if (std::find(keep.begin(), keep.end(), e.path().filename().string()) == keep.end())
      fs::remove_all(e.path(), ec);
}

}  // namespace

std::string realisation_folder(std::uint64_t index) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%06llu", static_cast<unsigned long long>(index));
  return buf;
}

std::vector<std::uint64_t> finished_realisations(const std::filesystem::path& dir,
                                                 const EnsembleSpec& spec) {
  std::vector<std::uint64_t> found;
  for (std::uint64_t k = 0; k < spec.realisations; ++k) {
    const std::uint64_t index = spec.physics.realisation + k;
    if (std::filesystem::is_directory(dir / realisation_folder(index))) found.push_back(index);
  }
  return found;
}

int default_threads() {
  return std::clamp(static_cast<int>(std::thread::hardware_concurrency()), 1, kMaxThreads);
}

void check_threads(int threads) {
  if (threads < 1 || threads > kMaxThreads)
    throw UsageError("--threads " + std::to_string(threads) + ": must be in [1, " +
                     std::to_string(kMaxThreads) + "]");
}

RunnerResult run_ensemble(const EnsembleSpec& spec, const RunnerOptions& o) {
  check_threads(o.threads);
  Ranks& ranks = o.ranks ? *o.ranks : Ranks::single();
  GS_CHECK(ranks.rank() == 0);
  const auto& dir = o.realisations_dir;
  RunnerResult result{EnsembleSums(spec)};

  // Read what a killed run left, first: a corrupt folder is refused before anything runs.
  std::vector<std::uint64_t> todo;
  if (!dir.empty()) {
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    if (ec) throw UserError("cannot create '" + dir.string() + "': " + ec.message());
    remove_stale_temporaries(dir);
    const auto found = finished_realisations(dir, spec);
    for (auto index : found) {
      const auto p = dir / realisation_folder(index);
      result.sums.add(read_realisation(p, index), p.string());
    }
    result.resumed = found.size();
  }
  for (std::uint64_t k = 0; k < spec.realisations; ++k) {
    const std::uint64_t index = spec.physics.realisation + k;
    if (!std::binary_search(result.sums.indices().begin(), result.sums.indices().end(), index))
      todo.push_back(index);
  }
  InFlightOptions in_flight;
  if (!dir.empty()) {
    in_flight.file = dir / kInFlightFolder;
    in_flight.interval = o.checkpoint_interval;
    in_flight.warn = o.on_warning ? o.on_warning : [](const std::string&) {};
    keep_in_flight_of(in_flight.file, todo);
  }

  // Round-robin shares: realisations cost about the same, and the sums do not care.
  const int K = ranks.size();
  std::vector<std::vector<std::uint64_t>> share(static_cast<std::size_t>(K));
  for (std::size_t j = 0; j < todo.size(); ++j) share[j % std::size_t(K)].push_back(todo[j]);
  const std::string spec_text = spec_toml(spec);
  for (int r = 1; r < K; ++r) {
    std::string job;
    put(job, spec_text);
    put(job, std::to_string(o.threads));
    put(job, std::to_string(share[std::size_t(r)].size()));
    for (auto index : share[std::size_t(r)]) put(job, std::to_string(index));
    ranks.send(r, kJob, job);
  }

  std::uint64_t finished = 0;
  std::string failure;
  bool failure_is_user = true;
  std::vector<bool> done(std::size_t(K), false);
  int ranks_done = 1;  // rank 0's own share is tracked by LocalWork
  LocalWork local(spec, share[0], o.threads, o.on_snapshot, in_flight);
  bool stop_sent = false;
  auto stop_others = [&](int sig) {
    if (stop_sent) return;
    stop_sent = true;
    for (int r = 1; r < K; ++r)
      if (!done[std::size_t(r)]) ranks.send(r, kStop, std::to_string(sig));
  };
  auto fail = [&](int rank, std::uint64_t index, const std::string& what, bool user) {
    if (failure.empty()) {
      failure = (K > 1 ? "rank " + std::to_string(rank) + ", " : std::string()) + "realisation " +
                std::to_string(index) + ": " + what;
      failure_is_user = user;
    }
    local.stop_pulling();
    stop_others(0);
  };
  auto add = [&](int rank, std::uint64_t index, const std::vector<RealisationFile>& files) {
    try {
      const auto p = dir.empty() ? std::filesystem::path(realisation_folder(index))
                                 : dir / realisation_folder(index);
      if (!dir.empty()) {
        write_realisation(p, files);
        remove_in_flight(dir / kInFlightFolder / realisation_folder(index));
      }
      result.sums.add(parse_realisation(files, index, p), "realisation " + std::to_string(index));
      ++finished;
      if (o.on_progress) o.on_progress(finished, todo.size());
    } catch (const UserError& e) {
      fail(rank, index, e.what(), true);
    }
  };

  for (bool local_over = false; !local_over || ranks_done < K;) {
    if (local_over) std::this_thread::sleep_for(kPollEvery);
    while (!local_over) {
      auto f = local.next(K > 1 ? kPollEvery : std::chrono::milliseconds(200), local_over);
      if (!f) break;
      if (f->files.empty())
        fail(0, f->index, f->error, f->user_error);
      else
        add(0, f->index, f->files);
    }
    while (auto m = ranks.poll()) {
      std::string_view in = m->payload;
      if (m->tag == kResult) {
        const std::uint64_t index = take_number(in);
        std::vector<RealisationFile> files;
        while (!in.empty()) {
          RealisationFile f;
          f.name = take(in);
          f.text = take(in);
          files.push_back(std::move(f));
        }
        add(m->from, index, files);
      } else if (m->tag == kFailed) {
        const std::uint64_t index = take_number(in);
        const bool user = take_number(in) != 0;
        fail(m->from, index, std::string(take(in)), user);
      } else if (m->tag == kDone) {
        GS_CHECK(!done[std::size_t(m->from)]);
        done[std::size_t(m->from)] = true;
        ++ranks_done;
        result.interrupted = result.interrupted || m->payload != "0";
      } else {
        GS_CHECK_MSG(false, "unexpected message between ranks");
      }
    }
    if (stop_requested()) {
      local.stop_pulling();
      stop_others(stop_signal());
    }
  }
  result.interrupted = result.interrupted || local.interrupted() || stop_requested();
  if (!failure.empty()) {
    ranks.finish(1);
    if (!dir.empty())
      failure += " (the " + std::to_string(finished + result.resumed) +
                 " realisations finished are kept in " + dir.string() + ")";
    if (failure_is_user) throw UserError(failure);
    throw std::runtime_error(failure);
  }
  ranks.finish(result.interrupted ? 128 + std::max(0, stop_signal()) : 0);
  return result;
}

int serve_ensemble(Ranks& ranks) {
  GS_CHECK(ranks.rank() != 0);
  const Ranks::Message m = ranks.receive();
  if (m.tag == Ranks::kFinishTag) return std::stoi(m.payload);  // rank 0 refused the job
  GS_CHECK_MSG(m.tag == kJob, "unexpected message between ranks");
  std::string_view in = m.payload;
  const std::string spec_text(take(in));
  const int threads = static_cast<int>(take_number(in));
  std::vector<std::uint64_t> indices(take_number(in));
  for (auto& index : indices) index = take_number(in);
  EnsembleSpec spec;
  try {
    spec = parse_spec(spec_text, "the job of rank 0");
  } catch (const UserError& e) {
    std::string out;
    put(out, std::to_string(indices.empty() ? 0 : indices.front()));
    put(out, "1");
    put(out, e.what());
    ranks.send(0, kFailed, out);
    ranks.send(0, kDone, "0");
    return ranks.finish(0);
  }

  LocalWork local(spec, indices, threads, {}, {});  // no folder: nothing kept in flight
  for (bool over = false; !over;) {
    while (auto f = local.next(kPollEvery, over)) {
      std::string out;
      put(out, std::to_string(f->index));
      if (f->files.empty()) {
        put(out, f->user_error ? "1" : "0");
        put(out, f->error);
        ranks.send(0, kFailed, out);
      } else {
        for (const auto& file : f->files) {
          put(out, file.name);
          put(out, file.text);
        }
        ranks.send(0, kResult, out);
      }
    }
    while (auto s = ranks.poll()) {
      if (s->tag == Ranks::kFinishTag) {  // rank 0 ended the job early (an internal error)
        request_stop();
        return std::stoi(s->payload);
      }
      GS_CHECK_MSG(s->tag == kStop, "unexpected message between ranks");
      local.stop_pulling();
      if (const int sig = std::stoi(s->payload); sig != 0) request_stop(sig);
    }
  }
  ranks.send(0, kDone, local.interrupted() || stop_requested() ? "1" : "0");
  return ranks.finish(0);
}

}  // namespace gs
