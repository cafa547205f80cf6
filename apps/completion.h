#pragma once
// Shell completion and the command reference generated from the command tree, so that neither
// lags behind the flags.
#include <CLI/CLI.hpp>
#include <string>

namespace gs::app {

// A bash script defining _grainshock and `complete -F _grainshock grainshock`: subcommands after
// `grainshock`, each subcommand's flags after it, file names elsewhere.
std::string bash_completion(CLI::App& app);

// The command reference in Markdown (docs/commands.md): each subcommand's description, a table
// of its flags (value, default, help) and its footer. Machine-dependent defaults are named, not
// printed, so that the file is the same wherever it is made.
std::string markdown_reference(CLI::App& app);

// `grainshock completion bash` prints the script, `grainshock completion markdown` the reference.
void add_completion_command(CLI::App& app);

}  // namespace gs::app
