#include "jobs/figures_report.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "analysis/core_energy.h"
#include "analysis/json.h"
#include "analysis/snowplow.h"
#include "io/atomic_file.h"
#include "sim/format.h"

namespace gs::jobs {
namespace {

std::string crossover_cell(const Crossover& c) {
  return c.found ? figure_number(c.time, 3) : "-";
}

// The front radius at the last sample over half the box side.
double front_reach(const CaseResult& c) {
  const Table ts = c.sums.timeseries();
  return ts.column("front_radius").back() / (0.5 * c.plan->spec.physics.box());
}

// Which crossovers were found, and why the others were not: a crossover beyond a run whose front
// is already near the box is out of reach of that box, not merely of the run's length.
std::string crossover_notes(const std::vector<CaseResult>& results) {
  std::ostringstream notes;
  for (const auto& c : results) {
    const auto& p = c.plan->spec.physics;
    const bool scan = c.plan->role == CaseRole::DeltaScan;
    const bool tc1_case =
        (c.plan->role == CaseRole::Paper || c.plan->role == CaseRole::Limit) && !p.elastic();
    if (!tc1_case && !scan) continue;
    const Crossover& tc = scan ? c.fits.tc2 : c.fits.tc1;
    if (tc.found && !scan) continue;
    notes << "- " << (scan ? "t_c2" : "t_c1") << " of " << c.plan->name << " (d = " << p.dim
          << ", r = " << format_number(p.restitution)
          << (scan ? ", delta = " + format_number(p.cutoff) : std::string())
          << "): " << (tc.found ? "= " + figure_number(tc.time) : "not found: " + tc.note);
    const double reach = front_reach(c);
    if (!tc.found && reach > 0.6)
      notes << ". The front is at " << figure_number(reach, 2)
            << " of L/2 at t_max = " << figure_number(p.t_max)
            << ": a longer run needs a larger box (more particles)";
    notes << ".\n";
  }
  return notes.str();
}

// phi1 between neighbouring r (intersection rule), towards the elastic limit.
std::string local_phi1_markdown(const Crossovers& crossovers) {
  std::ostringstream md;
  md << "### phi1 between neighbouring r\n\n"
        "-d ln t_c1 / d ln(1 - r^2) between successive r whose t_c1 is found (intersection "
        "rule), with 95% bootstrap intervals. phi1 is defined by the divergence as r -> 1: a "
        "drift along the rows means that the fit over all r mixes regimes, and the last row is "
        "the estimate nearest the elastic limit. With `--limit`, r = 0.9 and 0.95 come from the "
        "*_limit cases (the unbounded medium, run until E_t's local slope plateaus, but 3D "
        "r = 0.95 only to t = 4e5, about E_0/20: it has no t_c1 here, only the energy readings "
        "below).\n\n"
        "| d | between | phi1 | 95% interval |\n|---|---|---|---|\n";
  for (const auto& set : crossovers.tc1)
    for (const auto& e : set.local)
      md << "| " << set.d << " | " << e.from << " and " << e.to << " | " << figure_number(e.phi, 3)
         << " | [" << figure_number(e.ci_lo, 3) << ", " << figure_number(e.ci_hi, 3) << "] |\n";
  return md.str();
}

// phi1 from the energy curves between neighbouring r (analysis/energy_scaling.h).
std::string energy_phi1_markdown(const Crossovers& crossovers) {
  std::ostringstream md;
  md << "### phi1 without a plateau: E_t/E_0 collapse and fixed energy fractions\n\n"
        "Between successive r: the phi1 that collapses ln(<E_t>/E_0) of the two r against "
        "ln t + phi1 ln(1 - r^2) over E/E_0 in [0.01, 0.5] (the declared phi1 is this reading "
        "for the pair nearest r = 1), and -d ln t_f / d ln(1 - r^2) with t_f the time <E_t> "
        "falls to E_0/2, E_0/10, E_0/100. Where one crossover shape holds, every column of a row "
        "agrees; a level dependence shows a pair still outside the scaling form. 95% intervals "
        "from 200 draws resampling each r's realisations. The scaling estimate from cumulative "
        "dissipation during the elastic blast (energy lost ~ (1 - r^2) t^(2/(d+2))) is "
        "(d + 2)/2: 2 in 2D, 2.5 in 3D.\n\n"
        "| d | between | collapse | its interval | E_0/2 | its interval | E_0/10 | its interval "
        "| E_0/100 | its interval |\n|---|---|---|---|---|---|---|---|---|---|\n";
  for (const auto& set : crossovers.tc1) {
    const std::size_t per_pair = 1 + Phi1Options{}.levels.size();
    for (std::size_t k = 0; k + per_pair <= set.energy.size(); k += per_pair) {
      md << "| " << set.d << " | " << set.energy[k].from << " and " << set.energy[k].to;
      for (std::size_t j = k; j < k + per_pair; ++j) {
        const auto& e = set.energy[j];
        md << " | " << figure_number(e.phi, 3) << " | ";
        if (std::isfinite(e.ci_lo))
          md << "[" << figure_number(e.ci_lo, 3) << ", " << figure_number(e.ci_hi, 3) << "]";
        else
          md << "-";
      }
      md << " |\n";
    }
  }
  return md.str();
}

// phi1 nearest the elastic limit by each reading, weighed between the paper's value and the
// scaling estimate (analysis/paper.h, weigh_phi1): which of the two the data favour, answered per
// reading.
std::string phi1_limit_markdown(const Crossovers& crossovers) {
  std::ostringstream md;
  md << "### phi1 nearest the elastic limit: which value the data favour\n\n"
        "Each reading's estimate from the pair of r nearest r = 1 that gives one, weighed "
        "between the paper's value and the scaling estimate (d + 2)/2: z is each value's "
        "distance from the estimate in standard errors (from the 95% interval on that value's "
        "side), the odds the likelihood ratio of the nearer value over the other, in the words "
        "of Kass and Raftery (1995). The first row of each d is the declared reading. The "
        "odds count sampling error only: a pair short of the limit, or readings that disagree "
        "with one another, are systematic errors they do not see.\n\n"
        "| d | reading | between | phi1 | 95% interval | z, paper | z, (d + 2)/2 | favoured | "
        "odds | strength |\n|---|---|---|---|---|---|---|---|---|---|\n";
  auto row = [&](int d, const std::string& reading, const std::string& from, const std::string& to,
                 double phi, double lo, double hi) {
    const Phi1Weighing w = weigh_phi1(d, phi, lo, hi);
    md << "| " << d << " | " << reading << " | " << from << " and " << to << " | "
       << figure_number(phi, 3) << " | [" << figure_number(lo, 3) << ", " << figure_number(hi, 3)
       << "] | " << figure_number(w.z_paper, 3) << " (" << w.paper << ") | "
       << figure_number(w.z_scaling, 3) << " (" << w.scaling << ") | "
       << (w.favoured == "paper"     ? "paper's " + figure_number(w.paper, 3)
           : w.favoured == "scaling" ? "(d + 2)/2 = " + figure_number(w.scaling, 3)
           : w.favoured.empty()      ? std::string("-")
                                     : w.favoured)
       << " | " << figure_number(w.odds, 3) << " | " << (w.strength.empty() ? "-" : w.strength)
       << " |\n";
  };
  for (const auto& set : crossovers.tc1) {
    std::vector<double> kinds{std::nan("")};
    for (double level : Phi1Options{}.levels) kinds.push_back(level);
    for (double level : kinds) {
      const Phi1Reading* last = nearest_limit_reading(set.energy, level);
      const std::string name = std::isnan(level) ? "E_t/E_0 collapse (declared)"
                                                 : "time to E_0 x " + figure_number(level, 2);
      if (last)
        row(set.d, name, last->from, last->to, last->phi, last->ci_lo, last->ci_hi);
      else
        md << "| " << set.d << " | " << name << " | - | n/a | - | - | - | - | - | - |\n";
    }
    if (!set.local.empty()) {
      const auto& e = set.local.back();
      row(set.d, "intersection rule", e.from, e.to, e.phi, e.ci_lo, e.ci_hi);
    }
  }
  return md.str();
}

// The files line of Figs. 4 and 5: at which times each collapse is drawn.
std::string collapse_files_markdown(const std::vector<CaseResult>& results) {
  std::ostringstream md;
  md << "- fig4_collapse_2d, fig5_collapse_3d: P(R,t) and P(v,t) of r = 0.1 scaled with the "
        "theory's alpha, +- standard errors over realisations (Figs. 4, 5)";
  for (const auto& c : results) {
    if (!c.plan->collapse) continue;
    const auto& p = c.plan->spec.physics;
    md << "; " << p.dim << "D at t_paper =";
    for (double t : c.plan->figure_times) md << " " << figure_number(p.paper_time(t), 5);
    md << (c.plan->paper_times ? " (the paper's times)"
                               : " (the paper's times in ratio, ending at this run's t_max)");
  }
  md << ".\n";
  return md.str();
}

// The paper's "faster particles on the inside edge" as numbers, per case at the last snapshot:
// the mean speed inside the band's median radius over that outside it, and the correlation of
// speed with distance, each with its standard error over realisations.
std::string inner_edge_markdown(const std::vector<CaseResult>& results) {
  std::ostringstream md;
  md << "### The inner edge's speed\n\n"
        "Mean speed of the active particles inside their median distance from the centre of "
        "mass over that of those outside it (> 1: faster inside), and the Pearson correlation "
        "of speed with distance (< 0: faster inside), at the last snapshot; +- standard error "
        "over realisations; z of the ratio against 1.\n\n"
        "| case | d | r | inner / outer speed | z against 1 | correlation(speed, R) |\n"
        "|---|---|---|---|---|---|\n";
  for (const auto& c : results) {
    if (c.plan->delta_scan) continue;
    const auto& f = c.fits;
    const double ratio = f.last_scalar("inner_outer_ratio");
    const double sem = f.last_scalar_sem("inner_outer_ratio");
    md << "| " << c.plan->name << " | " << c.plan->spec.physics.dim << " | "
       << format_number(c.plan->spec.physics.restitution) << " | " << figure_number(ratio, 4)
       << " +- " << figure_number(sem, 2) << " | "
       << (sem > 0 ? figure_number((ratio - 1) / sem, 3) : std::string("-")) << " | "
       << figure_number(f.last_scalar("inner_correlation"), 3) << " +- "
       << figure_number(f.last_scalar_sem("inner_correlation"), 2) << " |\n";
  }
  md << "\nAgainst r: fig12_inner_edge.png.\n";
  return md.str();
}

// The band packing readings of the 2D r < 1 cases at every snapshot time, at the paper's delta
// (the *_packing cases, 4 times over the last decade) and the paper cases' 1e-5: whether a
// reading has settled, and how the cell side dilutes it (docs/definitions.md).
std::string packing_scan_markdown(const std::vector<CaseResult>& results) {
  const char* scalars[] = {"packing_voronoi_median", "packing_cell5", "packing_typical",
                           "packing_cell20", "packing_local_median"};
  std::ostringstream md;
  md << "### Band packing over time and cell side\n\n"
        "2D, r < 1: mean over realisations +- standard error at each snapshot time. Voronoi: "
        "the median over active particles of their disc's area over their Voronoi cell's (the "
        "declared reading); cells of 5, 10 (the paper's, declared before this scan), 20: the "
        "active-weighted mean over cells holding band particles; local: median of the packing "
        "within 3 diameters. Cells straddling the band's edges dilute the cell readings, the "
        "more the larger the cell; the paper reports 0.78-0.82 at delta = 1e-4, the *_packing "
        "cases' cutoff (the counted row is their last time).\n\n"
        "| case | delta | t | t_paper | Voronoi median | cells of 5 | cells of 10 | cells of 20 | "
        "local median |\n|---|---|---|---|---|---|---|---|---|\n";
  for (const auto& c : results) {
    const auto& p = c.plan->spec.physics;
    if (p.dim != 2 || p.elastic() || c.plan->delta_scan || c.sums.count() == 0) continue;
    if (c.plan->role != CaseRole::Paper && c.plan->role != CaseRole::Packing) continue;
    for (const auto& snap : c.sums.snapshots()) {
      const auto mean = snap.scalars.mean(), sem = snap.scalars.standard_error();
      md << "| " << c.plan->name << " | " << format_number(p.cutoff) << " | "
         << figure_number(snap.t, 4) << " | " << figure_number(p.paper_time(snap.t), 4);
      for (const char* name : scalars)
        for (std::size_t k = 0; k < kSnapshotScalars.size(); ++k)
          if (std::string(kSnapshotScalars[k]) == name)
            md << " | " << figure_number(mean[k], 4) << " +- " << figure_number(sem[k], 2);
      md << " |\n";
    }
  }
  return md.str();
}

std::string z_cell(const SnowplowReading& r) {
  if (!std::isfinite(r.exponent)) return "no plateau | - | -";
  return figure_number(r.exponent, 4) + " +- " + figure_number(r.sigma, 2) + " | " +
         figure_number(r.z_momentum, 3) + " | " + figure_number(r.z_pressure, 3);
}

// The r < 1 cases of the snowplow tables: neither the delta scan nor the packing runs (their
// own questions).
bool weighs_the_snowplow(const CaseResult& c) {
  return !c.plan->spec.physics.elastic() && !c.plan->delta_scan &&
         c.plan->role != CaseRole::Packing;
}

std::string end_cell(const EndSlope& e) {
  if (!e.found) return "-";
  return figure_number(e.slope, 4) + " +- " + figure_number(e.slope_error, 2);
}

// Where the runs end (analysis/snowplow.h snowplow_at_the_end): P_r's slope epsilon over the
// last decade and its drift, the shell momentum's slope against each picture, the heading.
std::string snowplow_end_markdown(const std::vector<CaseResult>& results) {
  std::ostringstream md;
  md << "### Where the runs end\n\n"
        "A run still in its crossover has no plateau, yet says where its slopes are and which "
        "way they move. A snowplow is a shell of the swept mass N ~ R^d whose momentum grows as "
        "t^epsilon, so that alpha = (1 + epsilon)/(d + 1): epsilon = 0 for the "
        "momentum-conserving snowplow, (d - 2)/(d + 4) = 1/7 in 3D for the pressure-driven "
        "one. Below, mean local slopes over the last decade (+- their resampling error): "
        "epsilon read as P_r's slope, with its drift per decade and where it is heading (the "
        "picture on the side its drift points to when the drift exceeds 2 sigma, undecided "
        "when both are; else the picture within 3 sigma); and read as the slope of the "
        "shell's momentum N_t dR_t/dt, x_N + x_R - 1, with its z against each picture "
        "(analysis/snowplow.h).\n\n"
        "| case | last decade | R_t | N_t | E_t | epsilon (P_r) | drift per decade | heading | "
        "x_N + x_R - 1 | z_mc | z_pd |\n"
        "|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const auto& c : results) {
    if (!weighs_the_snowplow(c)) continue;
    const SnowplowEnd v = snowplow_at_the_end(c.plan->spec.physics.dim, c.fits);
    md << "| " << c.plan->name << " | ";
    if (v.epsilon.found)
      md << figure_number(v.epsilon.window.t_lo, 3) << " - "
         << figure_number(v.epsilon.window.t_hi, 3);
    else
      md << "-";
    md << " | " << end_cell(v.radius) << " | " << end_cell(v.count) << " | " << end_cell(v.energy)
       << " | " << end_cell(v.epsilon) << " | ";
    if (v.epsilon.found)
      md << figure_number(v.epsilon.drift_per_decade, 3) << " +- "
         << figure_number(v.epsilon.drift_error, 2);
    else
      md << "-";
    md << " | " << v.heading << " | " << figure_number(v.shell, 4) << " +- "
       << figure_number(v.shell_sigma, 2) << " | " << figure_number(v.shell_z_momentum, 3) << " | "
       << figure_number(v.shell_z_pressure, 3) << " |\n";
  }
  return md.str();
}

// The snowplow question: per r < 1 case, the exponents of R_t, N_t, E_t and P_r with their z
// against each picture, and the verdict (analysis/snowplow.h).
std::string snowplow_markdown(const std::vector<CaseResult>& results) {
  std::ostringstream md;
  md << "## The snowplow question\n\n"
        "The paper's alpha = 1/(d+1) assumes the band conserves its radial momentum "
        "(momentum-conserving snowplow: P_r constant). Barbier, Villamaina and Trizac (\"Blast "
        "dynamics in a dissipative gas\", Phys. Rev. Lett., 2015) argue for a "
        "hot core that keeps pushing the shell, a pressure-driven snowplow with alpha = "
        "2/(d+4) for an adiabatic core: 2/7 against 1/4 in 3D, the same 1/3 in 2D. Each "
        "picture predicts every exponent: R_t ~ t^alpha, N_t ~ t^(alpha d), E_t ~ "
        "t^(alpha (d+2) - 2), P_r ~ t^(alpha (d+1) - 1) (1/4: 0.25, 0.75, -0.75, 0; 2/7: 0.2857, "
        "0.8571, -0.5714, 0.1429). Below, each measured exponent (plateau fit, sigma = "
        "statistics and window systematic combined) with z against the momentum-conserving "
        "(z_mc) and pressure-driven (z_pd) value; the verdict weighs them by chi^2 = sum z^2 "
        "(odds exp(delta chi^2 / 2), 'neither' when the nearer picture's chi^2 lies beyond "
        "its 99.7% quantile). `figures --snowplow` adds runs long enough to decide (3D r = "
        "0.1, 0.5 to 1.2e6; 2D to 2e6; fig11_snowplow_3d.png).\n\n"
        "| case | R_t | z_mc | z_pd | N_t | z_mc | z_pd | E_t | z_mc | z_pd | P_r | z_mc | "
        "z_pd | chi^2 mc | chi^2 pd | favours |\n"
        "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const auto& c : results) {
    if (!weighs_the_snowplow(c)) continue;
    const auto& p = c.plan->spec.physics;
    const SnowplowVerdict v = weigh_snowplow(p.dim, c.fits);
    md << "| " << c.plan->name;
    for (const auto& r : v.readings) md << " | " << z_cell(r);
    md << " | " << figure_number(v.chi2_momentum, 3) << " | "
       << figure_number(v.chi2_pressure, 3) << " | " << v.favoured
       << (v.strength.empty() ? "" : " (" + v.strength + ")") << " |\n";
  }
  md << "\n" << snowplow_end_markdown(results);
  return md.str();
}

