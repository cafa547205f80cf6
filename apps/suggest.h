#pragma once
// Usage errors that name the word typed and suggest the nearest valid one, as git and cargo do:
//   grainshock rnu          -> unknown subcommand 'rnu'; did you mean 'run'?
//   run --partcles 10       -> unknown flag '--partcles' for 'run'; did you mean '--particles'?
#include <CLI/CLI.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace gs::app {

// Optimal-string-alignment distance: insertions, deletions, substitutions and transpositions of
// neighbours each cost 1 (Damerau 1964), so "rnu" is one edit from "run".
std::size_t edit_distance(std::string_view a, std::string_view b);

// The candidate nearest to `word`, if it is within max(1, |word| / 3) edits (a likely typo
// rather than another word); the first of equally near ones.
std::optional<std::string> nearest(std::string_view word,
                                   const std::vector<std::string>& candidates);

// The one-line message for a parse error of `args` (argv without the program name): the first
// unknown subcommand or flag with a suggestion, else CLI11's own message.
std::string explain_parse_error(CLI::App& app, const std::vector<std::string>& args,
                                const CLI::ParseError& error);

}  // namespace gs::app
