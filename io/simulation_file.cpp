#include "io/simulation_file.h"

#include <string>

#include "io/checkpoint.h"
#include "sim/error.h"

namespace gs {
namespace {

constexpr const char* kTag = "grainshock simulation";

}  // namespace

void save_simulation(const Simulation& sim, const std::filesystem::path& path) {
  const PhysicsConfig& c = sim.config();
  CheckpointWriter out(path, path.string() + ".previous",
                       StateIdentity{c.dim, static_cast<std::uint64_t>(c.particles)});
  out.string(kTag);
  out.value(c);
  sim.save(out);
  out.commit();
  std::error_code ec;
  std::filesystem::remove(path.string() + ".previous", ec);  // one file is what the user asked
}

std::unique_ptr<Simulation> load_simulation_file(const std::filesystem::path& path) {
  CheckpointReader in(path);
  if (in.string() != kTag)
    throw UserError("'" + path.string() + "' is a checkpoint, but not of a saved Simulation");
  const auto c = in.value<PhysicsConfig>();
  auto sim = load_simulation(c, in);
  in.finish();
  return sim;
}

}  // namespace gs