std::string share_cell(double mean, double sem) {
  return figure_number(mean, 3) + " +- " + figure_number(sem, 2);
}

std::string trend_cell(const CoreShareTrend& c) {
  if (!std::isfinite(c.slope)) return "- | " + c.reading;
  return figure_number(c.slope, 3) + " +- " + figure_number(c.sigma, 2) + " | " + c.reading;
}

// The core's share of the energy over time (analysis/core_energy.h), per r < 1 case that
// measured it: at t_max / 100, / 10 and t_max, and its local slope over each decade.
std::string core_share_markdown(const std::vector<CaseResult>& results) {
  std::ostringstream md;
  md << "### The hot core\n\n"
        "The share of the active particles' kinetic energy (centre-of-mass frame) held behind "
        "the band's inner edge (Definitions), mean +- standard error over realisations, and its "
        "local slope d ln share / d ln t over each decade (sigma from the two standard errors). "
        "A momentum-conserving snowplow has a cold interior whose share falls to 0 (\"falls\": "
        "slope below 0 by more than 2 sigma); a pressure-driven one keeps a finite share "
        "(\"flat\": within 2 sigma of 0). Cases run before the share was measured are left "
        "out; a case mixing such realisations with newer ones reads n/a.\n\n"
        "| case | share at t_max/100 | share at t_max/10 | share at t_max | slope, decade "
        "before | reading | slope, last decade | reading |\n"
        "|---|---|---|---|---|---|---|---|\n";
  for (const auto& c : results) {
    const auto& p = c.plan->spec.physics;
    if (p.elastic() || c.plan->delta_scan) continue;
    const Table ts = c.sums.timeseries();
    if (!ts.has("core_energy_share")) continue;
    const auto& t = ts.column("t");
    const auto& m = ts.column("core_energy_share");
    if (std::none_of(m.begin(), m.end(), [](double x) { return std::isfinite(x); })) continue;
    const auto& e = ts.column("core_energy_share_sem");
    const CoreShareTrend early = core_share_trend(t, m, e, p.t_max / 100, p.t_max / 10);
    const CoreShareTrend late = core_share_trend(t, m, e, p.t_max / 10, p.t_max);
    md << "| " << c.plan->name << " | " << share_cell(early.from, early.from_sem) << " | "
       << share_cell(late.from, late.from_sem) << " | " << share_cell(late.to, late.to_sem)
       << " | " << trend_cell(early) << " | " << trend_cell(late) << " |\n";
  }
  return md.str();
}

