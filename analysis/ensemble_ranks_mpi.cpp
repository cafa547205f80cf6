// Ranks through MPI (built when CMake finds MPI and GRAINSHOCK_MPI is ON).
#include <mpi.h>

#include <chrono>
#include <cstdlib>
#include <string>
#include <thread>

#include "analysis/ensemble_ranks.h"
#include "sim/error.h"

namespace gs {
namespace {

// mpirun (Open MPI's, or a PMI/PMIx launcher such as srun) sets these; a plain start does not,
// and then MPI is not initialised at all, so the one-process ensemble pays nothing for it.
bool launched_by_mpirun() {
  return std::getenv("OMPI_COMM_WORLD_SIZE") != nullptr || std::getenv("PMIX_RANK") != nullptr ||
         std::getenv("PMI_RANK") != nullptr;
}

}  // namespace

Ranks::Ranks(bool join_mpi) {
  if (!join_mpi || !launched_by_mpirun()) return;
  int provided = 0;
  MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided);
  GS_CHECK_MSG(provided >= MPI_THREAD_FUNNELED, "MPI gives no thread support");
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
  mpi_ = true;
}

Ranks::~Ranks() {
  if (!mpi_) return;
  if (rank_ == 0 && !finished_) finish(1);
  MPI_Finalize();
}

Ranks& Ranks::world() {
  static Ranks r(true);
  return r;
}

Ranks& Ranks::single() {
  static Ranks r(false);
  return r;
}

void Ranks::send(int to, int tag, std::string_view payload) {
  GS_CHECK(mpi_ && to != rank_ && payload.size() < std::size_t{1} << 31);
  MPI_Send(payload.data(), static_cast<int>(payload.size()), MPI_CHAR, to, tag, MPI_COMM_WORLD);
}

namespace {

Ranks::Message take(const MPI_Status& status) {
  int n = 0;
  MPI_Get_count(&status, MPI_CHAR, &n);
  Ranks::Message m{status.MPI_SOURCE, status.MPI_TAG, std::string(std::size_t(n), '\0')};
  MPI_Recv(m.payload.data(), n, MPI_CHAR, m.from, m.tag, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
  return m;
}

}  // namespace

std::optional<Ranks::Message> Ranks::poll() {
  if (!mpi_) return std::nullopt;
  int flag = 0;
  MPI_Status status;
  MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &flag, &status);
  if (!flag) return std::nullopt;
  return take(status);
}

Ranks::Message Ranks::receive() {
  GS_CHECK(mpi_);
  // Not MPI_Probe: Open MPI spins a core in a blocking wait, and ranks wait while rank 0 fits.
  for (;;) {
    if (auto m = poll()) return *m;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
}

int Ranks::finish(int exit_code) {
  if (!mpi_ || finished_) return exit_code;
  finished_ = true;
  if (rank_ == 0) {
    const std::string code = std::to_string(exit_code);
    for (int r = 1; r < size_; ++r) send(r, kFinishTag, code);
    return exit_code;
  }
  for (;;) {
    const Message m = receive();
    if (m.tag == kFinishTag) return std::stoi(m.payload);
  }
}

}  // namespace gs
