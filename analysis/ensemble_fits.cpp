#include "analysis/ensemble_fits.h"

#include <cmath>

#include "analysis/collapse.h"
#include "sim/error.h"
#include "sim/format.h"

namespace gs {
namespace {

constexpr double kStartActive = 20;   // automatic windows start once <N_t> reaches this
constexpr double kLateDecades = 1.5;  // automatic windows lie within the last 1.5 decades

}  // namespace

void check_window(const EnsembleSpec& spec, const Window& w) {
  const auto t = sample_times(spec);
  if (!(w.t_lo > 0 && w.t_hi > w.t_lo))
    throw UserError("--window " + format_number(w.t_lo) + "," + format_number(w.t_hi) +
                    ": need 0 < T1 < T2");
  if (w.t_lo < t.front() || w.t_hi > t.back())
    throw UserError("--window " + format_number(w.t_lo) + "," + format_number(w.t_hi) +
                    " lies outside the data [" + format_number(t.front()) + ", " +
                    format_number(t.back()) + "]");
}

EnsembleFits fit_ensemble(const EnsembleSums& sums, const FitOptions& o) {
  const EnsembleSpec& spec = sums.spec();
  const int d = spec.physics.dim;
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

  const std::array<double, 4> theory = {a * d, a * d + 2 * a - 2, a, a - 1};
  const std::array<const char*, 4> names = {"N_t", "E_t", "R_t", "v_t"};
  for (std::size_t q = 0; q < kFittedColumns.size(); ++q) {
    ExponentFit e;
    e.column = kFittedColumns[q];
    e.quantity = names[q];
    e.theory = theory[q];
    const auto& y = ts.column(e.column);
    try {
      Window w;
      if (o.window) {
        w = *o.window;
      } else {
        // The asymptotic regime is the late one: the search is confined to the last
        // kLateDecades, so that a transient plateau (e.g. N_t ~ t^1 before the band forms in 3D)
        // cannot win by being long. No plateau there: the last decade, said so in the note.
        AutoWindowOptions ao;
        ao.t_min = std::max(t_start, t.back() * std::pow(10.0, -kLateDecades));
        try {
          w = auto_window(t, y, ao);
        } catch (const UserError&) {
          w = {std::max(t_start, t.back() / 10), t.back()};
          e.note =
              "the local slope drifts by more than +-0.05 over the last 1.5 decades; fit over "
              "the last decade";
        }
      }
      if (sums.count() >= 2) {
        std::vector<std::vector<double>> curves;
        for (const auto& [k, c] : sums.curves()) curves.push_back(c[q]);
        BootstrapOptions bo;
        bo.resamples = o.resamples;
        bo.seed = spec.physics.seed;
        bo.key = q + 1;
        e.fit = fit_power_law_bootstrap(t, curves, w, bo);
      } else {
        e.fit = fit_power_law(t, y, w);
      }
    } catch (const UserError& err) {
      if (o.window) throw;  // a window the user gave must fit
      e.note = err.what();
    }
    const double x = e.fit.exponent;
    const double half =
        e.fit.confidence > 0 ? 0.5 * (e.fit.ci_hi - e.fit.ci_lo) : e.fit.standard_error;
    // alpha from each relation: N ~ t^(alpha d), E ~ t^(alpha (d + 2) - 2), R ~ t^alpha, v ~
    // t^(alpha - 1).
    switch (q) {
      case 0:
        e.alpha = x / d;
        e.alpha_uncertainty = half / d;
        break;
      case 1:
        e.alpha = (x + 2) / (d + 2);
        e.alpha_uncertainty = half / (d + 2);
        break;
      case 2:
        e.alpha = x;
        e.alpha_uncertainty = half;
        break;
      default:
        e.alpha = x + 1;
        e.alpha_uncertainty = half;
        break;
    }
    f.exponents.push_back(e);
  }

  SlopeCrossoverOptions co;
  co.target = a * d;
  co.t_lo = t_start;
  const auto& n = ts.column("active");
  f.tc1 = crossover_enter(t, n, co);
  if (f.tc1.found) {
    co.t_lo = f.tc1.time;
    f.tc2 = crossover_leave(t, n, co);
  } else {
    f.tc2.note = "t_c1 not found";
  }

  const auto& an = ts.column("anisotropy");
  const auto& an_sem = ts.column("anisotropy_sem");
  f.anisotropy = an.back();
  f.anisotropy_sem = an_sem.back();

  const auto& snaps = sums.snapshots();
  if (!snaps.empty() && sums.count() > 0) {
    const auto m = snaps.back().scalars.mean();
    const auto se = snaps.back().scalars.standard_error();
    f.packing_typical = m[0];
    f.packing_typical_sem = se[0];
    f.packing_upper = m[1];
    f.packing_upper_sem = se[1];
    f.inner_outer_ratio = m[4];
    f.inner_outer_ratio_sem = se[4];
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
  } else {
    f.collapse_note = "needs at least two snapshot times";
  }
  return f;
}

}  // namespace gs