// The kinetic pressure profile at the last snapshot of the cases that measured it.
std::string pressure_markdown(const std::vector<CaseResult>& results) {
  std::ostringstream md;
  md << "### The kinetic pressure behind the front\n\n"
        "p(rho) = (1 / (d V_shell)) sum |v - u(rho)|^2 at the last snapshot, in shells of rho / "
        "R_front of width 1.5 / bins (0.025 at the default 60; simulation units, mean +- "
        "standard error over realisations; the hard-core collisional part left out, "
        "Definitions). A pressure-driven snowplow has a "
        "core pressure comparable to the band's; a momentum-conserving one a core near 0.\n\n"
        "| case | t | p(0.25) | p(0.5) | p(0.75) | p(0.9) | p(1.0) |\n"
        "|---|---|---|---|---|---|---|\n";
  for (const auto& c : results) {
    const auto& p = c.plan->spec.physics;
    if (p.elastic() || c.plan->delta_scan || c.sums.snapshots().empty()) continue;
    const auto& last = c.sums.snapshots().back();
    if (last.pressure.count() == 0) continue;
    const Binning b = pressure_binning(c.plan->spec);
    const std::vector<double> mean = last.pressure.mean(), sem = last.pressure.standard_error();
    md << "| " << c.plan->name << " | " << figure_number(last.t);
    for (double x : {0.25, 0.5, 0.75, 0.9, 1.0}) {
      const auto k = std::min(mean.size() - 1, std::size_t((x - b.lo) / (b.hi - b.lo) * b.bins));
      md << " | " << figure_number(mean[k], 3) << " +- " << figure_number(sem[k], 2);
    }
    md << " |\n";
  }
  return md.str();
}

