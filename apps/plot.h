#pragma once
// gnuplot as a program: figures are a CSV plus a .gp script beside the PNG, so that a user can
// restyle them by editing the script and running `gnuplot fig.gp` in the folder.
#include <filesystem>
#include <string>

namespace gs::app {

// Preamble of every script: PNG terminal, CSV input, a readable style.
std::string gnuplot_preamble(const std::string& png, int width, int height);

// Writes `script` to dir/name and runs gnuplot on it in `dir`. Returns an empty string on
// success, else what went wrong (gnuplot missing, script error) in one line.
std::string run_gnuplot(const std::filesystem::path& dir, const std::string& name,
                        const std::string& script);

}  // namespace gs::app
