#pragma once
// The processes of an ensemble job. Launched by mpirun in a build with MPI, the ranks of
// MPI_COMM_WORLD; otherwise one rank, and the ensemble takes the same code path. Only the
// ensemble runner (analysis/ensemble_runner.h) sends through it; only the main thread of a rank
// calls it (MPI_THREAD_FUNNELED). Payloads are bytes; the runner gives them meaning.
#include <optional>
#include <string>
#include <string_view>

namespace gs {

class Ranks {
 public:
  // Tag of the message that ends the job (finish()); the runner's own tags are positive.
  static constexpr int kFinishTag = 0;

  struct Message {
    int from = 0, tag = 0;
    std::string payload;
  };

  // The job's processes: the MPI world when started by mpirun (joined on the first call and
  // left at exit), else this process alone.
  static Ranks& world();
  // This process alone, whatever launched it (ensembles inside other commands, e.g. figures).
  static Ranks& single();

  Ranks(const Ranks&) = delete;
  Ranks& operator=(const Ranks&) = delete;
  ~Ranks();

  int rank() const { return rank_; }
  int size() const { return size_; }

  void send(int to, int tag, std::string_view payload);
  std::optional<Message> poll();  // a waiting message, if any
  Message receive();              // blocks until a message arrives

  // Rank 0: tells every other rank that the job is over and which exit code to return (once; the
  // destructor says 1 if rank 0 never did, e.g. after a user error). Other ranks: waits for that,
  // dropping other messages, and returns the code.
  int finish(int exit_code);

 private:
  explicit Ranks(bool join_mpi);
  int rank_ = 0, size_ = 1;
  bool mpi_ = false, finished_ = false;
};

}  // namespace gs
