#include "jobs/figures_plots.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <limits>
#include <span>

#include "analysis/quantile.h"
#include "analysis/snowplow.h"
#include "jobs/plot.h"
#include "render/png.h"
#include "render/renderer.h"
#include "sim/engine.h"
#include "sim/error.h"
#include "sim/format.h"
#include "sim/stop.h"

namespace gs::jobs {
namespace {

namespace fs = std::filesystem;

// Where figures go and in which formats.
struct Out {
  fs::path dir;
  std::vector<std::string> formats;
  std::string plot(const std::string& script_name, const std::string& script) const {
    return run_gnuplot(dir, script_name, script, formats);
  }
};

// Every time axis is in the paper's unit, its initial mean collision time 1/(v_0 n^(1/d)):
// t_paper = t v_0 n^(1/d), 0.5 t in 2D and 0.63 t in 3D at n = 0.25 (PhysicsConfig::paper_time).
constexpr const char* kPaperTimeLabel = "t (paper units 1/(v_0 n^{1/d}))";

std::string rtext(double r) {
  return format_number(r);
}

// A plot that says why it is empty (gnuplot refuses to plot a file without points).
std::string no_data_plot(const std::string& csv, const std::string& why) {
  return "# " + csv + " has no rows: " + why + "\nset label 1 '" + why +
         "' at graph 0.5, 0.5 center\nunset key\nplot [0:1][0:1] -1 notitle\n";
}

// Fig. 1 in diameters, the paper's length unit: a scale bar says how many (the framing follows
// the active particles, so the picture's width alone says nothing). Each snapshot's label gives
// t and t_paper.
std::string render_fig1(const Fig1Snapshots& s, const fs::path& dir) {
  try {
    render::Renderer renderer;
    render::View view;
    view.width = 1000;
    view.height = 1000;
    render::Style style;
    style.scale_bar = true;
    // Fig. 1b's colour bar: speeds in units of the kick's, the paper's v_0 (the plan kicks at
    // speed 1, so the engine's speeds are in v_0); lengths are in diameters, the scale bar's.
    GS_CHECK(s.b.info.speed.value_or(1.0) == 1.0);
    style.bar_label = "speed |v| / v_0";
    std::vector<const Snapshot*> ptrs;
    for (const auto& x : s.a) ptrs.push_back(&x);
    render::write_png((dir / "fig1a_overlay_r0.1.png").string(), renderer.render(ptrs, style, view),
                      render::png_text(s.a.back().info, s.a.back().size()));
    render::write_png((dir / "fig1b_elastic_r1.png").string(), renderer.render(s.b, style, view),
                      render::png_text(s.b.info, s.b.size()));
  } catch (const UserError& e) {
    return std::string("Fig. 1 not rendered: ") + e.what();
  }
  return {};
}

std::vector<const CaseResult*> cases_of(const std::vector<CaseResult>& all, int d, bool elastic) {
  std::vector<const CaseResult*> out;
  for (const auto& c : all)
    if (c.plan->role == CaseRole::Paper && c.plan->spec.physics.dim == d &&
        c.plan->spec.physics.elastic() == elastic)
      out.push_back(&c);
  return out;
}

// The r < 1 cases of dimension d that phi1 is read from, r ascending (towards the elastic limit):
// the paper's, a Limit case (`figures --limit`) taking the place of the paper case of its r, the
// same physics run to its plateau in the unbounded medium.
std::vector<const CaseResult*> phi1_cases(const std::vector<CaseResult>& all, int d) {
  std::vector<const CaseResult*> out = cases_of(all, d, false);
  for (const auto& c : all) {
    if (c.plan->role != CaseRole::Limit || c.plan->spec.physics.dim != d) continue;
    const double r = c.plan->spec.physics.restitution;
    std::erase_if(out, [&](const CaseResult* p) { return p->plan->spec.physics.restitution == r; });
    out.push_back(&c);
  }
  std::stable_sort(out.begin(), out.end(), [](const CaseResult* a, const CaseResult* b) {
    return a->plan->spec.physics.restitution < b->plan->spec.physics.restitution;
  });
  return out;
}

// Theory lines are told apart by dimension: d = 2 black dashes, d = 3 dark red dots-dashes.
std::string theory_style(int d) {
  return d == 2 ? "lw 2 dt 2 lc rgb 'black'" : "lw 2 dt 4 lc rgb '#a00000'";
}

std::string exponent_text(int d, bool energy) {
  return std::string(energy ? "-" : "") + (d == 2 ? "2/3" : "3/4");
}

std::string fig2(const std::vector<CaseResult>& all, const Out& out) {
  Table t;
  for (const char* n : {"d", "r", "t", "t_paper", "A", "A_sem"}) t.add_column(n, {});
  std::string plot;
  auto cases = cases_of(all, 2, false);
  for (const CaseResult* c : cases_of(all, 2, true)) cases.push_back(c);
  for (const CaseResult* c : cases) {
    const Table ts = c->sums.timeseries();
    const double r = c->plan->spec.physics.restitution;
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
  write_csv(t, out.dir / "fig2_anisotropy.csv");
  std::string gp = gnuplot_preamble("fig2_anisotropy", 900, 650);
  gp +=
      "set title 'Fig. 2: anisotropy index A(t) in 2D (mean over realisations)'\n"
      "set logscale xy\nset xlabel '" + std::string(kPaperTimeLabel) + "'\nset ylabel 'A(t)'\n"
      "set yrange [*:1]\nset format y '10^{%L}'\nset key bottom left\n" +
      plot + "\n";
  return out.plot("fig2_anisotropy.gp", gp);
}

// The theory's line y = A t^b through the last decade of a curve (t in paper units): A is the
// least-squares prefactor with b fixed, mean(ln y - b ln t), so that the line follows the late
// curve rather than hanging on its last point. NaN if no positive point lies there.
double late_prefactor(std::span<const double> t, std::span<const double> y, double b) {
  double sum = 0;
  int n = 0;
  for (std::size_t i = 0; i < t.size(); ++i)
    if (t[i] >= t.back() / 10 && y[i] > 0) {
      sum += std::log(y[i]) - b * std::log(t[i]);
      ++n;
    }
  return n > 0 ? std::exp(sum / n) : std::numeric_limits<double>::quiet_NaN();
}

// Fig. 3 as the paper's: <N_t> (a) and <E_t> (b) of r = 0.1, 0.5, 0.8, the 2D curves below and
// the 3D ones above, each shifted up a decade from the one before it "for the sake of clarity"
// (the key gives the factor), with the theory's exponent drawn along each curve over its last
// two decades, its prefactor fitted over the last decade (late_prefactor).
std::string fig3(const std::vector<CaseResult>& all, const Out& out) {
  Table t;
  for (const char* n : {"d", "r", "t", "t_paper", "N", "N_sem", "E", "E_sem"}) t.add_column(n, {});
  std::string plot_n, plot_e, theory;
  int k = 0;  // the curve's place from the bottom: shifted by 10^k
  for (int d : {2, 3}) {
    const double a = 1.0 / (d + 1);
    bool titled = false;
    for (const CaseResult* c : cases_of(all, d, false)) {
      const Table ts = c->sums.timeseries();
      const double r = c->plan->spec.physics.restitution;
      // The paper's Fig. 3 shows r = 0.1, 0.5, 0.8; the other r are there for phi1 (fig6).
      const int colour = r == 0.1 ? 1 : r == 0.5 ? 2 : r == 0.8 ? 3 : 0;
      if (colour == 0) continue;
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
      const std::string shift = "1e" + std::to_string(k);
      const std::string sel = "($1==" + std::to_string(d) + " && $2==" + rtext(r) + " ? $4 : 1/0)";
      // Colour by r, open points in 2D and filled ones in 3D.
      // 3D takes colours 4-6, so that no 2D and 3D curve share one.
      const std::string title = " lc " + std::to_string(colour + (d == 3 ? 3 : 0)) + " pt " +
                                (d == 2 ? "6" : "7") + " title 'd = " + std::to_string(d) +
                                ", r = " + rtext(r) + (k > 0 ? " (× 10^{" + std::to_string(k) + "})" : "") + "'";
      plot_n += std::string(plot_n.empty() ? "plot " : ", \\\n     ") +
                "'fig3_active_energy.csv' skip 1 using " + sel + ":($5*" + shift + ")" + title;
      plot_e += std::string(plot_e.empty() ? "plot " : ", \\\n     ") +
                "'fig3_active_energy.csv' skip 1 using " + sel + ":($7*" + shift + ")" + title;
      const auto tp = ts.column("t_paper");
      const double bn = a * d, be = a * d + 2 * a - 2;
      const double an = late_prefactor(tp, ts.column("active"), bn);
      const double ae = late_prefactor(tp, ts.column("energy"), be);
      const double lo = std::max(tp.front(), tp.back() / 100), hi = tp.back();
      const std::string ks = std::to_string(k), ds = std::to_string(d);
      char buf[400];
      std::snprintf(buf, sizeof buf,
                    "N%d(x) = x < %.6g || x > %.6g ? 1/0 : %s*%.6g*x**(%.6g)\n"
                    "E%d(x) = x < %.6g || x > %.6g ? 1/0 : %s*%.6g*x**(%.6g)\n",
                    k, lo, hi, shift.c_str(), an, bn, k, lo, hi, shift.c_str(), ae, be);
      theory += buf;
      auto titled_key = [&](bool energy) {
        return titled ? std::string(" notitle")
                      : " title 't^{" + exponent_text(d, energy) + "} (theory, d = " + ds +
                            "; prefactor fitted over the last decade)'";
      };
      plot_n += ", \\\n     N" + ks + "(x) with lines " + theory_style(d) + titled_key(false);
      plot_e += ", \\\n     E" + ks + "(x) with lines " + theory_style(d) + titled_key(true);
      titled = true;
      ++k;
    }
  }
  write_csv(t, out.dir / "fig3_active_energy.csv");
  std::string gp = gnuplot_preamble("fig3_active_energy", 1400, 800);
  gp += theory;
  gp += std::string(
            "set multiplot layout 1,2 title 'Fig. 3: mean active particles and kinetic energy, "
            "2D below and 3D above, each curve shifted a decade from the one below it'\n"
            "set samples 500\nset logscale xy\nset xlabel '") +
        kPaperTimeLabel +
        "'\nset format y '10^{%L}'\n"
        "set format x '10^{%L}'\nset key below maxrows 4 font ',9'\nset bmargin 8\n"
        "set title '(a) ⟨N_t⟩ (shifted)'\nset ylabel '⟨N_t⟩ × 10^k'\n" +
        plot_n + "\nset title '(b) ⟨E_t⟩ (shifted)'\nset ylabel '⟨E_t⟩ × 10^k'\n" +
        plot_e + "\nunset multiplot\n";
  return out.plot("fig3_active_energy.gp", gp);
}

// The x-range over which some curve is above `floor` times the largest value of any, padded: the
// scaled distributions' bins reach 5 theory scales (analysis/realisation.h), most of them empty or
// a few particles' noise, which squeezed the collapse into a corner of the panel.
std::string filled_xrange(const Table& t, const char* x, const char* f, double floor) {
  double peak = 0;
  for (double v : t.column(f))
    if (std::isfinite(v)) peak = std::max(peak, v);
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (std::size_t i = 0; i < t.rows(); ++i)
    if (std::isfinite(t.column(f)[i]) && t.column(f)[i] >= floor * peak && peak > 0) {
      lo = std::min(lo, t.column(x)[i]);
      hi = std::max(hi, t.column(x)[i]);
    }
  if (!(lo < hi)) return "set xrange [*:*]\n";
  const double pad = 0.05 * (hi - lo);
  return "set xrange [" + format_double(std::max(0.0, lo - pad)) + ":" + format_double(hi + pad) +
         "]\n";
}

// Figs. 4 and 5 in the paper's time unit (t_paper = t v_0 n^(1/d)), R in diameters and v in v_0,
// scaled with the theory's alpha as the paper's: x = R t_paper^-alpha, f1 = t_paper^alpha P(R,t),
// and v t_paper^(1-alpha), t_paper^(alpha-1) P(v,t), each with its standard error over the
// realisations (distributions_mean.csv's P_R_sem, P_v_sem) drawn as error bars. Drawn at the
// case's figure times (the paper's where the run reaches them; the key gives both units).
std::string fig_collapse(const CaseResult& c, const Out& out, const std::string& base, int fig) {
  const Table d = read_csv(out.dir / "ensembles" / c.plan->name / "distributions_mean.csv");
  Table t;
  for (const char* n : {"t", "t_paper", "x_R", "f1", "f1_sem", "x_v", "f2", "f2_sem"})
    t.add_column(n, {});
  const auto& p = c.plan->spec.physics;
  const double a = 1.0 / (p.dim + 1);
  for (std::size_t i = 0; i < d.rows(); ++i) {
    const double tp = p.paper_time(d.column("t")[i]);
    const double sr = std::pow(tp, a), sv = std::pow(tp, 1 - a);
    const std::vector<double> row = {d.column("t")[i],          tp,
                                     d.column("R")[i] / sr,     d.column("P_R")[i] * sr,
                                     d.column("P_R_sem")[i] * sr, d.column("v")[i] * sv,
                                     d.column("P_v")[i] / sv,   d.column("P_v_sem")[i] / sv};
    t.add_row(row);
  }
  write_csv(t, out.dir / (base + ".csv"));
  std::string pr, pv;
  for (double ts : c.plan->figure_times) {
    const std::string sel = "($1==" + format_double(ts) + " ? ";
    const std::string title = "'t_{paper} = " + format_number(std::round(p.paper_time(ts))) +
                              " (t = " + figure_number(ts, 6) + " d/v_0)'";
    pr += std::string(pr.empty() ? "plot " : ", \\\n     ") + "'" + base + ".csv' skip 1 using " +
          sel + "$3 : 1/0):4:5 with yerrorlines title " + title;
    pv += std::string(pv.empty() ? "plot " : ", \\\n     ") + "'" + base + ".csv' skip 1 using " +
          sel + "$6 : 1/0):($7 > 0 ? $7 : 1/0):8 with yerrorlines title " + title;
  }
  const std::string as = p.dim == 2 ? "1/3" : "1/4";
  const std::string bs = p.dim == 2 ? "2/3" : "3/4";  // 1 - alpha
  std::string gp = gnuplot_preamble(base, 1400, 600);
  gp += "set multiplot layout 1,2 title 'Fig. " + std::to_string(fig) + ": scaling collapse in " +
        std::to_string(p.dim) + "D, r = " + rtext(p.restitution) + ", α = " + as +
        (c.plan->paper_times ? " at the times of the paper" : " at the times of the paper scaled to the run") +
        "; t in paper units 1/(v_0 n^{1/d}), R in diameters, v in v_0; bars: ± standard error'\n";
  // (a): room above the peak for the key (linear y).
  gp += "set title '(a) t^{α} P(R,t) against R t^{-α}'\nset xlabel 'R t^{-" + as +
        "} (t in paper units)'\nset ylabel 't^{" + as +
        "} P(R,t)'\nset key top left\nset offsets 0, 0, graph 0.3, 0\n" +
        filled_xrange(t, "x_R", "f1", 1e-2) + pr + "\n";
  // Log y: the exponential tail down to 1e-4 of the peak, below which a bin holds a few
  // particles of one realisation; the key bottom left, below the rise (the peak is at the top).
  gp += "set title '(b) t^{α-1} P(v,t) against v t^{1-α}'\nset xlabel 'v t^{" + bs +
        "} (t in paper units)'\nset ylabel 't^{-" + bs +
        "} P(v,t)'\nset offsets 0, 0, 0, 0\nset logscale y\nset format y '10^{%L}'\n"
        "set key bottom left\n" +
        filled_xrange(t, "x_v", "f2", 1e-4) + pv + "\n";
  gp += "unset multiplot\n";
  return out.plot(base + ".gp", gp);
}

// "R_front" -> "R_{front}": a whole subscript in gnuplot's enhanced text.
std::string enhanced(const std::string& q) {
  std::string out;
  for (std::size_t i = 0; i < q.size(); ++i) {
    if (q[i] != '_') {
      out += q[i];
      continue;
    }
    std::size_t j = i + 1;
    while (j < q.size() && std::isalnum(static_cast<unsigned char>(q[j]))) ++j;
    out += "_{" + q.substr(i + 1, j - i - 1) + "}";
    i = j - 1;
  }
  return out;
}

// The local slopes of every fitted quantity of one case with their bootstrap bands, the
// theory's exponent and the plateau fit (fig8_local_slopes_<case>).
std::string fig_local_slopes(const CaseResult& c, const Out& out) {
  const auto& f = c.fits;
  const auto& p = c.plan->spec.physics;
  const std::string base = "fig8_local_slopes_" + c.plan->name;
  Table t;
  t.add_column("t", f.exponents.front().slope.t);
  std::vector<double> tp;
  for (double x : f.exponents.front().slope.t) tp.push_back(p.paper_time(x));
  t.add_column("t_paper", tp);
  for (const auto& e : f.exponents) {
    std::string col = e.column;
    t.add_column(col + "_slope", e.slope.slope);
    t.add_column(col + "_lo", e.slope.lo);
    t.add_column(col + "_hi", e.slope.hi);
  }
  write_csv(t, out.dir / (base + ".csv"));
  // From <N_t> >= 20 on, where the plateau search starts (earlier slopes are a handful of
  // particles' noise).
  const Table ts = c.sums.timeseries();
  double t_start = ts.column("t").back();
  for (std::size_t i = 0; i < ts.rows(); ++i)
    if (ts.column("active")[i] >= 20) {
      t_start = ts.column("t")[i];
      break;
    }
  // Four panels a row: 7 quantities, 10 with the kicked particle's (elastic blasts in a box).
  const int rows = int(f.exponents.size() + 3) / 4;
  std::string gp = gnuplot_preamble(base, 1900, 450 * rows);
  gp += "set xrange [" + format_double(p.paper_time(t_start)) + ":" +
        format_double(p.paper_time(ts.column("t").back())) + "]\n";
  gp +=
      "set multiplot layout " + std::to_string(rows) +
      ",4 title 'Local slopes d ln X / d ln t, d = " + std::to_string(p.dim) +
      ", r = " + rtext(p.restitution) + " (" + std::to_string(c.sums.count()) +
      " realisations; band: 95% bootstrap; dashed: theory; thick: fit on the plateau)'\n"
      "set logscale x\nset format x '10^{%L}'\nset xlabel '" + kPaperTimeLabel + "'\n"
      "set key top right font ',9' samplen 2\nset style fill transparent solid 0.3 "
      "noborder\n";
  for (std::size_t q = 0; q < f.exponents.size(); ++q) {
    const auto& e = f.exponents[q];
    const int col = 3 + 3 * int(q);  // slope column
    const std::string name = enhanced(e.quantity);
    gp += "set title '" + name + "'\nset ylabel 'd ln " + name + " / d ln t'\n";
    const auto [ylo, yhi] = slope_yrange(e);
    gp += std::isfinite(ylo) ? "set yrange [" + format_double(ylo) + ":" + format_double(yhi) + "]\n"
                             : std::string("set yrange [*:*]\n");
    std::string plot = "plot '" + base + ".csv' skip 1 using 2:" + std::to_string(col + 1) + ":" +
                       std::to_string(col + 2) +
                       " with filledcurves lc rgb '#6090d0' title '95% band', '' skip 1 using 2:" +
                       std::to_string(col) +
                       " with lines lw 2 lc rgb '#2050a0' title 'local slope'";
    if (std::isfinite(e.theory)) {
      char buf[200];
      std::snprintf(buf, sizeof buf, "%.6g", e.theory);
      plot += std::string(", ") + buf + " with lines " + theory_style(p.dim) + " title 'theory " +
              figure_number(e.theory, 3) + "'";
    }
    // The plateau fit is drawn only where a theory is compared (not on C_t of r < 1).
    if (std::isfinite(e.fit.exponent) && std::isfinite(e.theory)) {
      char buf[300];
      std::snprintf(buf, sizeof buf, ", (x >= %.6g && x <= %.6g) ? %.6g : 1/0",
                    p.paper_time(e.fit.window.t_lo), p.paper_time(e.fit.window.t_hi),
                    e.fit.exponent);
      plot += std::string(buf) + " with lines lw 5 lc rgb '#d06000' title 'fit " +
              figure_number(e.fit.exponent, 3) + " [" + figure_number(e.fit.ci_lo, 3) + ", " +
              figure_number(e.fit.ci_hi, 3) + "]'";
    } else if (std::isfinite(e.theory)) {
      gp += "set label 1 'no plateau within the run' at graph 0.04, 0.08 left\n";
    }
    gp += plot + "\nunset label 1\n";
  }
  gp += "unset multiplot\n";
  return out.plot(base + ".gp", gp);
}

// Crossover times (in paper units) against their control parameter with the fitted line, its
// exponent and interval in the key; one set of points per CrossoverSet (a rule in one
// dimension), the sets after the first of each dimension drawn open. A set without a crossover
// found has no key entry. `fit_note` follows each fit's title (what the fit is to the verdict).
struct CrossoverPlot {
  std::string base, title, xlabel, ylabel, name;  // name: φ_1 or φ_2
  std::string fit_note;
};

// The panel's plot command (without "plot") and its functions; the rows go into t.
struct CrossoverPanel {
  std::string plot, functions;
};
CrossoverPanel crossover_panel(const CrossoverPlot& cp, const std::vector<CrossoverSet>& sets,
                               Table& t) {
  CrossoverPanel out;
  for (std::size_t k = 0; k < sets.size(); ++k) {
    const CrossoverSet& set = sets[k];
    const int d = set.d;
    const std::size_t rows = t.rows();
    for (const auto& p : set.points) {
      if (!p.crossover.found) continue;
      std::vector<double> ok;
      for (double x : p.draws)
        if (std::isfinite(x)) ok.push_back(x * set.to_paper);
      std::sort(ok.begin(), ok.end());
      const double nan = std::numeric_limits<double>::quiet_NaN();
      const double lo = ok.size() >= 10 ? sorted_quantile(ok, 0.025) : nan;
      const double hi = ok.size() >= 10 ? sorted_quantile(ok, 0.975) : nan;
      const std::vector<double> row = {double(k), double(d), p.control,
                                       p.crossover.time * set.to_paper, lo, hi};
      t.add_row(row);
    }
    if (t.rows() == rows) continue;  // nothing found: no empty key entry
    const std::string ks = std::to_string(k), ds = std::to_string(d);
    const std::string title = "d = " + ds + (set.rule.empty() ? "" : ", " + set.rule);
    const std::string symbol = set.symbol != 0 ? std::to_string(set.symbol) : set.open ? "6" : "7";
    out.plot += std::string(out.plot.empty() ? "" : ", \\\n     ") + "'" + cp.base +
                ".csv' skip 1 using ($1==" + ks + " ? $3 : 1/0):4:5:6 with yerrorbars pt " +
                symbol + " ps 1.5 lc rgb '" + (d == 2 ? "black" : "#a00000") + "' title '" +
                title + "'";
    const auto& f = set.fit;
    if (std::isfinite(f.fit.phi)) {
      char buf[200];
      std::snprintf(buf, sizeof buf, "T%zu(x) = %.6g*x**(-%.6g)\n", k,
                    f.fit.prefactor * set.to_paper, f.fit.phi);
      out.functions += buf;
      const std::string interval =
          std::isfinite(f.ci_lo)
              ? " [" + figure_number(f.ci_lo, 3) + ", " + figure_number(f.ci_hi, 3) + "]"
              : " ± " + figure_number(f.fit.standard_error, 2);
      const std::string line =
          set.open ? std::string("lw 1 dt 3 lc rgb '") + (d == 2 ? "black" : "#a00000") + "'"
                   : theory_style(d);
      out.plot += ", \\\n     T" + ks + "(x) with lines " + line + " title '" + title + " fit" +
                  cp.fit_note + ": " + cp.name + " = " + figure_number(f.fit.phi, 3) + interval +
                  "'";
    }
  }
  return out;
}

std::string fig_crossover_points(const Out& out, const CrossoverPlot& cp,
                                 const std::vector<CrossoverSet>& sets) {
  Table t;
  for (const char* n : {"set", "d", "control", "t_c", "t_c_lo", "t_c_hi"}) t.add_column(n, {});
  const CrossoverPanel panel = crossover_panel(cp, sets, t);
  write_csv(t, out.dir / (cp.base + ".csv"));
  std::string gp = gnuplot_preamble(cp.base, 900, 650);
  if (t.rows() == 0)
    return out.plot(cp.base + ".gp",
                    gp + no_data_plot(cp.base + ".csv", "no crossover reached in these runs"));
  gp += panel.functions + "set title '" + cp.title + "'\nset logscale xy\nset xlabel '" +
        cp.xlabel + "'\nset ylabel '" + cp.ylabel + "'\nset key below font ',10'\n" + "plot " +
        panel.plot + "\n";
  return out.plot(cp.base + ".gp", gp);
}

// Fig. 6 (b): phi1 between neighbouring r against 1 - r^2 (the pair's geometric mean): the
// E_t/E_0 collapse, whose pair nearest r = 1 is the declared reading the verdict uses
// (phi1_energy_comparison), filled and ringed; the intersection rule's t_c1 ratios open; the
// paper's value as a line. Rows into t: d, kind (0 collapse, 1 intersection rule, 2 the
// declared reading), control, phi, its 95% interval.
std::string phi1_pairs_panel(const std::vector<CrossoverSet>& tc1, const std::string& csv,
                             Table& t) {
  std::string plot, lines;
  for (const CrossoverSet& set : tc1) {
    auto control = [&](const std::string& label) {
      for (const auto& p : set.points)
        if (p.label == label) return p.control;
      return std::numeric_limits<double>::quiet_NaN();
    };
    auto pair_x = [&](const std::string& a, const std::string& b) {
      return std::sqrt(control(a) * control(b));
    };
    const std::string ds = std::to_string(set.d);
    const std::string colour = set.d == 2 ? "black" : "#a00000";
    // One clause per kind that has points: a key entry without one says nothing.
    auto clause = [&](int kind, const std::string& style, const std::string& title) {
      plot += std::string(plot.empty() ? "" : ", \\\n     ") + "'" + csv + "' skip 1 using ($1==" +
              ds + " && $2==" + std::to_string(kind) + " ? $3 : 1/0):" + style + " lc rgb '" +
              colour + "' title '" + title + "'";
    };
    std::size_t rows = t.rows();
    for (const Phi1Reading& e : set.energy)
      if (std::isnan(e.level) && std::isfinite(e.phi)) {
        const std::vector<double> row = {double(set.d), 0, pair_x(e.from, e.to), e.phi, e.ci_lo,
                                         e.ci_hi};
        t.add_row(row);
      }
    if (t.rows() > rows)
      clause(0, "4:5:6 with yerrorbars pt 7 ps 1.2", "d = " + ds + ": E_t/E_0 collapse");
    rows = t.rows();
    for (const LocalCrossoverExponent& e : set.local)
      if (std::isfinite(e.phi)) {
        const std::vector<double> row = {double(set.d), 1, pair_x(e.from, e.to), e.phi, e.ci_lo,
                                         e.ci_hi};
        t.add_row(row);
      }
    if (t.rows() > rows)
      clause(1, "4:5:6 with yerrorbars pt 6 ps 1.2",
             "d = " + ds + ": t_{c1} ratio (intersection rule)");
    const Comparison declared =
        phi1_energy_comparison(set.d, set.energy, std::numeric_limits<double>::quiet_NaN());
    if (const Phi1Reading* last =
            nearest_limit_reading(set.energy, std::numeric_limits<double>::quiet_NaN())) {
      const std::vector<double> row = {double(set.d), 2, pair_x(last->from, last->to), last->phi,
                                       last->ci_lo, last->ci_hi};
      t.add_row(row);
      clause(2, "4 with points pt 65 ps 3 lw 2",
             "d = " + ds + ", declared (the verdict): φ_1 = " + figure_number(last->phi, 3) +
                 " [" + figure_number(last->ci_lo, 3) + ", " + figure_number(last->ci_hi, 3) +
                 "], " + last->from + " and " + last->to);
    }
    lines += ", \\\n     " + format_double(declared.theory) + " with lines " +
             theory_style(set.d) + " title 'paper, d = " + ds + ": φ_1 = " +
             figure_number(declared.theory, 3) + "'";
  }
  return plot.empty() ? std::string() : plot + lines;
}

// Fig. 6: (a) t_c1 against 1 - r^2 with the fits over all r (a sensitivity reading), (b) phi1
// between neighbouring r, with the declared reading the report's verdict uses.
std::string fig6(const Out& out, const Crossovers& x) {
  const std::string base = "fig6_crossover", pairs = "fig6_crossover_pairs.csv";
  std::vector<CrossoverSet> sets = x.tc1;
  sets.insert(sets.end(), x.tc1_theory_b.begin(), x.tc1_theory_b.end());
  const CrossoverPlot cp{base, "", "", "", "φ_1", " over all r (sensitivity)"};
  Table t, p;
  for (const char* n : {"set", "d", "control", "t_c", "t_c_lo", "t_c_hi"}) t.add_column(n, {});
  for (const char* n : {"d", "kind", "control", "phi1", "phi1_lo", "phi1_hi"}) p.add_column(n, {});
  const CrossoverPanel a = crossover_panel(cp, sets, t);
  const std::string b = phi1_pairs_panel(x.tc1, pairs, p);
  write_csv(t, out.dir / (base + ".csv"));
  write_csv(p, out.dir / pairs);
  std::string gp = gnuplot_preamble(base, 1500, 700);
  gp += a.functions +
        "set multiplot layout 1,2 title 'Fig. 6: the crossover t_{c1} ∝ (1 - r^2)^{-φ_1} "
        "(paper: φ_1 = 2.25 in 2D, 3.0 in 3D)'\n"
        "set logscale x\nset xlabel '1 - r^2'\nset key below font ',9'\n";
  gp += "set title '(a) t_{c1} by the intersection rule'\nset logscale y\nset ylabel 't_{c1} (" +
        std::string(kPaperTimeLabel).substr(3) + "'\n" +
        (a.plot.empty() ? "set label 1 'no t_{c1} found in these runs' at graph 0.5, 0.5 center\n"
                          "plot [0.1:1][1:10] -1 notitle\nunset label 1\n"
                        : "plot " + a.plot + "\n");
  gp += "set title '(b) φ_1 between neighbouring r'\nunset logscale y\nset ylabel 'φ_1'\n" +
        (b.empty() ? std::string("set label 1 'no pair of r gives φ_1' at graph 0.5, 0.5 center\n"
                                 "plot [0.1:1][0:5] -1 notitle\n")
                   : "plot " + b + "\n");
  gp += "unset multiplot\n";
  return out.plot(base + ".gp", gp);
}

// fig12: the paper's "faster particles are in the inside edge" as numbers against r: the mean
// speed of the active particles inside their median distance from the centre of mass over that
// of those outside it, at the last snapshot, +- its standard error over realisations (the
// report's table "The inner edge's speed"); > 1 is faster inside.
std::string fig_inner_edge(const std::vector<CaseResult>& all, const Out& out) {
  const std::string base = "fig12_inner_edge";
  Table t;
  for (const char* n : {"d", "r", "ratio", "ratio_sem"}) t.add_column(n, {});
  for (int d : {2, 3})
    for (bool elastic : {false, true})
      for (const CaseResult* c : cases_of(all, d, elastic)) {
        if (c->sums.count() == 0) continue;
        const std::vector<double> row = {double(d), c->plan->spec.physics.restitution,
                                         c->fits.last_scalar("inner_outer_ratio"),
                                         c->fits.last_scalar_sem("inner_outer_ratio")};
        if (std::isfinite(row[2])) t.add_row(row);
      }
  write_csv(t, out.dir / (base + ".csv"));
  std::string gp = gnuplot_preamble(base, 900, 600);
  if (t.rows() == 0)
    return out.plot(base + ".gp", gp + no_data_plot(base + ".csv", "no band at the last snapshot"));
  gp += "set title 'Fig. 12: inner over outer mean speed of the band, last snapshot (paper: faster inside)'\n"
        "set xlabel 'coefficient of restitution r'\nset ylabel '⟨|v|⟩ inside / ⟨|v|⟩ outside "
        "the median R'\nset xrange [0:1.05]\nset key top right\nset offsets 0, 0, graph 0.1, "
        "graph 0.05\n"
        "plot 1 with lines lw 1 dt 2 lc rgb 'gray40' title 'equal speeds', '" +
        base + ".csv' skip 1 using ($1==2 ? $2 : 1/0):3:4 with yerrorlines pt 7 lc rgb 'black' "
        "title 'd = 2 (± standard error)', '' skip 1 using ($1==3 ? $2 : 1/0):3:4 with "
        "yerrorlines pt 5 lc rgb '#a00000' title 'd = 3 (± standard error)'\n";
  return out.plot(base + ".gp", gp);
}

// The snowplow question in 3D (fig11_snowplow_3d): the local slopes of R_t, N_t, E_t and P_r
// of every 3D r < 1 case against the two pictures' exponents, alpha = 1/4 (momentum-conserving
// snowplow, dashed) and 2/7 (pressure-driven, dotted), and in P_r's panel the slope of the
// shell's momentum N_t dR_t/dt (analysis/snowplow.h); one CSV per case beside the script.
std::string fig_snowplow(const std::vector<CaseResult>& all, const Out& out) {
  const std::string base = "fig11_snowplow_3d";
  const Quantity panels[] = {Quantity::RadiusRms, Quantity::ActiveCount, Quantity::Energy,
                             Quantity::RadialMomentum};
  std::vector<const CaseResult*> cases;
  for (const auto& c : all)
    if (c.plan->spec.physics.dim == 3 && !c.plan->spec.physics.elastic() && !c.plan->delta_scan)
      cases.push_back(&c);
  // From <N_t> >= 20 on, as the plateau search (earlier slopes are a handful of particles').
  double t_start = std::numeric_limits<double>::infinity();
  for (const CaseResult* c : cases) {
    const Table ts = c->sums.timeseries();
    for (std::size_t i = 0; i < ts.rows(); ++i)
      if (ts.column("active")[i] >= 20) {
        t_start = std::min(t_start, c->plan->spec.physics.paper_time(ts.column("t")[i]));
        break;
      }
  }
  std::string gp = gnuplot_preamble(base, 1400, 1000);
  if (std::isfinite(t_start)) gp += "set xrange [" + format_double(t_start) + ":*]\n";
  gp += "set multiplot layout 2,2 title 'Local slopes in 3D against the momentum-conserving "
        "(alpha = 1/4, dashed) and pressure-driven (alpha = 2/7, dotted) snowplows'\n"
        "set logscale x\nset format x '10^{%L}'\nset xlabel '" + std::string(kPaperTimeLabel) + "'\n"
        "set key top right font ',8' samplen 2\n";
  for (std::size_t q = 0; q < std::size(panels); ++q) {
    const std::string name = quantity_name(panels[q]);
    const std::string title =
        panels[q] == Quantity::RadialMomentum
            ? name + " (solid) and the shell momentum N_t dR_t/dt (dash-dot)"
            : name;
    gp += "set title '" + title + "'\nset ylabel 'd ln " + name + " / d ln t'\n";
    std::string plot;
    for (std::size_t k = 0; k < cases.size(); ++k) {
      const CaseResult* c = cases[k];
      const ExponentFit* e = find_exponent(c->fits, panels[q]);
      if (!e) continue;
      const std::string csv = base + "_" + c->plan->name + ".csv";
      // A case's lines alike, and apart from every other case's: gnuplot's own cycle of 8
      // gave 3D r = 0.1 and the ninth case, r = 0.5 of --snowplow, one colour.
      static constexpr const char* kColours[] = {"#9400d3", "#009e73", "#56b4e9", "#e69f00",
                                                 "#f0e442", "#0072b2", "#e51e10", "#000000",
                                                 "#a0522d", "#ff69b4", "#808080", "#6b8e23"};
      const std::string colour = std::string(" lc rgb '") + kColours[k % std::size(kColours)] + "'";
      if (q == 0) {
        Table t;
        std::vector<double> tp;
        for (double x : e->slope.t) tp.push_back(c->plan->spec.physics.paper_time(x));
        t.add_column("t_paper", tp);
        for (Quantity p : panels) t.add_column(quantity_name(p), find_exponent(c->fits, p)->slope.slope);
        std::vector<double> shell;  // x_N + x_R - 1
        for (std::size_t i = 0; i < tp.size(); ++i)
          shell.push_back(t.column("N_t")[i] + t.column("R_t")[i] - 1);
        t.add_column("shell_momentum", shell);
        write_csv(t, out.dir / csv);
      }
      plot += std::string(plot.empty() ? "plot " : ", ") + "'" + csv +
              "' skip 1 using 1:" + std::to_string(q + 2) + " with lines lw 2" + colour +
              " title '" + c->plan->name + "' noenhanced";
      if (panels[q] == Quantity::RadialMomentum)
        plot += ", '" + csv + "' skip 1 using 1:6 with lines lw 1 dt 4" + colour + " notitle";
    }
    char lines[200];
    std::snprintf(lines, sizeof lines,
                  "%s%.6g with lines lw 2 dt 2 lc rgb 'black' title '1/4', %.6g with lines lw 2 "
                  "dt 3 lc rgb '#a00000' title '2/7'",
                  plot.empty() ? "plot [1:10] " : ", ",
                  exponent_from_alpha(panels[q], 3, momentum_conserving_alpha(3)),
                  exponent_from_alpha(panels[q], 3, pressure_driven_alpha(3)));
    gp += plot + lines + "\n";
  }
  gp += "unset multiplot\n";
  return out.plot(base + ".gp", gp);
}

// fig9: the active-weighted distribution of cell packing fractions in 2D at the last snapshot,
// beside the paper's 0.78-0.82 (r < 1) and ~0.47 (r = 1) and the edge-free measures.
std::string fig_packing(const std::vector<CaseResult>& all, const Out& out) {
  Table t;
  for (const char* n : {"r", "packing", "P"}) t.add_column(n, {});
  std::string plot;
  for (bool elastic : {false, true})
    for (const CaseResult* c : cases_of(all, 2, elastic)) {
      const double r = c->plan->spec.physics.restitution;
      if (c->sums.snapshots().empty() || c->sums.count() == 0) continue;
      const Histogram h = c->sums.snapshots().back().packing.mean();
      for (std::size_t b = 0; b < h.bins(); ++b) {
        const std::vector<double> row = {r, h.centre(b), h.values[b]};
        t.add_row(row);
      }
      plot += std::string(plot.empty() ? "plot " : ", \\\n     ") +
              "'fig9_packing.csv' skip 1 using ($1==" + rtext(r) +
              " ? $2 : 1/0):3 with steps lw 2 title sprintf('r = " + rtext(r) +
              ": Voronoi median %.2f, local 90%% %.2f, densest cell %.2f', " +
              format_double(c->fits.last_scalar("packing_voronoi_median")) + ", " +
              format_double(c->fits.last_scalar("packing_local_upper")) + ", " +
              format_double(c->fits.last_scalar("packing_densest_cell")) + ")";
    }
  write_csv(t, out.dir / "fig9_packing.csv");
  std::string gp = gnuplot_preamble("fig9_packing", 1000, 650);
  if (t.rows() == 0)
    return out.plot("fig9_packing.gp", gp + no_data_plot("fig9_packing.csv", "no band cells"));
  gp +=
      "set title 'Packing fraction of cells of side 10 holding band particles, weighted by "
      "their active particles (2D, last snapshot)'\n"
      "set xlabel 'cell packing fraction φ'\nset ylabel 'active-weighted density'\n"
      // The key below the panel and a free strip above the data for the paper's labels: inside,
      // the key covered the r = 0.7-0.9 peaks and the two labels overlapped.
      "set xrange [0:1]\nset yrange [0:*]\nset offsets 0, 0, graph 0.14, 0\n"
      "set key below maxrows 4 font ',10'\nset bmargin 8\n"
      "set object 1 rect from 0.78, graph 0 to 0.82, graph 1 fc rgb '#c0c0c0' fs solid 0.4 "
      "noborder behind\n"
      "set arrow 1 from 0.47, graph 0 to 0.47, graph 1 nohead dt 2 lw 2 lc rgb 'black'\n"
      "set label 2 'paper r < 1: 0.78-0.82' at 0.80, graph 0.96 center\n"
      "set label 3 'paper r = 1: about 0.47' at 0.46, graph 0.96 right\n" +
      plot + "\n";
  return out.plot("fig9_packing.gp", gp);
}

}  // namespace

std::pair<double, double> slope_yrange(const ExponentFit& e) {
  const SlopeBand& s = e.slope;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  if (s.t.empty()) return {nan, nan};
  double t_lo = s.t.back() / 10;
  if (std::isfinite(e.fit.exponent)) t_lo = std::min(t_lo, e.fit.window.t_lo);
  std::vector<double> slope, half;
  for (std::size_t i = 0; i < s.t.size(); ++i) {
    if (s.t[i] < t_lo || !std::isfinite(s.slope[i])) continue;
    slope.push_back(s.slope[i]);
    if (std::isfinite(s.lo[i]) && std::isfinite(s.hi[i])) half.push_back(0.5 * (s.hi[i] - s.lo[i]));
  }
  if (slope.empty()) return {nan, nan};
  std::sort(slope.begin(), slope.end());
  double lo = sorted_quantile(slope, 0.05), hi = sorted_quantile(slope, 0.95);
  for (double x : {e.theory, e.fit.exponent})
    if (std::isfinite(x)) {
      lo = std::min(lo, x);
      hi = std::max(hi, x);
    }
  std::sort(half.begin(), half.end());
  const double band = half.empty() ? 0 : sorted_quantile(half, 0.5);
  // The band pads the range up to half a unit of exponent: wider (one particle's slope, as the
  // kicked particle's) it is drawn cut by the panel's edges rather than squash the slope flat.
  const double pad = std::max({0.3 * (hi - lo), 0.03, std::min(band, 0.5)});
  return {lo - pad, hi + 1.5 * pad};  // room above for the key
}

Fig1Snapshots run_fig1(const FiguresPlan::Fig1& f) {
  Fig1Snapshots out;
  auto sim = make_simulation(f.a);
  for (double t : f.a_times) {
    sim->run_until(t);
    throw_if_stopped();  // run_until returns early on a stop: the snapshot would be early
    out.a.push_back(sim->snapshot());
  }
  sim = make_simulation(f.b);
  sim->run_until(f.b.t_max);
  throw_if_stopped();
  out.b = sim->snapshot();
  return out;
}

std::string figure_number(double x, int digits) {
  if (!std::isfinite(x)) return "n/a";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*g", digits, x);
  return buf;
}

std::string slope_figure_of(const FigureCase& c) {
  return "fig8_local_slopes_" + c.name + ".png";
}

namespace {

CrossoverSet crossover_set(int d, std::string rule, bool open = false, int symbol = 0) {
  CrossoverSet s;
  s.d = d;
  s.rule = std::move(rule);
  s.open = open;
  s.symbol = symbol;
  return s;
}

}  // namespace

Crossovers crossovers_of(const std::vector<CaseResult>& results) {
  Crossovers x;
  for (int d : {2, 3}) {
    CrossoverSet energy = crossover_set(d, "intersection rule (E_t)");
    CrossoverSet theory_b = crossover_set(d, "intersection rule, b = theory", true);
    std::vector<EnergyCurves> curves;
    for (const CaseResult* c : phi1_cases(results, d)) {
      const double r = c->plan->spec.physics.restitution;
      energy.to_paper = theory_b.to_paper = c->plan->spec.physics.paper_time(1.0);
      EnergyCurves ec;
      ec.control = 1 - r * r;
      ec.label = "r = " + rtext(r);
      ec.t = c->sums.timeseries().column("t");
      for (const auto& [k, cv] : c->sums.curves()) ec.realisations.push_back(cv[1]);  // energy
      ec.e0 = 0.5 * c->plan->spec.physics.speed * c->plan->spec.physics.speed;
      if (!ec.realisations.empty()) curves.push_back(std::move(ec));
      energy.points.push_back({1 - r * r, "r = " + rtext(r), c->fits.tc1, c->fits.tc1_draws});
      theory_b.points.push_back(
          {1 - r * r, "r = " + rtext(r), c->fits.tc1_theory_b, c->fits.tc1_theory_b_draws});
    }
    energy.fit = fit_crossover_points(energy.points);
    energy.local = local_crossover_exponents(energy.points);
    Phi1Options po;
    po.seed = 1 + std::uint64_t(d);
    energy.energy = phi1_readings(curves, po);
    theory_b.fit = fit_crossover_points(theory_b.points);
    x.tc1.push_back(std::move(energy));
    x.tc1_theory_b.push_back(std::move(theory_b));
    // Open circle, square, triangle for E_0/2, /10, /100.
    const int symbols[] = {6, 4, 8};
    for (std::size_t k = 0; k < po.levels.size(); ++k) {
      const double f = po.levels[k];
      CrossoverSet at =
          crossover_set(d, "time to E_0 x " + figure_number(f, 3), true, symbols[k % 3]);
      at.to_paper = energy.to_paper;
      for (const EnergyCurves& ec : curves) {
        FractionTime ft = time_to_fraction(ec, f, po);
        at.points.push_back(
            {ec.control, ec.label, {ft.t, std::isfinite(ft.t), ""}, std::move(ft.draws)});
      }
      x.fractions.push_back(std::move(at));
    }
  }
  CrossoverSet scan = crossover_set(2, "");
  for (const auto& c : results) {
    if (!c.plan->delta_scan) continue;
    const double delta = c.plan->spec.physics.cutoff;
    scan.to_paper = c.plan->spec.physics.paper_time(1.0);
    scan.points.push_back({delta, "delta = " + figure_number(delta), c.fits.tc2, c.fits.tc2_draws});
  }
  scan.fit = fit_crossover_points(scan.points);
  x.tc2.push_back(std::move(scan));
  return x;
}

std::vector<std::string> write_figures(const FiguresPlan& plan,
                                       const std::vector<CaseResult>& results,
                                       const Crossovers& crossovers, const fs::path& dir,
                                       const std::vector<std::string>& formats) {
  const Out out{dir, formats};
  std::vector<std::string> problems;
  auto check = [&](std::string e) {
    if (!e.empty()) problems.push_back(std::move(e));
  };
  check(render_fig1(run_fig1(plan.fig1), dir));
  check(fig2(results, out));
  check(fig3(results, out));
  for (const auto& c : results) {
    const auto& p = c.plan->spec.physics;
    if (c.plan->collapse)
      check(fig_collapse(c, out, p.dim == 2 ? "fig4_collapse_2d" : "fig5_collapse_3d",
                         p.dim == 2 ? 4 : 5));
    if (!c.plan->delta_scan) check(fig_local_slopes(c, out));
  }
  check(fig_packing(results, out));
  check(fig_inner_edge(results, out));
  check(fig_snowplow(results, out));
  check(fig6(out, crossovers));
  check(fig_crossover_points(out,
                             {"fig10_energy_fraction_times",
                              "Time for <E_t> to reach E_0/2, E_0/10, E_0/100 against 1 - r^2 "
                              "(level readings of φ_1)",
                              "1 - r^2", kPaperTimeLabel, "φ_1", ""},
                             crossovers.fractions));
  check(fig_crossover_points(
      out,
      {"fig7_tc2_delta",
       "Crossover time t_{c2} against the cutoff δ (2D, r = 0.1; paper: φ_2 = 3/2)", "δ",
       std::string("t_{c2} (") + (kPaperTimeLabel + 3), "φ_2", ""},
      crossovers.tc2));
  return problems;
}

}  // namespace gs::jobs
