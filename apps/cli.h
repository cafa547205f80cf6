#pragma once
// Pieces shared by the subcommands: the TOML config file, the physics flags of the design's
// contract, and the output folder that never overwrites earlier results by accident.
#include <CLI/CLI.hpp>
#include <filesystem>
#include <string>

#include "sim/atomic_file.h"
#include "sim/config.h"

namespace gs::app {

// Adds --config FILE (TOML, keys = long flag names; flags given on the command line win).
void add_config_option(CLI::App& sub);

// The physics flags shared by run, ensemble and movie.
void add_physics_options(CLI::App& sub, PhysicsConfig& c);

// --out DIR, --force and --quiet of every command that writes a folder; returns --out so a
// command without a default folder can make it required.
CLI::Option* add_output_options(CLI::App& sub, std::string& out, bool& force, bool& quiet);

// Creates `dir` for a new run. An existing non-empty folder is refused unless `force`;
// nothing in it is deleted either way (files are replaced one by one as they are written).
std::filesystem::path prepare_output_dir(const std::string& dir, bool force);

}  // namespace gs::app
