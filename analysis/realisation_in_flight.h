#pragma once
// A realisation in flight as one checkpoint file (io/checkpoint.h): the engine's state, the
// recorder's, the sample time to reach next and the measures taken so far (the realisation's
// folder text, analysis/realisation.h, so that they come back to the bit). A 3D realisation of
// `figures --limit` runs for hours; from this file a killed one goes on where it was instead of
// from t = 0, and ends in the same bytes (the engine resumes event for event).
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <memory>

#include "analysis/realisation.h"
#include "sim/engine.h"
#include "sim/recorder.h"

namespace gs {

// Writes `file` whole or not at all (temporary, then rename); UserError naming it on failure.
// `next_sample` indexes sample_times(spec); `partial` holds the rows and snapshots before it.
void save_in_flight(const std::filesystem::path& file, const EnsembleSpec& spec,
                    std::uint64_t index, std::size_t next_sample, const Simulation& sim,
                    const Recorder& recorder, const Realisation& partial);

// The simulation `file` holds, with `recorder`, `partial` and `next_sample` as they were; nullptr
// if there is no file. UserError (one line naming the file) for one that is not whole, of
// another build, or of another ensemble or realisation.
std::unique_ptr<Simulation> load_in_flight(const std::filesystem::path& file,
                                           const EnsembleSpec& spec, std::uint64_t index,
                                           Recorder& recorder, Realisation& partial,
                                           std::size_t& next_sample);

// Removes `file` and what a kill between a write's two renames left beside it.
void remove_in_flight(const std::filesystem::path& file);

}  // namespace gs
