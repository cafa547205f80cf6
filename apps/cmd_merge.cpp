// `grainshock merge DIR... --out OUT`: combines ensemble folders holding realisations/ (written
// with --per-realisation, e.g. split over cluster jobs with --realisation F --realisations M, or
// left by a killed ensemble) into the folder the one-shot ensemble would have written, byte for
// byte (exact sums, analysis/ensemble.h).
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
#include "io/output_dir.h"
#include "sim/error.h"
#include "sim/stop.h"

namespace gs::app {
namespace {

namespace fs = std::filesystem;

struct MergeOptions {
  std::vector<std::string> inputs;
  std::string out;
  bool force = false, quiet = false;
  int resamples = 1000;
  std::vector<double> window;
};

// Whether `inner` is `outer` or lies inside it, after resolving links and dots.
bool within(const fs::path& inner, const fs::path& outer) {
  std::error_code ec;
  const fs::path a = fs::weakly_canonical(inner, ec), b = fs::weakly_canonical(outer, ec);
  auto ia = a.begin(), ib = b.begin();
  for (; ib != b.end() && !ib->empty(); ++ia, ++ib)
    if (ia == a.end() || *ia != *ib) return false;
  return true;
}

void run(const MergeOptions& o) {
  const auto t0 = std::chrono::steady_clock::now();
  if (o.inputs.empty()) throw UserError("merge: give at least one ensemble folder");
  // A stop while the inputs are read leaves the output folder untouched (exit 130).
  install_stop_handlers();
  // Read and check everything before the output folder is touched.
  std::optional<EnsembleSpec> first;
  std::string first_dir;
  std::vector<std::pair<std::uint64_t, fs::path>> parts;
  for (const auto& in : o.inputs) {
    throw_if_stopped();
    const fs::path dir(in);
    if (within(o.out, dir))
      throw UserError("--out " + o.out + ": is the input " + in +
                      " or inside it (merging into an input would overwrite it)");
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
    const auto found = finished_realisations(rdir, s);
    // A folder whose ensemble did not finish (killed, or still running) gives what it holds.
    if (found.empty())
      throw UserError(in + ": no finished realisation yet (resume it with: grainshock resume " +
                      in + ")");
    if (found.size() < s.realisations && !o.quiet)
      std::fprintf(stderr,
                   "grainshock: %s: %zu of %llu realisations finished (an unfinished ensemble; "
                   "merging those)\n",
                   in.c_str(), found.size(), static_cast<unsigned long long>(s.realisations));
    for (auto index : found) parts.emplace_back(index, rdir / realisation_folder(index));
  }
  std::sort(parts.begin(), parts.end());
  for (std::size_t k = 1; k < parts.size(); ++k)
    if (parts[k].first == parts[k - 1].first)
      throw UserError(parts[k].second.string() + ": realisation " + std::to_string(parts[k].first) +
                      " is also in " + parts[k - 1].second.string());
  const FitOptions fit = jobs::fit_options(o.resamples, o.window, *first);
  EnsembleSums sums(*first);
  for (const auto& [index, p] : parts) {
    throw_if_stopped();
    sums.add(read_realisation(p, index), p.string());
  }
  const auto dir = prepare_output_dir(o.out, o.force);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const EnsembleFits fits = jobs::write_ensemble_folder(dir, sums, fit, wall, 1, 0);
  std::fputs(exponent_table(sums, fits).c_str(), stdout);
  if (!o.quiet)
    std::fprintf(stderr, "grainshock: merged %llu realisations from %zu folders into %s\n",
                 static_cast<unsigned long long>(sums.count()), o.inputs.size(), dir.c_str());
}

}  // namespace

void add_merge_command(CLI::App& app) {
  auto opt = std::make_shared<MergeOptions>();
  auto* sub = app.add_subcommand(
      "merge",
      "Combine ensemble folders holding realisations/ (--per-realisation, or killed) into one "
      "ensemble; prints the exponents on stdout");
  sub->add_option("folders", opt->inputs, "Ensemble folders (same physics and sampling)")
      ->required();
  add_output_options(*sub, opt->out, opt->force, opt->quiet)->required();
  add_fit_options(*sub, opt->resamples, opt->window);
  sub->callback([opt] { run(*opt); });
}

}  // namespace gs::app
