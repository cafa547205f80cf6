#include "analysis/realisation_in_flight.h"

#include <string>
#include <vector>

#include "io/checkpoint.h"
#include "sim/error.h"

namespace gs {
namespace {

constexpr const char* kTag = "grainshock realisation in flight 1";

std::filesystem::path previous_of(const std::filesystem::path& file) {
  return file.string() + ".previous";
}

}  // namespace

void save_in_flight(const std::filesystem::path& file, const EnsembleSpec& spec,
                    std::uint64_t index, std::size_t next_sample, const Simulation& sim,
                    const Recorder& recorder, const Realisation& partial) {
  const PhysicsConfig& c = sim.config();
  CheckpointWriter out(file, previous_of(file),
                       StateIdentity{c.dim, static_cast<std::uint64_t>(c.particles)});
  out.string(kTag);
  out.string(spec_identity(spec));
  out.value(index);
  out.value(static_cast<std::uint64_t>(next_sample));
  const std::vector<RealisationFile> files = realisation_files(partial);
  out.value(static_cast<std::uint64_t>(files.size()));
  for (const auto& f : files) {
    out.string(f.name);
    out.string(f.text);
  }
  recorder.save(out);
  sim.save(out);
  out.commit();
  std::error_code ec;
  std::filesystem::remove(previous_of(file), ec);
}

std::unique_ptr<Simulation> load_in_flight(const std::filesystem::path& file,
                                           const EnsembleSpec& spec, std::uint64_t index,
                                           Recorder& recorder, Realisation& partial,
                                           std::size_t& next_sample) {
  std::error_code ec;
  std::filesystem::path path = file;
  // A kill between the two renames of a write leaves only the previous state.
  if (!std::filesystem::exists(path, ec)) path = previous_of(file);
  if (!std::filesystem::exists(path, ec)) return nullptr;
  CheckpointReader in(path);
  std::string name = "'";  // appended: GCC 12 warns falsely (-Wrestrict) on "'" + std::string
  name.append(path.string()).append("'");
  if (in.string() != kTag) throw UserError(name + ": not a realisation in flight");
  if (in.string() != spec_identity(spec) || in.value<std::uint64_t>() != index)
    throw UserError(name + ": in flight for another ensemble or realisation");
  const auto next = in.value<std::uint64_t>();
  in.expect(in.value<std::uint64_t>() == kRealisationFiles.size());
  std::vector<RealisationFile> files(kRealisationFiles.size());
  for (auto& f : files) {
    f.name = in.string();
    f.text = in.string();
  }
  partial = parse_realisation(files, index, path);
  // The rows are those of the sample times before `next`, and the snapshots those among them.
  const std::vector<double> times = sample_times(spec);
  in.expect(next <= times.size() && partial.timeseries.rows() == next &&
            partial.snapshots.size() <= spec.snapshot_times.size());
  recorder.load(in);
  PhysicsConfig c = spec.physics;
  c.realisation = index;
  auto sim = load_simulation(c, in);
  in.finish();
  next_sample = static_cast<std::size_t>(next);
  return sim;
}

void remove_in_flight(const std::filesystem::path& file) {
  std::error_code ec;
  std::filesystem::remove(file, ec);
  std::filesystem::remove(previous_of(file), ec);
}

}  // namespace gs
