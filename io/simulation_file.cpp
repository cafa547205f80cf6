#include "io/simulation_file.h"

#include <string>

#include "io/checkpoint.h"
#include "sim/error.h"

namespace gs {
namespace {

// The PhysicsConfig is stored as its bytes, so the tag changes with its layout: version 2 added
// `medium`. A file of an older layout is named as such instead of being misread.
constexpr const char* kTag = "grainshock simulation 2";
constexpr const char* kOldTag = "grainshock simulation";

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
  const std::string tag = in.string();
  if (tag == kOldTag)
    throw UserError("'" + path.string() +
                    "' was saved by an older grainshock (before --medium): load it with that "
                    "version, or run it again");
  if (tag != kTag)
    throw UserError("'" + path.string() + "' is a checkpoint, but not of a saved Simulation");
  const auto c = in.value<PhysicsConfig>();
  auto sim = load_simulation(c, in);
  in.finish();
  return sim;
}

}  // namespace gs
