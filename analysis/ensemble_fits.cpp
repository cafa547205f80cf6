#include "analysis/ensemble_fits.h"

#include <algorithm>
#include <cmath>

#include "analysis/collapse.h"
#include "sim/error.h"
#include "sim/format.h"

namespace gs {
namespace {

constexpr double kStartActive = 20;  // local slopes are searched for plateaus once <N_t> >= 20

std::vector<std::vector<double>> curves_of(const EnsembleSums& sums, std::size_t q) {
  std::vector<std::vector<double>> out;
  for (const auto& [k, c] : sums.curves()) out.push_back(c[q]);
  return out;
}

// dR/dt by central differences on the grid; NaN at the ends.
std::vector<double> derivative(std::span<const double> t, std::span<const double> y) {
  std::vector<double> d(t.size(), std::numeric_limits<double>::quiet_NaN());
  for (std::size_t i = 1; i + 1 < t.size(); ++i)
    d[i] = (y[i + 1] - y[i - 1]) / (t[i + 1] - t[i - 1]);
  return d;
}

std::string window_text(const Window& w) {
  return "[" + format_number(w.t_lo) + ", " + format_number(w.t_hi) + "]";
}

void implied_alpha(ExponentFit& e, int d, double half) {
  e.alpha = alpha_from_exponent(e.quantity, d, e.fit.exponent);
  // The maps are affine: the half width scales by their slope.
  e.alpha_uncertainty =
      half * (alpha_from_exponent(e.quantity, d, 1) - alpha_from_exponent(e.quantity, d, 0));
}

}  // namespace

double alpha_from_exponent(const std::string& quantity, int d, double x) {
  if (quantity == "N_t") return x / d;
  if (quantity == "E_t") return (x + 2) / (d + 2);
  if (quantity == "R_t" || quantity == "R_front") return x;
  if (quantity == "dR_front/dt") return x + 1;
  return std::numeric_limits<double>::quiet_NaN();
}

void check_window(const EnsembleSpec& spec, const Window& w) {
  const auto t = sample_times(spec);
  if (!(w.t_lo > 0 && w.t_hi > w.t_lo))
    throw UsageError("--window " + format_number(w.t_lo) + "," + format_number(w.t_hi) +
                     ": need 0 < T1 < T2");
  if (w.t_lo < t.front() || w.t_hi > t.back())
    throw UsageError("--window " + format_number(w.t_lo) + "," + format_number(w.t_hi) +
                     " lies outside the data [" + format_number(t.front()) + ", " +
                     format_number(t.back()) + "]");
}

double EnsembleFits::last_scalar(const char* name) const {
  for (std::size_t k = 0; k < kSnapshotScalars.size(); ++k)
    if (std::string(kSnapshotScalars[k]) == name && k < last_scalars.size()) return last_scalars[k];
  return std::numeric_limits<double>::quiet_NaN();
}

double EnsembleFits::last_scalar_sem(const char* name) const {
  for (std::size_t k = 0; k < kSnapshotScalars.size(); ++k)
    if (std::string(kSnapshotScalars[k]) == name && k < last_scalars_sem.size())
      return last_scalars_sem[k];
  return std::numeric_limits<double>::quiet_NaN();
}

const ExponentFit* find_exponent(const EnsembleFits& f, const std::string& quantity) {
  for (const auto& e : f.exponents)
    if (e.quantity == quantity) return &e;
  return nullptr;
}

EnsembleFits fit_ensemble(const EnsembleSums& sums, const FitOptions& o) {
  const EnsembleSpec& spec = sums.spec();
  const int d = spec.physics.dim;
  const bool elastic = spec.physics.restitution >= 1;
  const double a = theory_alpha(spec.physics);
  EnsembleFits f;
  f.alpha_theory = a;
  const Table ts = sums.timeseries();
  const auto& t = ts.column("t");

  double t_start = t.back();
  for (std::size_t i = 0; i < t.size(); ++i)
    if (ts.column("active")[i] >= kStartActive) {
      t_start = t[i];
      break;
    }

  struct Quantity {
    const char* quantity;
    int curve;  // index into kCurveColumns; -1: front speed
    double theory;
    const char* source;
  };
  const char* rule =
      elastic ? "scaling theory, alpha = 2/(d+2)" : "scaling theory, alpha = 1/(d+1)";
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::vector<Quantity> quantities = {
      {"N_t", 0, a * d, rule},
      {"E_t", 1, a * d + 2 * a - 2, elastic ? "energy conservation" : rule},
      {"R_t", 2, a, rule},
      {"R_front", 5, a, rule},
      {"dR_front/dt", -1, a - 1, rule},
      {"C_t", 4, elastic ? 2.0 * (d + 1) / (d + 2) : nan,
       elastic ? "Antal, Krapivsky, Redner 2008: collisions ~ t^(2(d+1)/(d+2))" : ""}};

  for (std::size_t q = 0; q < quantities.size(); ++q) {
    const auto& qu = quantities[q];
    ExponentFit e;
    e.quantity = qu.quantity;
    e.column = qu.curve >= 0 ? kCurveColumns[std::size_t(qu.curve)] : "front_speed";
    e.theory = qu.theory;
    e.theory_source = qu.source;
    std::vector<std::vector<double>> curves;
    if (qu.curve >= 0) {
      curves = curves_of(sums, std::size_t(qu.curve));
    } else {
      for (const auto& c : curves_of(sums, 5)) curves.push_back(derivative(t, c));
    }
    SlopeBandOptions so;
    so.resamples = o.band_resamples;
    so.seed = spec.physics.seed;
    so.key = 100 + q;
    e.slope = local_slope_band(t, curves, so);
    PlateauOptions po = o.plateau;
    po.t_min = std::max(po.t_min, t_start);
    e.corrected = corrected_exponent(e.slope, std::max(t_start, t.back() / 100), t.back());
    Window w;
    if (o.window) {
      PlateauOptions inside = po;
      inside.t_min = std::max(po.t_min, o.window->t_lo);
      inside.t_max = std::min(po.t_max, o.window->t_hi);
      e.plateau = find_plateau(e.slope, inside);
      if (!e.plateau.found) {
        const Plateau anywhere = find_plateau(e.slope, po);
        throw UserError(
            "--window " + format_number(o.window->t_lo) + "," + format_number(o.window->t_hi) +
            ": the local slope of " + e.quantity + " has no plateau inside it; " +
            (anywhere.found ? "it plateaus over " + window_text(anywhere.window) : anywhere.note));
      }
      w = *o.window;
    } else {
      e.plateau = find_plateau(e.slope, po);
      if (!e.plateau.found) {
        e.note = e.plateau.note;
        implied_alpha(e, d, nan);
        f.exponents.push_back(std::move(e));
        continue;
      }
      w = e.plateau.window;
    }
    try {
      if (curves.size() >= 2) {
        BootstrapOptions bo;
        bo.resamples = o.resamples;
        bo.seed = spec.physics.seed;
        bo.key = q + 1;
        e.fit = fit_power_law_bootstrap(t, curves, w, bo);
      } else {
        e.fit = fit_power_law(t, curves.front(), w);
      }
    } catch (const UserError& err) {
      if (o.window) throw;  // a window the user gave must fit
      e.note = err.what();
    }
    const double half =
        e.fit.confidence > 0 ? 0.5 * (e.fit.ci_hi - e.fit.ci_lo) : e.fit.standard_error;
    implied_alpha(e, d, half);
    f.exponents.push_back(std::move(e));
  }

  // v_rms^2 = 2 E / N per realisation (unit masses; the particles at rest carry no energy).
  {
    double worst = 0;
    bool any = false;
    for (const auto& [k, c] : sums.curves())
      for (std::size_t i = 0; i < t.size(); ++i)
        if (c[0][i] >= kStartActive && c[1][i] > 0) {
          worst = std::max(worst, std::fabs(c[3][i] * c[3][i] * c[0][i] / (2 * c[1][i]) - 1));
          any = true;
        }
    if (any) f.speed_identity_error = worst;
  }

  SlopeCrossoverOptions co;
  co.target = a * d;
  co.t_lo = t_start;
  const auto& n = ts.column("active");
  const CrossoverPair tc = crossover_pair(t, n, co);
  f.tc1_slope = tc.enter;
  f.tc2 = tc.leave;
  // The same rules on resampled ensembles (realisations drawn with replacement).
  {
    const CrossoverDraws draws =
        crossover_draws(t, curves_of(sums, 0), co, o.band_resamples, spec.physics.seed, 200);
    f.tc1_slope_draws = draws.enter;
    f.tc2_draws = draws.leave;
  }
  if (elastic) {
    f.tc1.note = "r = 1 has no inelastic regime";
  } else {
    // The kick's energy (unit masses), all the blast has before its first collision.
    const double e0 = 0.5 * spec.physics.speed * spec.physics.speed;
    const ExponentFit* energy = find_exponent(f, "E_t");
    GS_CHECK(energy != nullptr);
    f.tc1 = crossover_energy(energy->fit, e0, t.back(), energy->note);
    if (f.tc1.found) {
      const Window& w = energy->fit.window;
      const auto energies = curves_of(sums, 1);
      f.tc1_draws =
          crossover_energy_draws(t, energies, w, e0, o.band_resamples, spec.physics.seed, 201);
      // The same plateau window with E_t's exponent fixed at the theory's.
      f.tc1_theory_b = crossover_energy(
          fit_power_law_fixed(t, ts.column("energy"), w, energy->theory), e0, t.back(), "");
      if (f.tc1_theory_b.found)
        f.tc1_theory_b_draws = crossover_energy_draws(t, energies, w, e0, o.band_resamples,
                                                      spec.physics.seed, 202, energy->theory);
    } else {
      // No settled plateau for the fitted law: none for this reading either, for that reason.
      f.tc1_theory_b.note = f.tc1.note;
    }
  }

  const auto& an = ts.column("anisotropy");
  const auto& an_sem = ts.column("anisotropy_sem");
  f.anisotropy = an.back();
  f.anisotropy_sem = an_sem.back();
  {
    // Weighted least squares of ln A on ln t over the last half decade.
    double sw = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
    std::size_t used = 0, first = t.size();
    for (std::size_t i = t.size(); i-- > 0;) {
      if (!(t[i] > 0) || std::log10(t.back() / t[i]) > 0.5) break;
      if (!(an[i] > 0) || !(an_sem[i] > 0)) continue;
      const double x = std::log(t[i]), y = std::log(an[i]);
      const double w = (an[i] / an_sem[i]) * (an[i] / an_sem[i]);
      sw += w;
      sx += w * x;
      sy += w * y;
      sxx += w * x * x;
      sxy += w * x * y;
      ++used;
      first = i;
    }
    const double det = sw * sxx - sx * sx;
    if (used >= 3 && det > 0) {
      f.anisotropy_slope = (sw * sxy - sx * sy) / det;
      f.anisotropy_slope_error = std::sqrt(sw / det);
      f.anisotropy_window = {t[first], t.back()};
    }
  }

  const auto& snaps = sums.snapshots();
  if (!snaps.empty() && sums.count() > 0) {
    f.last_scalars = snaps.back().scalars.mean();
    f.last_scalars_sem = snaps.back().scalars.standard_error();
    f.packing_typical = f.last_scalar("packing_typical");
    f.packing_typical_sem = f.last_scalar_sem("packing_typical");
    f.packing_upper = f.last_scalar("packing_upper");
    f.packing_upper_sem = f.last_scalar_sem("packing_upper");
    f.inner_outer_ratio = f.last_scalar("inner_outer_ratio");
    f.inner_outer_ratio_sem = f.last_scalar_sem("inner_outer_ratio");
  }
  if (snaps.size() >= 2 && sums.count() > 0) {
    std::vector<Curve> cr, cv;
    for (const auto& s : snaps) {
      cr.push_back(curve_of(scaled_radial_distribution(s.radius.mean(), s.t, a)));
      cv.push_back(curve_of(scaled_speed_distribution(s.speed.mean(), s.t, a)));
    }
    try {
      f.collapse_radius = collapse_quality(cr);
      f.collapse_speed = collapse_quality(cv);
    } catch (const UserError& err) {
      f.collapse_note = err.what();
    }
    std::vector<CollapseSnapshot> sr, sv;
    for (const auto& s : snaps) {
      sr.push_back({s.t, s.radius.mean(), s.radius.standard_error()});
      sv.push_back({s.t, s.speed.mean(), s.speed.standard_error()});
    }
    CollapseScanOptions cs;
    cs.resamples = o.band_resamples;
    cs.seed = spec.physics.seed;
    cs.key = 300;
    f.collapse_alpha_radius = best_collapse_alpha(sr, CollapseVariable::Radius, cs);
    cs.key = 301;
    f.collapse_alpha_speed = best_collapse_alpha(sv, CollapseVariable::Speed, cs);
  } else {
    f.collapse_note = "needs at least two snapshot times";
  }
  return f;
}

}  // namespace gs
