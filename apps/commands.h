#pragma once
// Each subcommand registers itself on the top-level app; main.cpp only lists them.
#include <CLI/CLI.hpp>
#include <filesystem>

namespace gs::app {

void add_run_command(CLI::App& app);
void add_resume_command(CLI::App& app);
// --checkpoint-every of run and resume.
void add_checkpoint_option(CLI::App& sub, double& every);
void add_render_command(CLI::App& app);
void add_bench_command(CLI::App& app);
void add_movie_command(CLI::App& app);
// For `grainshock resume DIR`: whether DIR is a movie folder (movie.toml), and going on from its
// checkpoint. resume_movie returns the exit code; UserError for a movie that cannot be resumed.
bool is_movie_folder(const std::filesystem::path& dir);
int resume_movie(const std::filesystem::path& dir, bool quiet, double checkpoint_every);
void add_ensemble_command(CLI::App& app);
void add_merge_command(CLI::App& app);
void add_figures_command(CLI::App& app);
// For `grainshock resume DIR` of a figures folder (jobs::is_unfinished_figures_folder): the job
// of its figures.toml, on `threads`; returns the exit code.
int resume_figures(const std::filesystem::path& dir, int threads, bool quiet);
void add_compare_command(CLI::App& app);
void add_view_command(CLI::App& app);

}  // namespace gs::app