std::string plateau_markdown(const std::vector<CaseResult>& results) {
  std::ostringstream md;
  md << "### Plateaus and their drift\n\n"
        "Every fitted exponent's window (the plateau rule in Definitions), the mean local slope "
        "over it, and its drift D (last third minus first third) and curvature K with their "
        "bootstrap standard deviations; a window is a plateau only where |D|, |K| and its offset "
        "from the last decade's slope are <= 2 sigma (+ 1e-3) and <= 0.005. sigma_sys: the "
        "spread of the mean slope over the passing windows.\n\n"
        "The last columns fit the local slope over the run's last two decades with a "
        "correction to scaling, s(t) = b + k t^-omega (b: the corrected exponent, 95% bootstrap "
        "interval): where b is nearer the theory than the plateau exponent, the offset is a "
        "finite-time correction.\n\n"
        "| case | quantity | window (sim t) | fitted exponent | theory | drift D | sigma_D | "
        "curvature K | sigma_K | sigma_sys | corrected b | its interval | omega |\n"
        "|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const auto& c : results)
    for (const auto& e : c.fits.exponents) {
      md << "| " << c.plan->name << " | " << e.quantity << " | ";
      const std::string corrected = " | " + figure_number(e.corrected.b, 4) + " | [" +
                                    figure_number(e.corrected.ci_lo, 4) + ", " +
                                    figure_number(e.corrected.ci_hi, 4) + "] | " +
                                    figure_number(e.corrected.omega, 2) + " |\n";
      if (!e.plateau.found) {
        md << "no plateau | - | " << figure_number(e.theory, 3) << " | - | - | - | - | -"
           << corrected;
        continue;
      }
      md << "[" << figure_number(e.plateau.window.t_lo, 3) << ", "
         << figure_number(e.plateau.window.t_hi, 3) << "] | " << figure_number(e.fit.exponent, 4)
         << " | " << figure_number(e.theory, 3) << " | " << figure_number(e.plateau.drift, 2)
         << " | " << figure_number(e.plateau.drift_error, 2) << " | "
         << figure_number(e.plateau.curvature, 2) << " | "
         << figure_number(e.plateau.curvature_error, 2) << " | "
         << figure_number(e.window_systematic, 2) << corrected;
    }
  return md.str();
}

