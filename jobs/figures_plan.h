#pragma once
// What `grainshock figures` runs: one ensemble per (d, r), sized per mode. Times are chosen so
// that the front stays well inside the periodic box (its outer edge below L/2 at t_max), and
// the snapshot times of the 2D and 3D r = 0.1 ensembles are the paper's Figs. 4 and 5 times
// scaled to the run (the paper's are 25000, 37500, 50000 and 30000, 50000, 75000 in its unit).
#include <algorithm>
#include <string>
#include <vector>

#include "analysis/realisation.h"

namespace gs::jobs {

enum class FiguresMode { Tiny, Quick, Full };

// Paper: one (d, r) of the paper's figures (and the added r of the phi1 fit). DeltaScan: the
// scan of the cutoff delta (2D, r = 0.1) that measures t_c2 ~ delta^-phi2, only in fig7 and the
// phi2 comparison. Elastic3D: the 3D elastic blast run big and long enough for its plateau.
// Long3D (opt-in, `figures --long`): 3D r = 0.1 and 0.5 to t = 1e6, to show whether 3D alpha =
// 1/4 is reached on a plateau that passes the drift rule; their exponents are compared, their
// t_c1 stay out of phi1 (the paper cases of the same r give it).
// Limit (opt-in, `figures --limit`): 2D and 3D r = 0.9 and 0.95 in the unbounded
// medium, run until E_t's local slope has plateaued, and (not in --tiny) r = 0.97, 0.98, 0.99
// run only until <E_t> has fallen to E_0/2; their t_c1 and energy curves join phi1's readings
// between neighbouring r, in place of a paper case of the same (d, r).
// Snowplow (opt-in, `figures --snowplow`): 3D and 2D r = 0.1 and 0.5 in the unbounded medium, run
// long enough that the local slopes of R_t, N_t, E_t and P_r can tell the momentum-conserving
// snowplow (alpha = 1/(d+1)) from the pressure-driven one (2/(d+4), analysis/snowplow.h); their
// exponents are reported, not counted, and stay out of phi1.
// Packing: 2D r = 0.1, 0.5, 0.8 at the paper's delta = 1e-4 with snapshots over the last decade,
// for the band packing alone (its counted reading; the paper cases run at 1e-5).
enum class CaseRole { Paper, DeltaScan, Elastic3D, Long3D, Limit, Snowplow, Packing };

struct FigureCase {
  std::string name;  // folder under ensembles/, e.g. "d2_r0.1"
  EnsembleSpec spec;
  CaseRole role = CaseRole::Paper;
  bool delta_scan = false;  // role == DeltaScan
  // The small 3D r = 1 case beside d3_r1_large: kept for Fig. 3, its alpha readings not counted
  // (its box is too small for the late elastic blast).
  bool superseded_for_alpha = false;
  // The case of the paper's Figs. 4 and 5 (its smallest r in each dimension): the collapse of
  // P(R,t) and P(v,t) is read on it.
  bool collapse = false;
  // The snapshot times Figs. 4 and 5 draw: the paper's (kFig4PaperTimes, kFig5PaperTimes) in
  // simulation units when the run reaches them (paper_times), else the paper's in ratio ending at
  // t_max. A run longer than the paper's times also has a snapshot at t_max, where the readings
  // of the last snapshot (packing, inner edge) are made.
  std::vector<double> figure_times;
  bool paper_times = false;
  // Limit: the time from which E_t's local slope is expected to be on its plateau (the plan's
  // comment says where each comes from); t_max lies at least half a decade past it, the span
  // the plateau rule needs (analysis/effective_exponent.h). 0: not run to its plateau (3D
  // r = 0.95, whose plateau would take 2.4 days, and --tiny's smoke cases).
  double plateau_start = 0;
  // The time --estimate's sample runs to (0: t_max); its cost is extrapolated to t_max from the
  // growth of the collisions at the sample's end (jobs/figures_job.cpp).
  double estimate_t_max = 0;
  // Realisations run at once at the most (0: one per thread): a case whose realisation needs
  // more than half the machine's memory runs them one at a time.
  int concurrent = 0;
  int threads_of(int threads) const {
    return concurrent > 0 ? std::min(threads, concurrent) : threads;
  }
};

struct FiguresPlan {
  FiguresMode mode = FiguresMode::Quick;
  std::vector<FigureCase> cases;
  // Fig. 1: one realisation of the 2D r = 0.1 case's physics drawn at a_times (overlay, the last
  // its t_max) and one of the 2D r = 1 case's at its t_max (simulation units). Quick and full: in the paper's box
  // (2.5e5 discs) at the paper's times; tiny: in the tiny cases' boxes, the paper's times scaled
  // to the r = 0.1 case's t_max (paper_times false), which the report says.
  struct Fig1 {
    PhysicsConfig a, b;
    std::vector<double> a_times;
    bool paper_times = true;
  } fig1;
};

const char* to_string(FiguresMode m);
// long_3d: add the Long3D cases to the mode's plan; limit: the Limit cases (in --tiny scaled down
// like the rest of it, to a smoke run), of dimension limit_dim only if it is 2 or 3 (the 2D ones
// take minutes, the 3D ones days).
FiguresPlan figures_plan(FiguresMode mode, std::uint64_t seed, bool long_3d = false,
                         bool limit = false, int limit_dim = 0, bool snowplow = false);

// The case of dimension d and restitution r, or nullptr.
const FigureCase* find_case(const FiguresPlan& plan, int d, double r);

}  // namespace gs::jobs
