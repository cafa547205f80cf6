#pragma once
// What `grainshock figures` writes beside its figures: summary.json (every case and comparison,
// for programs) and report.md (the same for a reader, with the definitions and notes).
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "analysis/paper.h"
#include "jobs/figures_plots.h"

namespace gs::jobs {

// How the figures were made.
struct FiguresRun {
  FiguresMode mode = FiguresMode::Quick;
  std::uint64_t seed = 1;
  int threads = 1;
  double wall = 0, simulation_wall = 0;  // seconds: all of it, and the ensembles alone
  // Realisations read from the folders of an earlier, stopped process (resume), whose time the
  // walls do not count.
  std::uint64_t resumed = 0;
  FiguresPlan::Fig1 fig1;  // what Fig. 1 shows, for the list of files
};

void write_figures_summary(const std::filesystem::path& dir, const FiguresRun& run,
                           const std::vector<CaseResult>& results,
                           const std::vector<Comparison>& cmp,
                           const std::vector<std::string>& problems);

void write_figures_report(const std::filesystem::path& dir, const FiguresRun& run,
                          const std::vector<CaseResult>& results, const Crossovers& crossovers,
                          const std::vector<Comparison>& cmp,
                          const std::vector<std::string>& problems);

}  // namespace gs::jobs
