// `grainshock figures`: the paper's Figs. 1-5 (Jabeen, Rajesh, Ray, EPL 2010) and a report of
// every measured number next to the paper's, from one ensemble per (d, r).
#include <CLI/CLI.hpp>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <mutex>
#include <sstream>
#include <thread>

#include "analysis/crossover.h"
#include "analysis/ensemble_output.h"
#include "analysis/ensemble_runner.h"
#include "analysis/json.h"
#include "apps/cli.h"
#include "apps/commands.h"
#include "apps/ensemble_cli.h"
#include "apps/figures_plan.h"
#include "apps/plot.h"
#include "apps/progress.h"
#include "render/png.h"
#include "render/renderer.h"
#include "sim/engine.h"
#include "sim/error.h"
#include "sim/format.h"
#include "sim/stop.h"

namespace gs::app {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

double since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

struct FiguresOptions {
  bool quick = false, full = false, tiny = false, estimate = false;
  std::string out = "grainshock-figures";
  bool force = false, quiet = false;
  int threads = std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
  std::uint64_t seed = 1;
  int sample = 2;  // realisations per case for --estimate
};

struct CaseResult {
  const FigureCase* plan = nullptr;
  EnsembleSums sums;
  EnsembleFits fits;
  double wall = 0;
};

// One entry of summary.json "comparisons".
struct Comparison {
  std::string quantity;
  int d = 0;
  double r = std::numeric_limits<double>::quiet_NaN();
  double measured = std::numeric_limits<double>::quiet_NaN();
  double uncertainty = std::numeric_limits<double>::quiet_NaN();
  double theory = std::numeric_limits<double>::quiet_NaN();
  std::string relation = "equal";  // equal | below
  double tolerance = 0;
  std::string source;  // where the theory value comes from
  std::string note;
  bool agrees() const {
    if (!std::isfinite(measured)) return false;
    const double u = std::isfinite(uncertainty) ? uncertainty : 0;
    if (relation == "below") return measured - u < theory;
    return std::fabs(measured - theory) <= std::max(u, tolerance);
  }
};

std::string rtext(double r) {
  return format_number(r);
}

std::string fmt(double x, int digits = 4) {
  if (!std::isfinite(x)) return "n/a";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*g", digits, x);
  return buf;
}

// A plot that says why it is empty (gnuplot refuses to plot a file without points).
std::string no_data_plot(const std::string& csv, const std::string& why) {
  return "# " + csv + " has no rows: " + why + "\nset label 1 '" + why +
         "' at graph 0.5, 0.5 center\nunset key\nplot [0:1][0:1] -1 notitle\n";
}

// --- Fig. 1: frames from the renderer -----------------------------------------------------------

std::string render_fig1(const FiguresPlan& plan, const fs::path& dir) {
  const FigureCase* a = find_case(plan, 2, 0.1);
  const FigureCase* b = find_case(plan, 2, 1.0);
  GS_CHECK(a && b);
  try {
    render::Renderer renderer;
    render::View view;
    view.width = 1000;
    view.height = 1000;
    render::Style style;
    {
      PhysicsConfig c = a->spec.physics;
      c.realisation = 0;
      auto sim = make_simulation(c);
      std::vector<Snapshot> snaps;
      for (double t : plan.fig1a_times) {
        sim->run_until(t);
        snaps.push_back(sim->snapshot());
      }
      std::vector<const Snapshot*> ptrs;
      for (const auto& s : snaps) ptrs.push_back(&s);
      const auto img = renderer.render(ptrs, style, view);
      render::write_png((dir / "fig1a_overlay_r0.1.png").string(), img,
                        render::png_text(snaps.back().info, snaps.back().size()));
    }
    {
      PhysicsConfig c = b->spec.physics;
      c.realisation = 0;
      auto sim = make_simulation(c);
      sim->run_until(plan.fig1b_time);
      const Snapshot s = sim->snapshot();
      const auto img = renderer.render(s, style, view);
      render::write_png((dir / "fig1b_elastic_r1.png").string(), img,
                        render::png_text(s.info, s.size()));
    }
  } catch (const UserError& e) {
    return std::string("Fig. 1 not rendered: ") + e.what();
  }
  return {};
}

// --- CSV and gnuplot scripts for Figs. 2-5 -------------------------------------------------------

std::vector<const CaseResult*> cases_of(const std::vector<CaseResult>& all, int d, bool elastic) {
  std::vector<const CaseResult*> out;
  for (const auto& c : all)
    if (!c.plan->delta_scan && c.plan->spec.physics.dim == d &&
        (c.plan->spec.physics.restitution == 1.0) == elastic)
      out.push_back(&c);
  return out;
}

std::string fig2(const std::vector<CaseResult>& all, const fs::path& dir) {
  Table t;
  for (const char* n : {"d", "r", "t", "t_paper", "A", "A_sem"}) t.add_column(n, {});
  std::string plot;
  for (const auto& c : all) {
    if (c.plan->spec.physics.dim != 2 || c.plan->delta_scan) continue;
    const Table ts = c.sums.timeseries();
    const double r = c.plan->spec.physics.restitution;
    for (std::size_t i = 0; i < ts.rows(); ++i) {
      if (ts.column("active")[i] < 3) continue;  // no shape before the band has particles
      const std::vector<double> row = {2.0,
                                       r,
                                       ts.column("t")[i],
                                       ts.column("t_paper")[i],
                                       ts.column("anisotropy")[i],
                                       ts.column("anisotropy_sem")[i]};
      t.add_row(row);
    }
    plot += std::string(plot.empty() ? "plot " : ", \\\n     ") +
            "'fig2_anisotropy.csv' skip 1 using ($2==" + rtext(r) +
            " ? $4 : 1/0):5:6 with yerrorlines title 'r = " + rtext(r) + "'";
  }
  write_csv(t, dir / "fig2_anisotropy.csv");
  std::string gp = gnuplot_preamble("fig2_anisotropy.png", 900, 650);
  gp +=
      "set title 'Fig. 2: anisotropy index A(t) in 2D (mean over realisations)'\n"
      "set logscale x\nset xlabel 't (paper units 1/(v_0 n^{1/d}))'\nset ylabel 'A(t)'\n"
      "set yrange [0:1]\nset key top right\n" +
      plot + "\n";
  return run_gnuplot(dir, "fig2_anisotropy.gp", gp);
}

std::string fig3(const std::vector<CaseResult>& all, const fs::path& dir) {
  Table t;
  for (const char* n : {"d", "r", "t", "t_paper", "N", "N_sem", "E", "E_sem"}) t.add_column(n, {});
  std::string plot_n, plot_e, theory;
  for (int d : {2, 3}) {
    for (const CaseResult* c : cases_of(all, d, false)) {
      const Table ts = c->sums.timeseries();
      const double r = c->plan->spec.physics.restitution;
      for (std::size_t i = 0; i < ts.rows(); ++i) {
        const std::vector<double> row = {double(d),
                                         r,
                                         ts.column("t")[i],
                                         ts.column("t_paper")[i],
                                         ts.column("active")[i],
                                         ts.column("active_sem")[i],
                                         ts.column("energy")[i],
                                         ts.column("energy_sem")[i]};
        t.add_row(row);
      }
      const std::string sel = "($1==" + std::to_string(d) + " && $2==" + rtext(r) + " ? $4 : 1/0)";
      const std::string title = "'d = " + std::to_string(d) + ", r = " + rtext(r) + "'";
      plot_n += std::string(plot_n.empty() ? "plot " : ", \\\n     ") +
                "'fig3_active_energy.csv' skip 1 using " + sel + ":5 title " + title;
      plot_e += std::string(plot_e.empty() ? "plot " : ", \\\n     ") +
                "'fig3_active_energy.csv' skip 1 using " + sel + ":7 title " + title;
    }
    // Theory lines through the last point of the r = 0.1 curve.
    const auto cs = cases_of(all, d, false);
    if (!cs.empty()) {
      const Table ts = cs.front()->sums.timeseries();
      const double a = 1.0 / (d + 1);
      const double tp = ts.column("t_paper").back();
      const double n = ts.column("active").back(), e = ts.column("energy").back();
      char buf[400];
      // Drawn over the last two decades only, where the scaling regime is.
      std::snprintf(buf, sizeof buf,
                    "N%d(x) = x < %.6g ? 1/0 : %.6g*(x/%.6g)**(%.6g)\n"
                    "E%d(x) = x < %.6g ? 1/0 : %.6g*(x/%.6g)**(%.6g)\n",
                    d, tp / 100, n, tp, a * d, d, tp / 100, e, tp, a * d + 2 * a - 2);
      theory += buf;
      plot_n += ", \\\n     N" + std::to_string(d) +
                "(x) with lines lw 2 dt 2 lc 'black' title 't^{" +
                (d == 2 ? std::string("2/3") : std::string("3/4")) +
                "} (theory, d = " + std::to_string(d) + ")'";
      plot_e += ", \\\n     E" + std::to_string(d) +
                "(x) with lines lw 2 dt 2 lc 'black' title 't^{-" +
                (d == 2 ? std::string("2/3") : std::string("3/4")) +
                "} (theory, d = " + std::to_string(d) + ")'";
    }
  }
  write_csv(t, dir / "fig3_active_energy.csv");
  std::string gp = gnuplot_preamble("fig3_active_energy.png", 1400, 600);
  gp += theory;
  gp +=
      "set multiplot layout 1,2 title 'Fig. 3: mean active particles and kinetic energy (not "
      "shifted)'\n"
      "set samples 500\nset logscale xy\nset xlabel 't (paper units)'\nset format y '10^{%L}'\n"
      "set title '(a) <N_t>'\nset ylabel '<N_t>'\n" +
      plot_n + "\nset title '(b) <E_t>'\nset ylabel '<E_t>'\nset key bottom left\n" + plot_e +
      "\nunset multiplot\n";
  return run_gnuplot(dir, "fig3_active_energy.gp", gp);
}

std::string fig_collapse(const CaseResult& c, const fs::path& dir, const std::string& base,
                         int fig) {
  const Table d = [&] {
    // distributions_mean.csv of the case, as written in its ensemble folder.
    return read_csv(dir / "ensembles" / c.plan->name / "distributions_mean.csv");
  }();
  Table t;
  for (const char* n : {"t", "t_paper", "x_R", "f1", "x_v", "f2"}) t.add_column(n, {});
  const auto& p = c.plan->spec.physics;
  for (std::size_t i = 0; i < d.rows(); ++i) {
    const std::vector<double> row = {d.column("t")[i],   p.paper_time(d.column("t")[i]),
                                     d.column("x_R")[i], d.column("f1")[i],
                                     d.column("x_v")[i], d.column("f2")[i]};
    t.add_row(row);
  }
  write_csv(t, dir / (base + ".csv"));
  const double a = theory_alpha(p);
  std::string pr, pv;
  for (double ts : c.plan->spec.snapshot_times) {
    const std::string sel = "($1==" + format_number(ts) + " ? ";
    const std::string title = "'t = " + format_number(std::round(p.paper_time(ts))) + "'";
    pr += std::string(pr.empty() ? "plot " : ", \\\n     ") + "'" + base + ".csv' skip 1 using " +
          sel + "$3 : 1/0):4 title " + title;
    pv += std::string(pv.empty() ? "plot " : ", \\\n     ") + "'" + base + ".csv' skip 1 using " +
          sel + "$5 : 1/0):($6 > 0 ? $6 : 1/0) title " + title;
  }
  const std::string as = p.dim == 2 ? "1/3" : "1/4";
  std::string gp = gnuplot_preamble(base + ".png", 1400, 600);
  gp += "set multiplot layout 1,2 title 'Fig. " + std::to_string(fig) + ": scaling collapse in " +
        std::to_string(p.dim) + "D, r = " + rtext(p.restitution) + ", alpha = " + as +
        " (times in paper units)'\n";
  gp += "set title '(a) t^{alpha} P(R,t) against R t^{-alpha}'\nset xlabel 'R t^{-" + as +
        "}'\nset ylabel 't^{" + as + "} P(R,t)'\nset key top left\n" + pr + "\n";
  gp +=
      "set title '(b) t^{alpha-1} P(v,t) against v t^{1-alpha}'\nset xlabel 'v t^{1-alpha}'\n"
      "set ylabel 't^{alpha-1} P(v,t)'\nset logscale y\nset format y '10^{%L}'\nset key top "
      "right\n" +
      pv + "\n";
  gp += "unset multiplot\n";
  (void)a;
  return run_gnuplot(dir, base + ".gp", gp);
}

std::string fig_crossover(const std::vector<CaseResult>& all, const fs::path& dir,
                          std::vector<Comparison>& cmp, std::ostringstream& notes) {
  Table t;
  for (const char* n : {"d", "r", "one_minus_r2", "t_c1", "t_c1_paper"}) t.add_column(n, {});
  std::string plot, fits;
  for (int d : {2, 3}) {
    std::vector<double> x, y;
    for (const CaseResult* c : cases_of(all, d, false)) {
      const double r = c->plan->spec.physics.restitution;
      if (!c->fits.tc1.found) {
        notes << "- t_c1 not found for d = " << d << ", r = " << rtext(r) << ": "
              << c->fits.tc1.note << "\n";
        continue;
      }
      x.push_back(1 - r * r);
      y.push_back(c->fits.tc1.time);
      const std::vector<double> row = {double(d), r, 1 - r * r, c->fits.tc1.time,
                                       c->plan->spec.physics.paper_time(c->fits.tc1.time)};
      t.add_row(row);
    }
    Comparison phi;
    phi.quantity = "phi1";
    phi.d = d;
    phi.theory = d == 2 ? 2.25 : 3.0;
    phi.tolerance = 0.5;
    phi.source = "paper (t_c1 ~ (1-r^2)^-phi1)";
    if (x.size() >= 3) {
      const CrossoverExponent e = fit_crossover_exponent(x, y);
      phi.measured = e.phi;
      phi.uncertainty = e.standard_error;
      phi.note = "least-squares fit over r = 0.1, 0.5, 0.8 (" + std::to_string(e.points) +
                 " points); uncertainty: standard error of the slope";
      char buf[200];
      std::snprintf(buf, sizeof buf, "T%d(x) = %.6g*x**(-%.6g)\n", d, e.prefactor, e.phi);
      fits += buf;
      plot += std::string(plot.empty() ? "" : ", \\\n     ") + "T" + std::to_string(d) +
              "(x) with lines dt 2 title sprintf('d = " + std::to_string(d) +
              " fit: phi_1 = %.2f', " + format_double(e.phi) + ")";
    } else {
      phi.note = "fewer than 3 crossover times found";
    }
    cmp.push_back(phi);
    plot = "'fig6_crossover.csv' skip 1 using ($1==" + std::to_string(d) +
           " ? $3 : 1/0):4 with points pt 7 ps 1.5 title 'd = " + std::to_string(d) +
           " (slope rule)'" + (plot.empty() ? "" : ", \\\n     ") + plot;
  }
  write_csv(t, dir / "fig6_crossover.csv");
  std::string gp = gnuplot_preamble("fig6_crossover.png", 900, 650);
  if (t.rows() == 0)
    return run_gnuplot(dir, "fig6_crossover.gp",
                       gp + no_data_plot("fig6_crossover.csv", "no t_c1 found in these runs"));
  gp += fits;
  gp +=
      "set title 'Crossover time t_{c1} against 1 - r^2 (paper: phi_1 = 2.25 in 2D, 3.0 in 3D)'\n"
      "set logscale xy\nset xlabel '1 - r^2'\nset ylabel 't_{c1} (simulation units)'\nset key top "
      "right\n"
      "plot " +
      plot + "\n";
  return run_gnuplot(dir, "fig6_crossover.gp", gp);
}

// t_c2 against delta: the time from which the local slope of <N_t> leaves the 10% band around
// alpha d for good (towards the elastic 2/(d+2) d), searched from <N_t> >= 20 on.
std::string fig_delta(const std::vector<CaseResult>& all, const fs::path& dir,
                      std::vector<Comparison>& cmp, std::ostringstream& notes) {
  Table t;
  for (const char* n : {"delta", "t_c2", "t_c2_paper"}) t.add_column(n, {});
  std::vector<double> x, y;
  for (const auto& c : all) {
    if (!c.plan->delta_scan) continue;
    const auto& p = c.plan->spec.physics;
    const Table ts = c.sums.timeseries();
    const auto& tt = ts.column("t");
    const auto& n = ts.column("active");
    SlopeCrossoverOptions o;
    o.target = theory_alpha(p) * p.dim;
    for (std::size_t i = 0; i < n.size(); ++i)
      if (n[i] >= 20) {
        o.t_lo = tt[i];
        break;
      }
    const Crossover tc2 = crossover_leave(tt, n, o);
    if (!tc2.found) {
      notes << "- t_c2 not found for delta = " << fmt(p.cutoff) << ": " << tc2.note << "\n";
      continue;
    }
    notes << "- t_c2(delta = " << fmt(p.cutoff) << ") = " << fmt(tc2.time) << " (2D, r = 0.1, "
          << c.sums.count() << " realisations)\n";
    x.push_back(p.cutoff);
    y.push_back(tc2.time);
    const std::vector<double> row = {p.cutoff, tc2.time, p.paper_time(tc2.time)};
    t.add_row(row);
  }
  Comparison phi;
  phi.quantity = "phi2";
  phi.d = 2;
  phi.r = 0.1;
  phi.theory = 1.5;
  phi.tolerance = 0.3;
  phi.source = "paper: t_c2 ~ delta^-phi2, phi2 = 1/(1-alpha) = 3/2 in 2D";
  std::string fitline;
  if (x.size() >= 3) {
    const CrossoverExponent e = fit_crossover_exponent(x, y);
    phi.measured = e.phi;
    phi.uncertainty = e.standard_error;
    phi.note =
        "least-squares fit of ln t_c2 against ln delta over delta = 1e-2, 3e-3, 1e-3; "
        "uncertainty: standard error of the slope";
    char buf[200];
    std::snprintf(buf, sizeof buf, "T(x) = %.6g*x**(-%.6g)\n", e.prefactor, e.phi);
    fitline = buf;
  } else {
    phi.note = "fewer than 3 values of t_c2 found";
  }
  cmp.push_back(phi);
  write_csv(t, dir / "fig7_tc2_delta.csv");
  std::string gp = gnuplot_preamble("fig7_tc2_delta.png", 900, 650);
  if (t.rows() == 0)
    return run_gnuplot(dir, "fig7_tc2_delta.gp",
                       gp + no_data_plot("fig7_tc2_delta.csv", "no t_c2 reached in these runs"));
  gp += fitline;
  gp +=
      "set title 'Crossover time t_{c2} against the cutoff delta (2D, r = 0.1; paper: phi_2 = "
      "3/2)'\n"
      "set logscale xy\nset xlabel 'delta'\nset ylabel 't_{c2} (simulation units)'\nset key top "
      "right\n"
      "plot 'fig7_tc2_delta.csv' skip 1 using 1:2 with points pt 7 ps 1.5 title 'slope rule'";
  if (!fitline.empty())
    gp += ", \\\n     T(x) with lines dt 2 title sprintf('fit: phi_2 = %.2f', " +
          format_double(phi.measured) + ")";
  gp += "\n";
  return run_gnuplot(dir, "fig7_tc2_delta.gp", gp);
}

// --- Comparisons ---------------------------------------------------------------------------------

void add_comparisons(const CaseResult& c, std::vector<Comparison>& out) {
  const auto& p = c.plan->spec.physics;
  const double r = p.restitution;
  for (const auto& e : c.fits.exponents) {
    if (r == 1 && e.column == "energy") continue;  // conserved: says nothing about alpha
    Comparison x;
    x.quantity = "alpha from " + e.quantity;
    x.d = p.dim;
    x.r = r;
    x.measured = e.alpha;
    x.uncertainty = e.alpha_uncertainty;
    x.theory = c.fits.alpha_theory;
    x.tolerance = 0.02;
    x.source = r < 1 ? "scaling theory 1/(d+1)" : "scaling theory 2/(d+2)";
    x.note = e.note.empty()
                 ? "exponent " + format_number(e.fit.exponent) + " over t in [" +
                       format_number(e.fit.window.t_lo) + ", " + format_number(e.fit.window.t_hi) +
                       "]; uncertainty: half width of the 95% bootstrap interval"
                 : e.note;
    out.push_back(x);
  }
  Comparison a;
  a.quantity = "A(t_max)";
  a.d = p.dim;
  a.r = r;
  a.measured = c.fits.anisotropy;
  a.uncertainty = c.fits.anisotropy_sem;
  if (r < 1) {
    a.relation = "below";
    a.theory = 1;
    a.source = "paper: A(t) converges to a value below 1 for r < 1";
  } else {
    a.theory = 0;
    a.tolerance = 0.05;
    a.source = "paper: A(t) converges to 0 for r = 1";
  }
  a.note = "mean over realisations at the last sample; uncertainty: standard error";
  out.push_back(a);
  if (p.dim == 2) {
    for (int k = 0; k < 2; ++k) {
      Comparison b;
      b.quantity = k == 0 ? "band packing (typical)" : "band packing (upper, 90% quantile)";
      b.d = 2;
      b.r = r;
      b.measured = k == 0 ? c.fits.packing_typical : c.fits.packing_upper;
      b.uncertainty = k == 0 ? c.fits.packing_typical_sem : c.fits.packing_upper_sem;
      b.theory = r < 1 ? 0.80 : 0.47;
      b.tolerance = r < 1 ? 0.02 : 0.05;
      b.source = r < 1 ? "paper: 0.78-0.82 for r < 1 (cells of side 10)" : "paper: ~0.47 for r = 1";
      b.note = "at the last snapshot time; uncertainty: standard error over realisations";
      out.push_back(b);
    }
  }
  if (r == 0.1) {
    for (int k = 0; k < 2; ++k) {
      Comparison q;
      q.quantity = k == 0 ? "collapse quality Q of P(R,t)" : "collapse quality Q of P(v,t)";
      q.d = p.dim;
      q.r = r;
      q.measured = k == 0 ? c.fits.collapse_radius : c.fits.collapse_speed;
      q.theory = 0;
      q.tolerance = 0.05;
      q.source = "perfect collapse (paper Figs. 4, 5); Q = inter-curve variance / curve variance";
      q.note = c.fits.collapse_note;
      out.push_back(q);
    }
  }
}

std::string comparisons_json(const std::vector<Comparison>& cmp) {
  std::ostringstream j;
  j << "[\n";
  for (std::size_t k = 0; k < cmp.size(); ++k) {
    const auto& c = cmp[k];
    j << "    {\"quantity\": " << json_string(c.quantity) << ", \"d\": " << c.d
      << ", \"r\": " << json_number(c.r) << ", \"measured\": " << json_number(c.measured)
      << ", \"uncertainty\": " << json_number(c.uncertainty)
      << ", \"theory\": " << json_number(c.theory) << ", \"relation\": " << json_string(c.relation)
      << ", \"tolerance\": " << json_number(c.tolerance)
      << ", \"agrees\": " << (c.agrees() ? "true" : "false")
      << ", \"source\": " << json_string(c.source) << ", \"note\": " << json_string(c.note) << "}"
      << (k + 1 < cmp.size() ? "," : "") << "\n";
  }
  j << "  ]";
  return j.str();
}

// --- The command ---------------------------------------------------------------------------------

FiguresMode mode_of(const FiguresOptions& o) {
  if (int(o.quick) + int(o.full) + int(o.tiny) > 1)
    throw UserError("figures: give at most one of --quick, --full, --tiny");
  return o.full ? FiguresMode::Full : o.tiny ? FiguresMode::Tiny : FiguresMode::Quick;
}

// --estimate: a sample of realisations of every case, run `threads` at a time as the real run
// would, extrapolated to the plan's realisation counts.
void estimate(const FiguresOptions& o, const FiguresPlan& plan, const fs::path& dir) {
  std::ostringstream j, table;
  j << "{\n  \"mode\": " << json_string(to_string(plan.mode)) << ",\n  \"threads\": " << o.threads
    << ",\n  \"sample_per_case\": " << o.sample << ",\n  \"cases\": [\n";
  table << "| case | N | t_max | M | sample wall (s) | s per realisation per thread | estimated "
           "wall (s) |\n"
           "|---|---|---|---|---|---|---|\n";
  double total = 0;
  for (std::size_t k = 0; k < plan.cases.size(); ++k) {
    const auto& c = plan.cases[k];
    EnsembleSpec s = c.spec;
    s.realisations = static_cast<std::uint64_t>(o.sample);
    RunnerOptions ro;
    ro.threads = o.threads;
    const auto t0 = Clock::now();
    const RunnerResult r = run_ensemble(s, ro);
    const double wall = since(t0);
    if (r.interrupted) throw UserError("interrupted");
    // Each thread ran sample/threads realisations in `wall`.
    const double per = wall * std::min(o.threads, o.sample) / o.sample;
    const double est = per * double(c.spec.realisations) / o.threads;
    total += est;
    j << "    {\"case\": " << json_string(c.name) << ", \"particles\": " << c.spec.physics.particles
      << ", \"t_max\": " << json_number(c.spec.physics.t_max)
      << ", \"realisations\": " << c.spec.realisations
      << ", \"sample_wall_seconds\": " << json_number(wall)
      << ", \"estimated_wall_seconds\": " << json_number(est) << "}"
      << (k + 1 < plan.cases.size() ? "," : "") << "\n";
    table << "| " << c.name << " | " << c.spec.physics.particles << " | "
          << fmt(c.spec.physics.t_max) << " | " << c.spec.realisations << " | " << fmt(wall)
          << " | " << fmt(per) << " | " << fmt(est) << " |\n";
    if (!o.quiet)
      std::fprintf(stderr,
                   "grainshock: estimate %s: %d realisations in %.3g s -> %.4g s for %llu\n",
                   c.name.c_str(), o.sample, wall, est,
                   static_cast<unsigned long long>(c.spec.realisations));
  }
  j << "  ],\n  \"estimated_wall_seconds\": " << json_number(total) << "\n}\n";
  write_file_atomic(dir / "estimate.json", j.str());
  std::ostringstream md;
  md << "# Wall-time estimate of `grainshock figures --" << to_string(plan.mode) << "`\n\n"
     << "From " << o.sample << " realisations per case run on " << o.threads
     << " threads, scaled to the plan's realisation counts (the renderer and plots add "
        "seconds).\n\n"
     << table.str() << "\n**Total: " << fmt(total) << " s (" << fmt(total / 60, 3) << " min).**\n";
  write_file_atomic(dir / "estimate.md", md.str());
  if (!o.quiet)
    std::fprintf(stderr, "grainshock: estimated wall time %.4g s (%.3g min)\n", total, total / 60);
}

void run(const FiguresOptions& o) {
  const FiguresMode mode = mode_of(o);
  if (o.threads < 1) throw UserError("--threads must be at least 1");
  if (o.sample < 1) throw UserError("--sample must be at least 1");
  const FiguresPlan plan = figures_plan(mode, o.seed);
  const auto dir = prepare_output_dir(o.out, o.force);
  install_stop_handlers();
  if (o.estimate) return estimate(o, plan, dir);

  const auto t0 = Clock::now();
  std::vector<CaseResult> results;
  std::uint64_t total = 0, done_before = 0;
  for (const auto& c : plan.cases) total += c.spec.realisations;
  Progress progress(o.quiet);
  std::vector<Comparison> cmp;
  for (const auto& c : plan.cases) {
    RunnerOptions ro;
    ro.threads = o.threads;
    ro.on_progress = [&](std::uint64_t done, std::uint64_t) {
      progress.update(double(done_before + done) / double(total),
                      c.name + ": " + std::to_string(done) + " of " +
                          std::to_string(c.spec.realisations) + " realisations");
    };
    const auto tc = Clock::now();
    RunnerResult r = run_ensemble(c.spec, ro);
    if (r.interrupted)
      throw UserError("interrupted; the ensembles finished so far are in " + dir.string());
    done_before += c.spec.realisations;
    const auto edir = dir / "ensembles" / c.name;
    fs::create_directories(edir);
    CaseResult cr{&c, std::move(r.sums), {}, since(tc)};
    cr.fits = write_ensemble_folder(edir, cr.sums, FitOptions{}, cr.wall, o.threads);
    if (!c.delta_scan) add_comparisons(cr, cmp);
    results.push_back(std::move(cr));
  }
  progress.done();
  const double sim_wall = since(t0);

  std::vector<std::string> problems;
  std::ostringstream notes;
  auto check = [&](std::string e) {
    if (!e.empty()) problems.push_back(std::move(e));
  };
  check(render_fig1(plan, dir));
  check(fig2(results, dir));
  check(fig3(results, dir));
  for (const auto& c : results)
    if (c.plan->spec.physics.restitution == 0.1 && !c.plan->delta_scan)
      check(fig_collapse(c, dir,
                         c.plan->spec.physics.dim == 2 ? "fig4_collapse_2d" : "fig5_collapse_3d",
                         c.plan->spec.physics.dim == 2 ? 4 : 5));
  check(fig_crossover(results, dir, cmp, notes));
  check(fig_delta(results, dir, cmp, notes));
  const double wall = since(t0);

  // t_c2 where the data reach it.
  for (const auto& c : results) {
    const auto& p = c.plan->spec.physics;
    if (c.plan->delta_scan) continue;
    if (p.restitution < 1 && !c.fits.tc2.found)
      notes << "- t_c2 (d = " << p.dim << ", r = " << rtext(p.restitution)
            << ") not reached by t_max = " << fmt(p.t_max)
            << ": v_t is still far above delta = " << fmt(p.cutoff)
            << " (expected t_c2 ~ delta^-1/(1-alpha), "
            << fmt(std::pow(p.cutoff, -1 / (1 - theory_alpha(p))), 3)
            << " in units where v_t ~ t^(alpha-1) with prefactor 1)\n";
    else if (c.fits.tc2.found)
      notes << "- t_c2 (d = " << p.dim << ", r = " << rtext(p.restitution)
            << ") = " << fmt(c.fits.tc2.time) << "\n";
  }

  // summary.json
  std::ostringstream j;
  j << "{\n  \"version\": " << json_string(GRAINSHOCK_VERSION)
    << ",\n  \"mode\": " << json_string(to_string(mode)) << ",\n  \"seed\": " << o.seed
    << ",\n  \"threads\": " << o.threads << ",\n  \"wall_seconds\": " << json_number(wall)
    << ",\n  \"simulation_wall_seconds\": " << json_number(sim_wall) << ",\n  \"cases\": [\n";
  for (std::size_t k = 0; k < results.size(); ++k) {
    const auto& c = results[k];
    const auto& p = c.plan->spec.physics;
    j << "    {\"name\": " << json_string(c.plan->name) << ", \"d\": " << p.dim
      << ", \"r\": " << json_number(p.restitution) << ", \"particles\": " << p.particles
      << ", \"t_max\": " << json_number(p.t_max) << ", \"realisations\": " << c.sums.count()
      << ", \"wall_seconds\": " << json_number(c.wall)
      << ", \"t_c1\": " << json_number(c.fits.tc1.time)
      << ", \"t_c2\": " << json_number(c.fits.tc2.time)
      << ", \"folder\": " << json_string("ensembles/" + c.plan->name) << "}"
      << (k + 1 < results.size() ? "," : "") << "\n";
  }
  j << "  ],\n  \"comparisons\": " << comparisons_json(cmp) << ",\n  \"problems\": [";
  for (std::size_t k = 0; k < problems.size(); ++k)
    j << (k ? ", " : "") << json_string(problems[k]);
  j << "]\n}\n";
  write_file_atomic(dir / "summary.json", j.str());

  // report.md
  std::ostringstream md;
  md << "# grainshock figures (" << to_string(mode) << ")\n\n"
     << "Jabeen, Rajesh, Ray, EPL 2010, reproduced by `grainshock figures --" << to_string(mode)
     << " --threads " << o.threads << " --seed " << o.seed << "` in " << fmt(wall, 4) << " s wall ("
     << fmt(sim_wall, 4) << " s of simulation).\n\n## Runs\n\n"
     << "| case | d | r | N | t_max (sim) | t_max (paper) | realisations | wall (s) "
        "|\n|---|---|---|---|---|---|---|---|\n";
  for (const auto& c : results) {
    const auto& p = c.plan->spec.physics;
    md << "| " << c.plan->name << " | " << p.dim << " | " << rtext(p.restitution) << " | "
       << p.particles << " | " << fmt(p.t_max) << " | " << fmt(p.paper_time(p.t_max)) << " | "
       << c.sums.count() << " | " << fmt(c.wall, 3) << " |\n";
  }
  md << "\nEach case's averaged time series, distributions and fits are in `ensembles/<case>/` "
        "(see its summary.json for the windows and intervals).\n\n## Measured against the paper\n\n"
     << "| quantity | d | r | measured | uncertainty | paper / theory | agrees | note "
        "|\n|---|---|---|---|---|---|---|---|\n";
  for (const auto& c : cmp)
    md << "| " << c.quantity << " | " << c.d << " | " << (std::isfinite(c.r) ? rtext(c.r) : "-")
       << " | " << fmt(c.measured) << " | " << fmt(c.uncertainty, 2) << " | "
       << (c.relation == "below" ? "< " : "") << fmt(c.theory) << " | "
       << (c.agrees() ? "yes" : "**no**") << " | " << c.note << " |\n";
  md << "\n'agrees': |measured - theory| <= max(uncertainty, tolerance) with tolerance 0.02 for "
        "alpha, "
        "0.5 for phi1, 0.02 for the packing (the paper's range 0.78-0.82), 0.05 for A -> 0 and for "
        "Q; for "
        "'< 1', measured - uncertainty < 1.\n\n## Definitions\n\n"
        "- alpha from X: the exponent of <X> fitted as a straight line of ln <X> against ln t over "
        "a scaling "
        "window (the longest range within the last 1.5 decades, once <N_t> >= 20, where the local "
        "log-slope "
        "stays within +-0.05; without one, the last decade), turned "
        "into alpha by N ~ t^(alpha d), E ~ t^(alpha d + 2 alpha - 2), R ~ t^alpha, v ~ "
        "t^(alpha-1); the "
        "uncertainty is half the 95% percentile interval of 1000 bootstrap resamples of the "
        "realisations.\n"
        "- t_c1: the time from which the local slope of <N_t> stays within 10% of alpha d (slope "
        "rule); "
        "phi1: least-squares slope of ln t_c1 against -ln(1 - r^2) over r = 0.1, 0.5, 0.8, with "
        "its standard "
        "error. t_c2: the later time from which the slope leaves that band for good.\n"
        "- Band packing: cells of side ~10; `typical` = active-weighted mean packing fraction of "
        "cells "
        "holding band particles; `upper` = active-weighted 90% quantile. A band only ~10 diameters "
        "thick "
        "leaves most cells straddling its edges, which pulls `typical` below the packing inside "
        "the band.\n"
        "- Q (collapse quality): mean inter-curve variance of the scaled distributions on a common "
        "grid over "
        "the variance of their mean curve (0 = perfect collapse).\n"
        "- A(t): ((l1-l2)/(l1+l2))^2 in 2D, relative shape anisotropy in 3D, of the gyration "
        "tensor of the "
        "active particles, averaged over realisations.\n\n## Notes\n\n"
     << notes.str();
  for (const auto& p : problems) md << "- problem: " << p << "\n";
  md << "\n## Files\n\n"
        "- fig1a_overlay_r0.1.png: active particles of one 2D r = 0.1 realisation at four times "
        "(Fig. 1a); "
        "fig1b_elastic_r1.png: 2D r = 1 (Fig. 1b).\n"
        "- fig2_anisotropy.{png,csv,gp}: A(t) in 2D (Fig. 2).\n"
        "- fig3_active_energy.{png,csv,gp}: <N_t>, <E_t> in 2D and 3D with the theory's slopes "
        "(Fig. 3).\n"
        "- fig4_collapse_2d.{png,csv,gp}, fig5_collapse_3d.{png,csv,gp}: scaled P(R,t), P(v,t) for "
        "r = 0.1 "
        "(Figs. 4, 5).\n"
        "- fig6_crossover.{png,csv,gp}: t_c1 against 1 - r^2 and the phi1 fits.\n"
        "- fig7_tc2_delta.{png,csv,gp}: t_c2 against the cutoff delta (2D, r = 0.1) and the phi2 "
        "fit.\n"
        "- summary.json: every comparison as {quantity, d, r, measured, uncertainty, theory, "
        "agrees}.\n"
        "Restyle a plot by editing its .gp script and running `gnuplot figN.gp` in this folder.\n";
  write_file_atomic(dir / "report.md", md.str());
  if (!o.quiet) {
    std::fprintf(stderr, "grainshock: figures (%s) in %.4g s; report in %s\n", to_string(mode),
                 wall, (dir / "report.md").c_str());
    for (const auto& p : problems) std::fprintf(stderr, "grainshock: warning: %s\n", p.c_str());
  }
}

}  // namespace

void add_figures_command(CLI::App& app) {
  auto opt = std::make_shared<FiguresOptions>();
  auto* sub =
      app.add_subcommand("figures", "Reproduce the paper's Figs. 1-5 and a report with numbers");
  sub->add_flag("--quick", opt->quick,
                "Smaller systems, fewer realisations: about 1.5 minutes on 2 cores (default)");
  sub->add_flag("--full", opt->full,
                "The paper's sizes: 2.5e5 discs, 2e6 spheres, 100 realisations (about 26 minutes "
                "on 2 cores)");
  sub->add_flag("--tiny", opt->tiny,
                "Seconds-long smoke run (tests): every file, meaningless numbers");
  sub->add_flag(
      "--estimate", opt->estimate,
      "Only estimate the wall time of the chosen mode from --sample realisations per case");
  sub->add_option("--sample", opt->sample, "Realisations per case for --estimate")
      ->capture_default_str();
  add_output_options(*sub, opt->out, opt->force, opt->quiet);
  sub->add_option("--threads", opt->threads, "Worker threads")->capture_default_str();
  sub->add_option("--seed", opt->seed, "Master seed of every ensemble")->capture_default_str();
  sub->callback([opt] { run(*opt); });
}

}  // namespace gs::app
