#pragma once
// Shell completion generated from the command tree, so it never lags behind the flags.
#include <CLI/CLI.hpp>
#include <string>

namespace gs::app {

// A bash script defining _grainshock and `complete -F _grainshock grainshock`: subcommands after
// `grainshock`, each subcommand's flags after it, file names elsewhere.
std::string bash_completion(CLI::App& app);

// `grainshock completion bash` prints that script.
void add_completion_command(CLI::App& app);

}  // namespace gs::app
