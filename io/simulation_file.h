#pragma once
// A simulation alone in a checkpoint file (io/checkpoint.h), with the physics that made it: what
// the Python module's Simulation.save and Simulation.load use. A run folder's checkpoint holds
// more (its sample grid, its files) and is read by `resume`, not here.
#include <filesystem>
#include <memory>

#include "sim/engine.h"

namespace gs {

// Writes atomically (temporary file, then rename); UserError naming the file on failure.
void save_simulation(const Simulation& sim, const std::filesystem::path& path);
// The simulation save_simulation wrote, continuing the same history event for event. UserError
// naming the file for anything else (a run folder's checkpoint included).
std::unique_ptr<Simulation> load_simulation_file(const std::filesystem::path& path);

}  // namespace gs
