#pragma once
// Pieces shared by the subcommands: the TOML config file, the physics flags of the design's
// contract, and the output folder that never overwrites earlier results by accident.
#include <CLI/CLI.hpp>
#include <filesystem>
#include <span>
#include <string>
#include <string_view>

#include "sim/config.h"

namespace gs::app {

// Adds --config FILE (TOML, keys = long flag names; flags given on the command line win).
void add_config_option(CLI::App& sub);

// Parses the settings file a command wrote into its folder (run.toml, movie.toml, figures.toml)
// as `grainshock COMMAND --config FILE`: `app` holds the subcommand COMMAND with its flags (and
// --config); UserError naming the file when a value is refused.
void parse_settings_file(CLI::App& app, const std::string& command,
                         const std::filesystem::path& file);

// Every option of `sub` that was given or has a default, as TOML lines `name = value` (the long
// flag name, or a positional argument's name) that --config reads back: the run file of a
// command whose settings are all flags. Help, version, --config and the output-folder flags
// (--out, --force, --quiet) are left out, since they do not shape the results, and so are the
// options named in `left_out`. Input files (input_files) given as relative paths are written
// relative to `file_dir`, the folder of the file the text goes into, which --config reads them
// from, so the file works from any folder; absolute paths stay as given.
std::string settings_toml(const CLI::App& sub, std::span<const std::string_view> left_out = {},
                          const std::filesystem::path& file_dir = {});

// Marks `opt` as naming input files (its type in --help reads FILE): in a --config file its
// relative paths are taken from the file's folder. Returns `opt`.
inline constexpr const char* kInputFilesType = "FILE";
CLI::Option* input_files(CLI::Option* opt);
bool is_input_files(const CLI::Option& opt);

// Lets a count be written as physicists write it, 2e6 or 1e12, when it is a whole number: the
// option's integer conversion then sees the digits (so its range checks still apply).
CLI::Validator whole_number();

// Every number option of every subcommand of `app` (CLI11's INT, UINT and FLOAT): text that
// CLI11's conversion would turn into another number than the one typed is refused (exit 2,
// naming the flag and the text): an empty value (read as 0), a negative value of an unsigned
// option (read as 2^64 - 1), an integer past 64 bits (read as the largest), a decimal beyond a
// double's range (read as inf, or as 0 for 1e-400). Call once every option exists.
void check_number_text(CLI::App& app);

// A number's bounds as a check that says them in a few digits (CLI::NonNegativeNumber and
// PositiveNumber print DBL_MAX in full, 300 digits).
CLI::Validator non_negative();
CLI::Validator positive();

// A picture file's name: it must end in .png (any case), since PNG is all that is written, so
// that --out x.jpg is refused (exit 2, naming the file) instead of given PNG bytes.
CLI::Validator png_name();

// The physics flags shared by run, ensemble and movie.
void add_physics_options(CLI::App& sub, PhysicsConfig& c);
// --medium when neither the command line nor --config gives it: default_medium() of the physics
// given, or the box if `box`. Call once every flag is read; it becomes the option's default, so
// that the files settings_toml() writes state it.
void apply_medium_default(CLI::App& sub, PhysicsConfig& c, bool box = false);

// --out DIR, --force and --quiet of every command that writes a folder; returns --out so a
// command without a default folder can make it required.
CLI::Option* add_output_options(CLI::App& sub, std::string& out, bool& force, bool& quiet);

// --checkpoint-every SECONDS of the commands that run ensembles (`ensemble`, `figures`), into
// `minutes`, as run, movie and resume take it; and --checkpoint-minutes, which it replaces and
// which still works (deprecated_checkpoint_minutes() says so).
void add_checkpoint_minutes_option(CLI::App& sub, double& minutes);
// Whether --checkpoint-minutes was given on the command line (not in a --config file, where our
// own figures.toml writes it): one line on stderr then names its replacement.
void deprecated_checkpoint_minutes(const CLI::App& sub, bool quiet);

}  // namespace gs::app