// What Fig. 1 shows: its times in both units, its box, and the scale bar's unit.
std::string fig1_markdown(const FiguresPlan::Fig1& f) {
  auto times = [](const PhysicsConfig& p, const std::vector<double>& ts) {
    std::string sim, paper;
    for (double t : ts) {
      sim += (sim.empty() ? "" : ", ") + figure_number(t, 6);
      paper += (paper.empty() ? "" : ", ") + figure_number(p.paper_time(t), 6);
    }
    return "t = " + sim + " (t_paper = " + paper + ")";
  };
  std::string paper_times;
  for (double t : kFig1aPaperTimes)
    paper_times += (paper_times.empty() ? "" : ", ") + figure_number(t, 6);
  std::ostringstream md;
  md << "- fig1a_overlay_r0.1.png: the active particles of one 2D r = 0.1 realisation of "
     << f.a.particles << " discs (box side " << figure_number(f.a.box()) << ") at "
     << times(f.a, f.a_times) << ", overlaid (Fig. 1a); fig1b_elastic_r1.png: 2D r = 1, "
     << f.b.particles << " discs, at " << times(f.b, {f.b.t_max}) << " (Fig. 1b). "
     << (f.paper_times
             ? "These are the paper's times and box. "
             : "This mode's box is smaller than the paper's (" + std::to_string(kFig1Particles) +
                   " discs), so its times are the "
                   "paper's (t_paper = " +
                   paper_times + " and " + figure_number(kFig1bPaperTime, 6) +
                   ") scaled to its r = 0.1 run. ")
     << "The scale bar is in particle diameters, the paper's length unit; each colour's label "
        "gives t (simulation units) and t_paper.\n";
  return md.str();
}

}  // namespace

