// `grainshock merge DIR... --out OUT`: combines ensemble folders written with --per-realisation
// (e.g. split over cluster jobs with --realisation F --realisations M) into the folder the
// one-shot ensemble would have written, byte for byte (exact sums, analysis/ensemble.h).
#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>

#include "analysis/ensemble_output.h"
#include "analysis/ensemble_runner.h"
#include "apps/cli.h"
#include "apps/commands.h"
#include "apps/ensemble_cli.h"
#include "sim/error.h"

namespace gs::app {
namespace {

struct MergeOptions {
  std::vector<std::string> inputs;
  std::string out;
  bool force = false, quiet = false;
  int resamples = 1000;
  std::vector<double> window;
};

void run(const MergeOptions& o) {
  namespace fs = std::filesystem;
  const auto t0 = std::chrono::steady_clock::now();
  if (o.inputs.empty()) throw UserError("merge: give at least one ensemble folder");
  // Read and check everything before the output folder is touched.
  std::optional<EnsembleSpec> first;
  std::string first_dir;
  std::vector<std::pair<std::uint64_t, fs::path>> parts;
  for (const auto& in : o.inputs) {
    const fs::path dir(in);
    if (!fs::is_regular_file(dir / "ensemble.toml"))
      throw UserError(in + ": not an ensemble folder (no ensemble.toml)");
    const EnsembleSpec s = read_spec(dir / "ensemble.toml");
    if (!first) {
      first = s;
      first_dir = in;
    } else if (spec_identity(s) != spec_identity(*first)) {
      throw UserError(in + ": different physics or sampling from " + first_dir +
                      " (compare their ensemble.toml)");
    }
    const fs::path rdir = dir / "realisations";
    if (!fs::is_directory(rdir))
      throw UserError(in + ": no realisations/ folder (run ensemble with --per-realisation)");
    for (std::uint64_t k = 0; k < s.realisations; ++k) {
      const std::uint64_t index = s.physics.realisation + k;
      const fs::path p = rdir / realisation_folder(index);
      if (!fs::is_directory(p))
        throw UserError(p.string() + ": missing (the folder says it holds " +
                        std::to_string(s.realisations) + " realisations)");
      parts.emplace_back(index, p);
    }
  }
  std::sort(parts.begin(), parts.end());
  for (std::size_t k = 1; k < parts.size(); ++k)
    if (parts[k].first == parts[k - 1].first)
      throw UserError(parts[k].second.string() + ": realisation " + std::to_string(parts[k].first) +
                      " is also in " + parts[k - 1].second.string());
  FitOptions fit;
  fit.window = window_of(o.window, *first);
  fit.resamples = o.resamples;
  EnsembleSums sums(*first);
  for (const auto& [index, p] : parts) sums.add(read_realisation(p, index), p.string());
  const auto dir = prepare_output_dir(o.out, o.force);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  write_ensemble_folder(dir, sums, fit, wall, 1);
  if (!o.quiet)
    std::fprintf(stderr, "grainshock: merged %llu realisations from %zu folders into %s\n",
                 static_cast<unsigned long long>(sums.count()), o.inputs.size(), dir.c_str());
}

}  // namespace

void add_merge_command(CLI::App& app) {
  auto opt = std::make_shared<MergeOptions>();
  auto* sub = app.add_subcommand(
      "merge", "Combine ensemble folders made with --per-realisation into one ensemble");
  sub->add_option("folders", opt->inputs, "Ensemble folders (same physics and sampling)")
      ->required();
  add_output_options(*sub, opt->out, opt->force, opt->quiet)->required();
  sub->add_option("--resamples", opt->resamples, "Bootstrap resamples of the exponent intervals")
      ->capture_default_str();
  add_window_option(*sub, opt->window);
  sub->callback([opt] { run(*opt); });
}

}  // namespace gs::app
