// Ranks in a build without MPI: always this process alone.
#include "analysis/ensemble_ranks.h"

#include "sim/error.h"

namespace gs {

Ranks::Ranks(bool) {}
Ranks::~Ranks() = default;

Ranks& Ranks::world() {
  static Ranks r(false);
  return r;
}

Ranks& Ranks::single() {
  return world();
}

void Ranks::send(int, int, std::string_view) {
  GS_CHECK_MSG(false, "send with a single rank");
}

std::optional<Ranks::Message> Ranks::poll() {
  return std::nullopt;
}

Ranks::Message Ranks::receive() {
  GS_CHECK_MSG(false, "receive with a single rank");
  return {};
}

int Ranks::finish(int exit_code) {
  finished_ = true;
  return exit_code;
}

}  // namespace gs
