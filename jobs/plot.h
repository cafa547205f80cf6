#pragma once
// gnuplot as a program: figures are a CSV plus a .gp script beside the picture, so that a user can
// restyle them by editing the script and running `gnuplot fig.gp` in the folder. A script writes
// fig.png by default and fig.svg or fig.pdf with `gnuplot -e "format='svg'" fig.gp` (gnuplot's
// svg and cairo terminals, all in Debian's gnuplot-nox).
#include <filesystem>
#include <string>
#include <vector>

namespace gs::jobs {

// "png,svg,pdf" -> {"png", "svg", "pdf"}; UserError naming --format for anything else or none.
std::vector<std::string> parse_plot_formats(const std::string& list);

// Preamble of every script: the terminal chosen by the variable `format` (png unless given),
// output `base.format`, UTF-8 enhanced text (Greek letters, t^{2/3}), CSV input, margins that
// keep the last tick label inside the picture, a readable style.
std::string gnuplot_preamble(const std::string& base, int width, int height);

// Writes `script` to dir/name and runs gnuplot on it once per format, in `dir`, without a shell
// (any folder name works). Returns an empty string on success, else what went wrong (gnuplot
// missing, script error) in one line.
std::string run_gnuplot(const std::filesystem::path& dir, const std::string& name,
                        const std::string& script,
                        const std::vector<std::string>& formats = {"png"});

}  // namespace gs::jobs
