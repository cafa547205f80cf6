#include "jobs/figures_plan.h"

#include <cstdio>
#include <iterator>
#include <span>

#include "analysis/paper.h"
#include "sim/format.h"

namespace gs::jobs {
namespace {

// One (d, r) of the plan, sized per mode.
struct RunSize {
  double r;
  std::int64_t particles;
  double t_max;
  std::uint64_t realisations;
};

// The paper's r = 0.1, 0.5, 0.8 and 1, with 0.3, 0.7, 0.9 (and 0.85 in 3D) added so that phi1
// rests on six values of r, enough for a fit with its own error. The paper's r < 1 have the most
// realisations (Figs. 3-5 and the plateau fits), the added r fewer (only t_c1 and exponents are
// read from them).
//
// The largest r run farthest (t_c1 grows as r -> 1) and r = 1 fastest (R ~ t^(2/(d+2))); the
// times keep the front (where the active density falls to half the ambient) below ~0.7 L/2 and
// the outermost active particle below ~0.8 L/2, measured (2D: r = 0.8 at 1e5 reaches 176 of
// L/2 = 316 with 1e5 discs; 3D, 5e5 spheres, L/2 = 63: the front at 0.52-0.60 L/2 for r <= 0.8
// and at 0.71 L/2 for r = 0.9 at t = 8000; 4e6 spheres, L/2 = 126: 0.47-0.6 L/2 for r = 0.7-0.9
// at t = 1e5, R_front ~ t^0.24-0.29). The report lists R_front / (L/2) at t_max for every case.
//
// 3D, r >= 0.7: E_t's local slope reaches its plateau only after t ~ 2e4 (r = 0.7: -0.68 at 2e4,
// -0.71 from 3e4 to 1e5; r = 0.8 and 0.85: -0.66 to -0.69 and -0.63 to -0.68 over 2e4-1e5; r =
// 0.9: still -0.60 to -0.64 and drifting over 3e4-1e5, 2 realisations each of 4e6 spheres,
// delta = 1e-6), so --full runs them to 1e5 in boxes of 4e6 spheres (22, 21, 33 CPU-s per
// realisation) and leaves r = 0.9 short: it would need t ~ 1e6 and ~3e7 spheres. --quick cannot
// afford that and reaches t_c1 in 3D only for r <= 0.5; the report names the others.
//
// --quick (< 3 min on 2 cores; CPU time per realisation ~0.7-4.6 s in 2D and 1.4-3.8 s in 3D, the
// larger r costing more) keeps every figure and report section, at half the --full times in 2D
// (r = 0.9 also half, its t_c1 being ~1e2) and a sixth to a quarter in 3D, with 16 (2D) or 12
// (3D) realisations for the paper's r < 1 (bootstrap intervals ~2x wider than --full's), 12 or 8
// for the added r, 10 or 8 for r = 1. Measured on a quiet machine: 81 s wall.
//
// --full has the paper's sizes (2.5e5 discs, 2e6 spheres; 4e6 for 3D r = 0.7-0.85) but not its
// ~100 realisations per case, which would take ~2 h on 2 cores: 40 / 32 / 24 realisations in 2D
// (paper r, added r, r = 1) and 20 / 12 / 16 in 3D. --estimate of this plan (sample 2,
// measured at load ~7): 2641 CPU-s, 22.6 min on a quiet 2-core machine, of which 3D r = 0.7,
// 0.8, 0.85 and the 4e6-sphere elastic blast 159, 438, 372 and 166 CPU-s, 2D 930; realisations
// 2-5 of 3D r = 0.85 cost 13% more than the sample's 0-1. The last --full run (before 2D's
// cutoff went to 1e-5 and r = 0.95 was added) took 2931 CPU-s, 44 min wall on a shared machine.
std::vector<RunSize> sizes_of(FiguresMode m, int d) {
  switch (m) {
    case FiguresMode::Tiny:
      if (d == 2)
        return {{0.1, 3000, 1500, 3}, {0.3, 3000, 1500, 3}, {0.5, 3000, 1500, 3},
                {0.7, 3000, 1500, 3}, {0.8, 3000, 1500, 3}, {0.9, 3000, 1500, 3},
                {1.0, 3000, 150, 3}};
      return {{0.1, 5000, 1000, 3}, {0.3, 5000, 1000, 3}, {0.5, 5000, 1000, 3}, {0.7, 5000, 600, 3},
              {0.8, 5000, 600, 3},  {0.85, 5000, 600, 3}, {0.9, 5000, 600, 3},  {1.0, 5000, 80, 3}};
    case FiguresMode::Quick:
      if (d == 2)
        return {{0.1, 100000, 1e5, 16},  {0.3, 100000, 1e5, 12}, {0.5, 100000, 1e5, 16},
                {0.7, 100000, 1e5, 12},  {0.8, 100000, 1e5, 16}, {0.9, 100000, 5e4, 12},
                {1.0, 100000, 12000, 10}};
      return {{0.1, 500000, 30000, 12}, {0.3, 500000, 25000, 8}, {0.5, 500000, 20000, 12},
              {0.7, 500000, 10000, 8},  {0.8, 500000, 8000, 12}, {0.85, 500000, 7000, 8},
              {0.9, 500000, 6000, 8},   {1.0, 500000, 1200, 8}};
    case FiguresMode::Full:
    default:
      if (d == 2)
        // r = 0.95: phi1 nearest the elastic limit from 0.9 -> 0.95; its t_c1 is
        // ~4.6 times r = 0.9's (~3e2), the plateau from ~1e4.
        return {{0.1, 250000, 2e5, 40},  {0.3, 250000, 2e5, 32},  {0.5, 250000, 2e5, 40},
                {0.7, 250000, 2e5, 32},  {0.8, 250000, 2e5, 40},  {0.9, 250000, 1e5, 32},
                {0.95, 250000, 1e5, 24}, {1.0, 250000, 30000, 24}};
      return {{0.1, 2000000, 120000, 20}, {0.3, 2000000, 110000, 12}, {0.5, 2000000, 100000, 20},
              {0.7, 4000000, 100000, 12}, {0.8, 4000000, 100000, 20}, {0.85, 4000000, 100000, 12},
              {0.9, 2000000, 20000, 12},  {1.0, 2000000, 6000, 16}};
  }
}

// 3D, r < 1: the cutoff below which collisions are elastic is 1e-6, not the paper's 1e-4. With
// 1e-4, E_t's local slope turns back up (towards the elastic regime, t_c2: v_t ~ delta) before it
// plateaus: from t ~ 5e3 at r = 0.1 (-0.70 to -0.655 by 2.4e4, 5e5 spheres) and ~3e4 at r = 0.7
// (-0.69 to -0.63 by 6e4, 4e6 spheres, where 1e-6 gives -0.71 throughout); t_c2 ~ delta^-(4/3)
// comes ~460 times later at 1e-6. 2D keeps the paper's 1e-4: its late slopes are the same with
// 1e-6 (r = 0.1, 1e5 discs: -0.63 to -0.64 from 1e4 to 1e5 with either).
constexpr double kCutoff3D = 1e-6;

// 2D, r < 1: 1e-5. At the paper's 1e-4 the local slope of N_t in --full drifts from
// 0.66 to 0.72 over [8.9e3, 2e5], the start of the delta crossover (t_c2 ~ 2.7e5 at 1e-4 by the
// measured phi2); at 1e-6 (r = 0.1, 20 realisations) it is flat at 0.668 [0.662, 0.673]. 1e-6
// as in 3D costs ~6 times 1e-4 in 2D (r = 0.1, 1e5 discs, t = 1e5: ~9 CPU-s per realisation
// against 1.6), 1e-5 1.6 times (2.5 CPU-s), and t_c2 ~ delta^-3/2 comes 32 times later than at
// 1e-4, at ~8e6, 40 times the longest 2D run. The delta scan keeps its own larger cutoffs and
// measures t_c2 itself.
constexpr double kCutoff2D = 1e-5;

// --long: 3D r = 0.1 and 0.5 to t = 1e6 with delta = 1e-6, 16 realisations. The box was sized
// for the front to stay below ~0.6 L/2 by R_front ~ t^0.25 from the --quick fronts; run in 4e6
// spheres, it reached 0.59 L/2 (r = 0.1) and 0.72 L/2 (r = 0.5) at 1e6, the local slopes still
// rising (`figures --quick --long` at 81eb19d, 2935 CPU-s against 2665 estimated). r = 0.5 now
// runs in 8e6 spheres, whose L is 2^(1/3) larger: 0.72 / 1.26 = 0.57 L/2. A box, not the
// unbounded medium, because the box's cost per collision is 1.7 times lower in 3D
// (`bench sim/unbounded_vs_box_3d`) and its resting spheres are never touched. `--quick --long
// --estimate --sample 1`: 46 CPU-s per r = 0.1 realisation, 92 per r = 0.5 one, 2403 in all.
struct Long3D {
  double r;
  std::int64_t particles;
  double t_max;
  std::uint64_t realisations;
};
std::vector<Long3D> long3d_cases() {
  return {{0.1, 4000000, 1e6, 16}, {0.5, 8000000, 1e6, 16}};
}

// --limit: phi1 nearest the elastic limit, from 2D and 3D r = 0.9 and 0.95 run in
// the unbounded medium (sim/unbounded_medium.h) until E_t's local slope has plateaued. The
// plateau rule (analysis/effective_exponent.h, asymptotic_plateau) needs a window of at least
// half a decade ending near the last sample, so each t_max lies at least 0.5 decade past the
// time the plateau is expected to start:
//  - 3D r = 0.9: still drifting at 1e5 (above); r = 0.7's plateau starts at ~3e4, and scaled by
//    t_c1 ~ (1 - r^2)^-phi1 with phi1 = 2.5 (the measured value nearest the elastic limit,
//    2.5 +- 0.2) that is (0.19 / 0.51)^-2.5 = 12 times later, ~3.5e5: "needs t ~ 1e6", as
//    measured before. t_max 1.2e6, 0.53 decade past it. Measured since (12 realisations, stop
//    45): no plateau by 1.2e6 either, E_t's slope -0.675 at 3.5e5, -0.679 at 5e5 and -0.684 at
//    1.1e6, still bending towards -3/4; 3.5e5 stays the start the plan expected (and the bench's
//    length), not one the data show.
//  - 2D r = 0.9: plateaus by ~5e4-1e5 (N_t's and E_t's slopes of --full); from 1e5, t_max 4e5.
//  - r = 0.95: the start of r = 0.9 times ((1 - 0.95^2) / (1 - 0.9^2))^-phi1 = 0.513^-phi1, with
//    phi1 = 2.25 in 2D (x4.5: 4.5e5); 2D t_max 1.6e6 (0.55 decade). In 3D (phi1 = 2.5: x5.3,
//    1.9e6) the plateau would need t_max 6.5e6: 2.6e4 CPU-s a realisation, one at a time (5e7
//    made, 21 GB), 2.4 days for 8 on this machine. 3D r = 0.95 therefore runs to 4e5 and not
//    to its plateau: it gives the readings that need no plateau (analysis/energy_scaling.h), the
//    declared E_t/E_0 collapse and the time to E_0/10, and none by the intersection rule. The
//    3D r = 0.9 realisations of --limit fall to E_0/10 at 1.6e4 and E_0/20 at 5.3e4 (two
//    realisations' mean), so by 4e5 r = 0.95 is at E_0/20 if phi1 <= 3 (x7.4: 3.9e5) and past
//    E_0/10 if phi1 <= 4.3: the collapse spans a decade of E_t.
// Cutoffs: t_c2 ~ delta^-(1/(1-alpha)) must stay far beyond t_max. 2D 1e-6: t_c2 ~ 2.5e8 by the
// delta scan (2.2e4 (5e-4 / delta)^1.5), 150 times 1.6e6; 3D 1e-7: at 1e-4 E_t's slope turns up
// from ~3e4 at r = 0.7, so ~3e4 x 1000^(4/3) = 3e8 at 1e-7, where 1e-6 (1.4e7) would come
// within a factor 2 of r = 0.95's t_max.
// Caps on made particles (--particles; a run stops with a message if the medium needs more).
// Measured in the unbounded medium (one realisation, delta = 1e-7): 3D r = 0.9 at t = 1e5 has
// 8.2e5 active spheres, R_rms 83 (R ~ t^0.29 over 5e4-1e5) and 8.7e5 made (peak RSS 615 MB with
// an XYZ snapshot written); made ~ R^3 extrapolates to ~8e6 at 1.2e6. 3D r = 0.95 spreads
// further: R_rms 99.6 and 1.56e6 made at 1e5 (R ~ t^0.32 over 5.6e4-1e5; peak RSS 951 MB) and,
// with R ~ t^0.27-0.29 after, 145-150 at 4e5, i.e. 5e6 made. Caps: 2.5e7 for 3D, two
// realisations at once in 21 GB by the engine's estimate (estimated_bytes: ~425 B per particle
// with a snapshot). 2D: 2e6 (R ~
// t^(1/3)-t^0.4: r = 0.95 has R_rms 280 and 7.7e4 active at 1.4e5, so ~6e5 made at 1.6e6).
// Realisations: t_c1's interval comes from resampling realisations (200 draws, percentiles), and
// a percentile interval over M realisations is set by single realisations below M ~ 8 (8 gives
// 6435 distinct resamples); 12 in 3D r = 0.9 as --full's added 3D r, 8 at 0.95 (each costs ~5
// times more); 2D as --full's 0.9 and 0.95 (32, 24), being cheap.
// --estimate runs each 3D sample to t_max / 30 (1.5 decades short, past t_c1 in every case) and
// each 2D one to t_max / 3: in 2D the collisions' growth g = d ln C / d ln t rises late, from
// 1.16-1.21 over 3e3-3e4 to 1.44 at 1e5 and 1.66 at 3e5, at the same times for r = 0.9 and
// 0.95 (one realisation each, `run --dim 2 --medium unbounded --particles 2e6 --cutoff 1e-6`),
// so that a sample to t_max / 30 extrapolated with its own g missed by 3.4x (r = 0.95: 316
// CPU-s per realisation to 1.6e6, 2.35e8 collisions, peak RSS 272 MB, at load 5-8, where 92
// were estimated; r = 0.9: 17.4 CPU-s to 4e5, 2.2e7 collisions). A third of t_max costs a 2D
// sample about a sixth of a realisation.
// `figures --limit --estimate` (sample 2, load ~3.4), with 3D r = 0.95 to its plateau at 6.5e6:
// 2.24e5 CPU-s, 60 h on a quiet 2-core machine, of which 3D r = 0.95 2.06e5 (2.6e4 CPU-s per
// realisation, one at a time; the sample to 2.17e5 took 358 per realisation, its collisions
// growing as t^1.26), 3D r = 0.9 1.5e4, 2D 2.5e3, the --quick cases 230. With r = 0.95 to 4e5
// (`--limit --limit-dim 3 --estimate --sample 2`, load ~2): 1.79e4 CPU-s, 2.5 h quiet, of which
// 3D r = 0.9 1.23e4 (1023 a realisation) and 3D r = 0.95 5.4e3 (681 a realisation, two at
// once). Checked: one 3D r = 0.9 realisation to 3.5e5 (bench sim/kick3d_r0.9_plateau) took
// 272 CPU-s, 275 extrapolated from a sample's 17.5 at 4e4.
struct LimitCase {
  int d;
  double r;
  std::int64_t cap;  // particles the medium may make
  double plateau_start, t_max;
  std::uint64_t realisations;
  int concurrent = 0;                   // FigureCase::concurrent
  double estimate_fraction = 1.0 / 30;  // --estimate samples to t_max times this
};
std::vector<LimitCase> limit_cases(FiguresMode m) {
  if (m == FiguresMode::Tiny)  // smoke run: every file, no plateau
    return {{2, 0.9, 50000, 0, 1500, 3},
            {2, 0.95, 50000, 0, 1500, 3},
            {3, 0.9, 100000, 0, 600, 3},
            {3, 0.95, 100000, 0, 600, 3}};
  std::vector<LimitCase> cases = {{2, 0.9, 2000000, 1e5, 4e5, 32, 0, 1.0 / 3},
                                   {2, 0.95, 2000000, 4.5e5, 1.6e6, 24, 0, 1.0 / 3},
                                   {3, 0.9, 25000000, 3.5e5, 1.2e6, 12},
                                   {3, 0.95, 25000000, 0, 4e5, 8}};  // plateau_start 0: none
  // r = 0.97, 0.98, 0.99: phi1 nearest the elastic limit from the time <E_t> falls to E_0/2
  // alone (analysis/paper.h phi1_near_elastic_comparison), no plateau, so each runs only past
  // that time. Measured, one realisation each in the unbounded medium (`run --medium unbounded
  // --restitution 0.99`, delta 1e-6 in 2D, 1e-7 in 3D): 2D r = 0.99 falls to E_0/2 at 1.41e4
  // (0.385 E_0 at 3e4, 2.1 CPU-s to 3e4, 6e4 active); 3D r = 0.99 is still at 0.614 E_0 at
  // 3.98e4 (1.16e6 active, 1.6e7 collisions, ~4 CPU-min at load ~9), its lost fraction growing
  // as t^0.29, which puts E_0/2 at ~1e5: "under ~1.5e4" holds in 2D only. The other r from
  // t_half ~ (1 - r^2)^-phi1 (2D phi1 2-2.25: r = 0.98 ~3.3e3, 0.97 ~1.4e3; 3D 2.5-3: r = 0.98
  // 1.3e4-1.8e4, 0.97 4e3-7e3), each t_max 2-3 times that (1.5 times for 3D r = 0.99, whose
  // collisions grow as ~t^1.5: ~480 CPU-s a realisation to 1.5e5, ~7e6 spheres made). 2D r = 0.99
  // costs seconds, so 24 realisations each; 3D 12, and 8 at r = 0.99 (the fewest that give a
  // percentile interval, above).
  if (m != FiguresMode::Tiny)  // not in the smoke run: too short to reach E_0/2 there
    for (const LimitCase& c : std::vector<LimitCase>{{2, 0.97, 2000000, 0, 5e3, 24, 0, 1.0 / 3},
                                                     {2, 0.98, 2000000, 0, 1e4, 24, 0, 1.0 / 3},
                                                     {2, 0.99, 2000000, 0, 3e4, 24, 0, 1.0 / 3},
                                                     {3, 0.97, 25000000, 0, 1.5e4, 12},
                                                     {3, 0.98, 25000000, 0, 4e4, 12},
                                                     {3, 0.99, 25000000, 0, 1.5e5, 8}})
      cases.push_back(c);
  return cases;
}
constexpr double kLimitCutoff2D = 1e-6, kLimitCutoff3D = 1e-7;

// --snowplow: 3D r = 0.1 and 0.5 to t = 1.2e6 and 2D r = 0.1 and 0.5 to t = 2e6 in the unbounded
// medium, 20 realisations each, at the --limit cases' cutoffs (t_c2 stays far beyond t_max:
// above). 3D to 1.2e6 gives the plateau rule (a decade at least, ending at the run's end) the
// decade from 1.2e5 on, past where --long's 3D slopes at 1e6 were still rising; 2D to 2e6 a
// decade and a half past --full's 1e5. Caps on made particles as --limit's r = 0.9 (r = 0.1
// and 0.5 spread less far: alpha ~ 0.25-0.29 against 0.29-0.32). --estimate samples each to
// t_max / 30 (3D) or / 3 (2D), as --limit does and for the same reasons.
std::vector<LimitCase> snowplow_cases(FiguresMode m) {
  if (m == FiguresMode::Tiny)  // smoke run: every file, no plateau
    return {{3, 0.1, 100000, 0, 600, 3},
            {3, 0.5, 100000, 0, 600, 3},
            {2, 0.1, 50000, 0, 1500, 3},
            {2, 0.5, 50000, 0, 1500, 3}};
  return {{3, 0.1, 25000000, 1.2e5, 1.2e6, 20},
          {3, 0.5, 25000000, 1.2e5, 1.2e6, 20},
          {2, 0.1, 2000000, 2e5, 2e6, 20, 0, 1.0 / 3},
          {2, 0.5, 2000000, 2e5, 2e6, 20, 0, 1.0 / 3}};
}

// The band packing at the paper's delta = 1e-4 (2D, r = 0.1, 0.5, 0.8): the structure of the
// band depends on delta, below which collisions are elastic, so the paper's 0.78-0.82 is read
// where the paper ran, not at the paper cases' 1e-5. Snapshots a factor 2 apart over the last
// decade show whether each reading has settled; t_max = 1e5 is t_paper = 5e4, the paper's Fig. 4
// last time, and lies before t_c2 ~ 2.7e5 at 1e-4 (the delta scan's phi2). The paper's box in
// --full; --quick half the time in 1e5 discs (r = 0.8 reaches 176 of L/2 = 316 by 1e5 there).
// Measured at the --full size (4 realisations, one thread, loaded machine): 3.7 s a realisation
// for r = 0.1 and 7.4 s for r = 0.8 with every snapshot's measures, ~250 CPU-s for the three.
// Their Voronoi median at t = 1.25e4, 2.5e4, 5e4, 1e5: r = 0.1 0.653, 0.688, 0.700, 0.688
// (+- 0.002-0.006, settled); r = 0.8 0.487, 0.615, 0.708, 0.730 (still rising). At the paper
// cases' 1e-5, r = 0.1 reaches 0.766 at 1e5 and 0.781 at 2e5, still rising: the band compacts
// further where fewer collisions are made elastic.
struct PackingRun {
  std::int64_t particles;
  double t_max;
  std::uint64_t realisations;
};
PackingRun packing_run_of(FiguresMode m) {
  switch (m) {
    case FiguresMode::Tiny:
      return {3000, 1500, 2};
    case FiguresMode::Quick:
      return {100000, 5e4, 6};
    case FiguresMode::Full:
    default:
      return {250000, 1e5, 16};
  }
}
constexpr double kPackingRestitutions[] = {0.1, 0.5, 0.8};

// The 3D elastic blast where its local slopes reach their plateau (d ln R / d ln t dips
// to 0.32 near t = 1000 and recovers to 0.397 by 2e4 at N = 4e6, front inside half the box): its
// own case, at N >= 4e6 to t = 2e4 in --full, and smaller in --quick, the plateau rule deciding.
struct Elastic3D {
  std::int64_t particles;
  double t_max;
  std::uint64_t realisations;
};
Elastic3D elastic3d_of(FiguresMode m) {
  switch (m) {
    case FiguresMode::Tiny:
      return {8000, 120, 2};
    case FiguresMode::Quick:  // to the end of the dip: the plateau rule says whether it is reached
      return {1500000, 5000, 3};
    case FiguresMode::Full:
    default:  // 64 CPU-s per realisation (--estimate)
      return {4000000, 20000, 5};
  }
}

// The delta scan (2D, r = 0.1). t_c2 ~ delta^(-1/(1-alpha)) (the paper's phi2 = 3/2 in 2D): with
// the paper's delta = 1e-4 it lies near t ~ 2e5-3e5, beyond the longest run, so larger cutoffs
// bring it into reach. Measured on 8 realisations of 2e5 discs: v_t ~ 0.66 t^(-2/3) and the
// local slope of N_t leaves the band around 2/3 for good at t ~ 7e3, 1e4, 1.5e4, 2.4e4 for delta
// = 1.4e-3, 1e-3, 7e-4, 5e-4, reaching 0.95 by 1.8e5 (--quick, 12 realisations of 1e5 discs:
// t_c2 = 4.5e3, 7.8e3, 1.1e4, 2.2e4, phi2 ~ 1.55).
// Larger cutoffs are useless: from delta ~ 2e-3 on, t_c2 comes before the band is reached at
// t_c1 ~ 1e3 and no crossover is defined. Each run lasts >= 3.5 t_c2 of its smallest cutoff, so the
// slope is well above the band at its end; past t_c2 the front spreads as r = 1 does (R ~
// t^(1/2)) and was at 184 of L/2 = 447 at t = 1.8e5 (2e5 discs, delta = 1.4e-3): 1e5 discs
// (L/2 = 316) hold it to 1e5 (0.44 L/2 measured), 2.5e5 (L/2 = 500) to 2.5e5.
struct DeltaScan {
  std::int64_t particles;
  double t_max;
  std::uint64_t realisations;
  std::vector<double> cutoffs;
};
DeltaScan delta_scan_of(FiguresMode m) {
  switch (m) {
    case FiguresMode::Tiny:  // every file; no t_c2 in 300 time units
      return {3000, 300, 2, {1e-2, 5e-3, 2.5e-3, 1e-3}};
    case FiguresMode::Quick:
      return {100000, 80000, 12, {1.4e-3, 1e-3, 7e-4, 5e-4}};
    case FiguresMode::Full:
    default:  // five cutoffs, the smallest's t_c2 ~ 6e4
      return {250000, 250000, 16, {1e-3, 7e-4, 5e-4, 3.5e-4, 2.5e-4}};
  }
}

// Snapshot times of a case: the paper's collapse times are in ratio 1 : 1.5 : 2 (2D) and
// 1 : 5/3 : 2.5 (3D), ending at t_max.
std::vector<double> collapse_times(int d, double t_max) {
  return d == 2 ? std::vector<double>{t_max / 2, 0.75 * t_max, t_max}
                : std::vector<double>{0.4 * t_max, t_max * 2 / 3, t_max};
}

// The collapse case's figure times: the paper's in simulation units if the run reaches them
// (then t_max is a snapshot too, if later), else collapse_times.
void set_collapse_times(FigureCase& c) {
  const PhysicsConfig& p = c.spec.physics;
  std::vector<double> paper;
  for (double tp : p.dim == 2 ? std::span<const double>(kFig4PaperTimes)
                              : std::span<const double>(kFig5PaperTimes))
    paper.push_back(tp / p.paper_time(1.0));
  c.paper_times = paper.back() <= p.t_max;
  c.figure_times = c.paper_times ? paper : collapse_times(p.dim, p.t_max);
  c.spec.snapshot_times = c.figure_times;
  if (c.spec.snapshot_times.back() < p.t_max) c.spec.snapshot_times.push_back(p.t_max);
  c.spec = checked(c.spec);
}

}  // namespace

const char* to_string(FiguresMode m) {
  switch (m) {
    case FiguresMode::Tiny:
      return "tiny";
    case FiguresMode::Quick:
      return "quick";
    default:
      return "full";
  }
}

FiguresPlan figures_plan(FiguresMode mode, std::uint64_t seed, bool long_3d, bool limit,
                         int limit_dim, bool snowplow) {
  FiguresPlan plan;
  plan.mode = mode;
  auto add = [&](const std::string& name, EnsembleSpec e, CaseRole role) {
    FigureCase c;
    c.name = name;
    c.role = role;
    c.delta_scan = role == CaseRole::DeltaScan;
    e.physics.seed = seed;
    e.per_decade = 20;
    c.spec = checked(e);
    plan.cases.push_back(std::move(c));
  };
  for (int d : {2, 3}) {
    const auto sizes = sizes_of(mode, d);
    for (const RunSize& s : sizes) {
      EnsembleSpec e;
      e.physics.dim = d;
      e.physics.particles = s.particles;
      e.physics.restitution = s.r;
      if (s.r < 1) e.physics.cutoff = d == 3 ? kCutoff3D : kCutoff2D;
      e.physics.t_max = s.t_max;
      e.realisations = s.realisations;
      e.snapshot_times = collapse_times(d, s.t_max);
      // Built with append: GCC 12 warns falsely (-Wrestrict) on "literal" + std::string&&.
      std::string name = "d";
      name.append(std::to_string(d)).append("_r").append(format_number(s.r));
      add(name, e, CaseRole::Paper);
      plan.cases.back().collapse = &s == &sizes.front();  // the lists start at r = 0.1
      if (plan.cases.back().collapse) set_collapse_times(plan.cases.back());
    }
  }
  {
    const Elastic3D s = elastic3d_of(mode);
    EnsembleSpec e;
    e.physics.dim = 3;
    e.physics.particles = s.particles;
    e.physics.restitution = 1;
    e.physics.t_max = s.t_max;
    e.realisations = s.realisations;
    add("d3_r1_large", e, CaseRole::Elastic3D);
    for (auto& c : plan.cases)
      c.superseded_for_alpha =
          c.role == CaseRole::Paper && c.spec.physics.dim == 3 && c.spec.physics.elastic();
  }
  if (long_3d) {
    for (const Long3D& s : long3d_cases()) {
      EnsembleSpec e;
      e.physics.dim = 3;
      e.physics.particles = s.particles;
      e.physics.restitution = s.r;
      e.physics.cutoff = kCutoff3D;
      e.physics.t_max = s.t_max;
      e.realisations = s.realisations;
      e.snapshot_times = collapse_times(3, s.t_max);
      add(std::string("d3_r").append(format_number(s.r)).append("_long"), e, CaseRole::Long3D);
    }
  }
  // The cases of the unbounded medium (--limit, --snowplow), named d<d>_r<r>_<suffix>.
  auto add_unbounded = [&](const LimitCase& s, CaseRole role, const char* suffix) {
    EnsembleSpec e;
    e.physics.dim = s.d;
    e.physics.medium = Medium::Unbounded;
    e.physics.particles = s.cap;
    e.physics.restitution = s.r;
    e.physics.cutoff = s.d == 3 ? kLimitCutoff3D : kLimitCutoff2D;
    e.physics.t_max = s.t_max;
    e.realisations = s.realisations;
    e.snapshot_times = collapse_times(s.d, s.t_max);
    add(std::string("d")
            .append(std::to_string(s.d))
            .append("_r")
            .append(format_number(s.r))
            .append("_")
            .append(suffix),
        e, role);
    plan.cases.back().plateau_start = s.plateau_start;
    plan.cases.back().estimate_t_max = s.t_max * s.estimate_fraction;
    plan.cases.back().concurrent = s.concurrent;
  };
  if (limit)
    for (const LimitCase& s : limit_cases(mode))
      if (limit_dim == 0 || s.d == limit_dim) add_unbounded(s, CaseRole::Limit, "limit");
  if (snowplow)
    for (const LimitCase& s : snowplow_cases(mode)) add_unbounded(s, CaseRole::Snowplow, "snowplow");
  {
    const PackingRun s = packing_run_of(mode);
    for (double r : kPackingRestitutions) {
      EnsembleSpec e;
      e.physics.dim = 2;
      e.physics.particles = s.particles;
      e.physics.restitution = r;
      e.physics.cutoff = kPaperCutoff;
      e.physics.t_max = s.t_max;
      e.realisations = s.realisations;
      e.snapshot_times = {s.t_max / 8, s.t_max / 4, s.t_max / 2, s.t_max};
      add(std::string("d2_r").append(format_number(r)).append("_packing"), e, CaseRole::Packing);
    }
  }
  {
    const DeltaScan s = delta_scan_of(mode);
    for (double delta : s.cutoffs) {
      EnsembleSpec e;
      e.physics.dim = 2;
      e.physics.particles = s.particles;
      e.physics.restitution = 0.1;
      e.physics.cutoff = delta;
      e.physics.t_max = s.t_max;
      e.realisations = s.realisations;
      add(std::string("d2_r0.1_delta").append(format_number(delta)), e, CaseRole::DeltaScan);
    }
  }
  // Fig. 1 from the 2D r = 0.1 and r = 1 cases' physics (cutoff included).
  FiguresPlan::Fig1& f = plan.fig1;
  f.a = find_case(plan, 2, 0.1)->spec.physics;
  f.b = find_case(plan, 2, 1.0)->spec.physics;
  f.a.realisation = f.b.realisation = 0;
  f.paper_times = mode != FiguresMode::Tiny;
  if (f.paper_times) {
    // The paper's box. Measured at r = 1, t_paper = 25000: the outermost active disc at 433 of
    // L/2 = 500 from the centre of mass, none wrapped, 9 CPU-s; r = 0.1 spreads far less.
    f.a.particles = f.b.particles = kFig1Particles;
    for (double t : kFig1aPaperTimes) f.a_times.push_back(t / f.a.paper_time(1.0));
    f.b.t_max = kFig1bPaperTime / f.b.paper_time(1.0);
  } else {
    // The paper's times in ratio, ending at the tiny run's t_max (its box holds no more).
    const double T = f.a.t_max, last = std::end(kFig1aPaperTimes)[-1];
    for (double t : kFig1aPaperTimes) f.a_times.push_back(T * t / last);
  }
  f.a.t_max = f.a_times.back();
  return plan;
}

const FigureCase* find_case(const FiguresPlan& plan, int d, double r) {
  for (const auto& c : plan.cases)
    if (c.role == CaseRole::Paper && c.spec.physics.dim == d && c.spec.physics.restitution == r)
      return &c;
  return nullptr;
}

}  // namespace gs::jobs