void write_figures_summary(const std::filesystem::path& dir, const FiguresRun& run,
                           const std::vector<CaseResult>& results,
                           const std::vector<Comparison>& cmp,
                           const std::vector<std::string>& problems) {
  Json j;
  j["version"] = GRAINSHOCK_VERSION;
  j["mode"] = to_string(run.mode);
  j["seed"] = run.seed;
  j["threads"] = run.threads;
  j["wall_seconds"] = run.wall;
  j["simulation_wall_seconds"] = run.simulation_wall;
  j["resumed_realisations"] = run.resumed;
  Json& cases = j["cases"] = Json::array();
  for (const auto& c : results) {
    const auto& p = c.plan->spec.physics;
    cases.push_back(
        {{"name", c.plan->name},
         {"d", p.dim},
         {"r", p.restitution},
         {"particles", p.particles},
         {"t_max", p.t_max},
         {"realisations", c.sums.count()},
         {"wall_seconds", c.wall},
         {"t_c1", c.fits.tc1.time},
         {"t_c1_theory_b", c.fits.tc1_theory_b.time},
         // Read only in the delta scan (the run table's rule).
         {"t_c2", c.plan->role == CaseRole::DeltaScan ? Json(c.fits.tc2.time) : Json(nullptr)},
         {"superseded_for_alpha", c.plan->superseded_for_alpha},
         {"folder", "ensembles/" + c.plan->name}});
  }
  j["comparisons"] = comparisons_json(cmp);
  j["problems"] = problems;
  write_file_atomic(dir / "summary.json", json_text(j));
}

