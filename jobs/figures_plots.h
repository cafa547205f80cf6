#pragma once
// The figures of `grainshock figures` from the ensembles of a FiguresPlan: Fig. 1 drawn by the
// renderer, the others as a CSV beside the gnuplot script that draws it (jobs/plot.h); and the
// crossover points of the phi1 and phi2 fits, which figs. 6 and 7 and the report share.
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "analysis/energy_scaling.h"
#include "analysis/ensemble_output.h"
#include "analysis/paper.h"
#include "jobs/figures_plan.h"
#include "sim/snapshot.h"

namespace gs::jobs {

// One case of the plan, run.
struct CaseResult {
  const FigureCase* plan = nullptr;
  EnsembleSums sums;
  EnsembleFits fits;
  double wall = 0;  // seconds
};

// The crossover times of one rule in one dimension and their phi fit.
struct CrossoverSet {
  int d = 2;
  std::string rule;  // in the figure's key; empty for the only rule
  std::vector<CrossoverPoint> points;
  CrossoverExponentFit fit;
  bool open = false;  // drawn with open symbols: a reading beside the reported one
  int symbol = 0;     // gnuplot point type; 0: a circle (filled, or open as above)
  double to_paper = 1;  // paper time units per simulation time unit: the figures' times are in them
  std::vector<LocalCrossoverExponent> local;  // between neighbouring points (tc1 only)
  // phi1 from the energy curves between neighbouring r, no plateau needed (tc1 only,
  // analysis/energy_scaling.h): per pair the collapse, then each fixed fraction of E_0.
  std::vector<Phi1Reading> energy;
};

// t_c1 against 1 - r^2 for each dimension (phi1, from every r < 1, the Limit cases of
// `figures --limit` in place of the paper cases of their r) by the intersection rule and,
// beside it, with E_t's exponent fixed at the theory's; t_c2 against the cutoff delta (phi2,
// from the 2D r = 0.1 scan).
// `fractions`: per dimension and fraction f of E_0, the time <E_t> first falls to f E_0 against
// 1 - r^2, whose ratios between neighbouring r are the level readings of phi1 (fig10; no fit
// across all r, which would mix regimes).
struct Crossovers {
  std::vector<CrossoverSet> tc1, tc1_theory_b, tc2, fractions;
};
Crossovers crossovers_of(const std::vector<CaseResult>& results);

// "fig8_local_slopes_<case>.png": the figure an exponent of the case was read from.
std::string slope_figure_of(const FigureCase& c);

// Fig. 1's snapshots: the r = 0.1 realisation at each of the plan's times, the r = 1 one at its.
struct Fig1Snapshots {
  std::vector<Snapshot> a;
  Snapshot b;
};
Fig1Snapshots run_fig1(const FiguresPlan::Fig1& f);

// Writes every figure into `dir` in `formats` (png, svg, pdf); returns what could not be drawn.
std::vector<std::string> write_figures(const FiguresPlan& plan,
                                       const std::vector<CaseResult>& results,
                                       const Crossovers& crossovers,
                                       const std::filesystem::path& dir,
                                       const std::vector<std::string>& formats);

// The y-range of a local-slope panel of Fig. 8: the 5-95% quantiles of the local slope where the
// exponent is read (the last decade, and the plateau fit's window), widened to the theory and the
// fit and padded by the band's median half width. Min and max let the first collisions' noise
// (R_front quantised in shells: local slopes of +-3 at t ~ 100) squash the part that matters.
// NaNs when the slope has no finite value there.
std::pair<double, double> slope_yrange(const ExponentFit& e);

// x to `digits` significant digits, "n/a" when not finite: numbers in figure keys and reports.
std::string figure_number(double x, int digits = 4);

}  // namespace gs::jobs