void write_figures_report(const std::filesystem::path& dir, const FiguresRun& run,
                          const std::vector<CaseResult>& results, const Crossovers& crossovers,
                          const std::vector<Comparison>& cmp,
                          const std::vector<std::string>& problems) {
  std::ostringstream md;
  md << "# grainshock figures (" << to_string(run.mode) << ")\n\n"
     << "Jabeen, Rajesh, Ray, EPL 2010, reproduced by `grainshock figures --" << to_string(run.mode)
     << " --threads " << run.threads << " --seed " << run.seed << "` in "
     << figure_number(run.wall, 4) << " s wall (" << figure_number(run.simulation_wall, 4)
     << " s of simulation)."
     << (run.resumed > 0 ? " Resumed after a stop: " + std::to_string(run.resumed) +
                               " realisations were read from the earlier process's folders, "
                               "whose time the walls do not count."
                         : std::string())
     << "\n\n## Summary\n\n"
     << comparison_summary_markdown(cmp) << "\n## Runs\n\n"
     << "| case | d | r | delta | N | t_max (sim) | t_max (paper) | realisations | wall (s) | "
        "t_c1 (sim t) | t_c1, b = theory (sim t) | t_c2 (sim t) | R_front / (L/2) at t_max |\n"
        "|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const auto& c : results) {
    const auto& p = c.plan->spec.physics;
    const bool superseded = c.plan->superseded_for_alpha;
    // t_c2 is read only where the delta scan puts it inside the run; elsewhere the slope rule
    // fires on pre-asymptotic slopes leaving their band (3D r = 0.9), which is no crossover.
    const bool scan = c.plan->role == CaseRole::DeltaScan;
    md << "| " << c.plan->name << (superseded ? " (superseded by d3_r1_large)" : "") << " | "
       << p.dim << " | " << format_number(p.restitution) << " | " << format_number(p.cutoff)
       << " | " << p.particles << " | " << figure_number(p.t_max) << " | "
       << figure_number(p.paper_time(p.t_max)) << " | " << c.sums.count() << " | "
       << figure_number(c.wall, 3) << " | " << crossover_cell(c.fits.tc1) << " | "
       << crossover_cell(c.fits.tc1_theory_b) << " | "
       << (scan ? crossover_cell(c.fits.tc2) : std::string("-")) << " | "
       << figure_number(front_reach(c), 2) << " |\n";
  }
  md << "\nt_c1: where the plateau law of <E_t> meets E_0 (intersection rule); t_c1 (b = "
        "theory): the same with E_t's exponent fixed at the theory's; t_c2: the slope rule's "
        "crossover of <N_t>, read only in the delta scan (see Definitions; \"-\": not within "
        "the run, the Notes say why). Times in simulation units unless a column says paper (the "
        "paper's unit is 1 / (v_0 n^{1/d}): t_paper = t v_0 n^{1/d}). The small d3_r1 is kept for "
        "Fig. 3 and "
        "superseded for alpha by d3_r1_large. R_front / (L/2): how far the front (half the "
        "ambient density) has come towards the nearest periodic image of the kicked site; the "
        "plan keeps it below ~0.8 so that the front does not wrap.\n";
  md << "\nEach case's averaged time series, distributions and fits are in `ensembles/<case>/` "
        "(see its summary.json for the windows and intervals); each exponent's row links the "
        "local-slope figure it was read from.\n\n## Measured against the paper\n\n"
     << comparisons_markdown(cmp) << "\n"
     << "### Checks and reported numbers (not counted)\n\n"
        "Identities, the shock jump (hydrodynamics does not hold behind this front), 3D A(t) "
        "(the paper's claim is for 2D) and the radial momentum P_r, each with its z.\n\n"
     << checks_markdown(cmp) << "\n"
     << "### Sensitivity: other readings of the paper's numbers (not counted)\n\n"
     << sensitivity_markdown(cmp) << "\n"
     << plateau_markdown(results) << "\n"
     << local_phi1_markdown(crossovers) << "\n"
     << energy_phi1_markdown(crossovers) << "\n"
     << phi1_limit_markdown(crossovers) << "\n"
     << inner_edge_markdown(results) << "\n"
     << packing_scan_markdown(results) << "\n"
     << snowplow_markdown(results) << "\n"
     << core_share_markdown(results) << "\n"
     << pressure_markdown(results) << "\n## Definitions\n\n"
     << definitions_markdown() << "\n## Notes\n\n"
     << crossover_notes(results);
  for (const auto& p : problems) md << "- problem: " << p << "\n";
  md << "\n## Files\n\n"
        "Every time axis of the figures is in the paper's unit, the initial mean collision time "
        "1 / (v_0 n^{1/d}): t_paper = t v_0 n^{1/d} (0.5 t in 2D, 0.63 t in 3D at n = 0.25); "
        "lengths in diameters, speeds in v_0. The tables above keep simulation units unless a "
        "column says paper.\n\n"
     << fig1_markdown(run.fig1)
     << "- fig2_anisotropy: A(t) in 2D (Fig. 2).\n"
        "- fig3_active_energy: <N_t>, <E_t> of r = 0.1, 0.5, 0.8, 2D below and 3D above, each "
        "curve shifted a decade from the one below it as in the paper's Fig. 3 (the key gives "
        "the factor), with the theory's slope along each curve, its prefactor fitted over the "
        "curve's last decade.\n"
     << collapse_files_markdown(results)
     << "- fig6_crossover: (a) t_c1 against 1 - r^2 with bootstrap intervals and the phi1 fits "
        "over all r (a sensitivity reading), by the intersection rule (filled) and with b fixed "
        "at the theory's (open); (b) phi1 between neighbouring r, the E_t/E_0 collapse (filled) "
        "and the intersection rule (open), the declared reading the verdict uses marked "
        "(fig6_crossover_pairs.csv).\n"
        "- fig12_inner_edge: the inner edge's speed ratio against r, 2D and 3D, +- its standard "
        "error (the table The inner edge's speed).\n"
        "- fig7_tc2_delta: t_c2 against the cutoff delta (2D, r = 0.1) and the phi2 fit.\n"
        "- fig10_energy_fraction_times: the time <E_t> falls to E_0/2, E_0/10 and E_0/100 "
        "against 1 - r^2 with bootstrap intervals, in 2D and 3D: the times whose ratios between "
        "neighbouring r are the level readings of phi1.\n"
        "- fig8_local_slopes_<case>: local slopes of N_t, E_t, R_t, R_front, P_r, P_r/N_t and "
        "C_t with bootstrap bands, theory lines and plateau fits (CSV beside).\n"
        "- fig9_packing: active-weighted distribution of the cell packing in 2D.\n"
        "- fig11_snowplow_3d: local slopes of R_t, N_t, E_t and P_r of every 3D r < 1 case "
        "against alpha = 1/4 and 2/7 (the snowplow question).\n"
        "- Each figure is a .png (and .svg/.pdf with --format) from the .gp script and .csv "
        "beside it. summary.json: every comparison as {quantity, d, r, measured, sigma_stat, "
        "sigma_sys, theory, z, role, agrees}.\n"
        "Restyle a plot by editing its .gp script and running gnuplot on it in this folder "
        "(`gnuplot fig2_anisotropy.gp`).\n";
  write_file_atomic(dir / "report.md", md.str());
}

}  // namespace gs::jobs
