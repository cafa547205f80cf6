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

std::string window_text(const Window& w) {
  std::string s = "[";  // appended: GCC 12 warns falsely (-Wrestrict) on "[" + std::string&&
  return s.append(format_number(w.t_lo)).append(", ").append(format_number(w.t_hi)).append("]");
}

void implied_alpha(ExponentFit& e, int d, double half) {
  e.alpha = alpha_from_exponent(e.kind, d, e.fit.exponent);
  // The maps are affine: the half width scales by their slope.
  e.alpha_uncertainty =
      half * (alpha_from_exponent(e.kind, d, 1) - alpha_from_exponent(e.kind, d, 0));
}

}  // namespace

const char* quantity_name(Quantity q) {
  switch (q) {
    case Quantity::ActiveCount: return "N_t";
    case Quantity::Energy: return "E_t";
    case Quantity::RadiusRms: return "R_t";
    case Quantity::FrontRadius: return "R_front";
    case Quantity::RadialMomentum: return "P_r";
    case Quantity::RadialSpeed: return "P_r/N_t";
    case Quantity::Collisions: return "C_t";
    case Quantity::KickedDisplacement: return "x_kick";
    case Quantity::KickedSpeed: return "v_kick";
    case Quantity::KickedCollisions: return "C_kick";
  }
  return "?";
}

bool is_kicked(Quantity q) {
  return q == Quantity::KickedDisplacement || q == Quantity::KickedSpeed ||
         q == Quantity::KickedCollisions;
}

double impurity_exponent(Quantity q, int d) {
  const double d2 = double(d) * d, radius = 2.0 / (d + 2), den = 8 + 3 * d2;
  switch (q) {
    case Quantity::KickedDisplacement: return radius * (4 + 3 * d2) / den;
    case Quantity::KickedCollisions: return radius * (8 + 2 * d2) / den;
    case Quantity::KickedSpeed: return -d * (8 - 2 * d + 3 * d2) / ((2 + d) * den);
    default: return std::numeric_limits<double>::quiet_NaN();
  }
}

double exponent_from_alpha(Quantity q, int d, double a) {
  switch (q) {
    case Quantity::ActiveCount: return a * d;
    case Quantity::Energy: return a * (d + 2) - 2;
    case Quantity::RadiusRms:
    case Quantity::FrontRadius: return a;
    case Quantity::RadialMomentum: return a * (d + 1) - 1;
    case Quantity::RadialSpeed: return a - 1;
    case Quantity::Collisions:
    case Quantity::KickedDisplacement:
    case Quantity::KickedSpeed:
    case Quantity::KickedCollisions: break;
  }
  return std::numeric_limits<double>::quiet_NaN();
}

double alpha_from_exponent(Quantity q, int d, double x) {
  switch (q) {
    case Quantity::ActiveCount: return x / d;
    case Quantity::Energy: return (x + 2) / (d + 2);
    case Quantity::RadiusRms:
    case Quantity::FrontRadius: return x;
    case Quantity::RadialMomentum: return (x + 1) / (d + 1);
    case Quantity::RadialSpeed: return x + 1;
    case Quantity::Collisions:
    case Quantity::KickedDisplacement:
    case Quantity::KickedSpeed:
    case Quantity::KickedCollisions: break;
  }
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

const ExponentFit* find_exponent(const EnsembleFits& f, Quantity quantity) {
  for (const auto& e : f.exponents)
    if (e.kind == quantity) return &e;
  return nullptr;
}

namespace {

struct QuantityPlan {
  Quantity kind;
  double theory;
  const char* source;
  std::size_t key;  // of the bootstrap streams (kept from before P_r joined)
};

// What is fitted, with the theory's exponent: alpha = 1/(d+1) for r < 1 (momentum-conserving
// snowplow), 2/(d+2) for r = 1; the elastic blast conserves E_t.
std::vector<QuantityPlan> quantities_of(const PhysicsConfig& p, double a) {
  const bool elastic = p.elastic();
  const int d = p.dim;
  const char* rule =
      elastic ? "scaling theory, alpha = 2/(d+2)" : "scaling theory, alpha = 1/(d+1)";
  std::vector<QuantityPlan> out;
  const std::pair<Quantity, std::size_t> keyed[] = {
      {Quantity::ActiveCount, 0}, {Quantity::Energy, 1},         {Quantity::RadiusRms, 2},
      {Quantity::FrontRadius, 3}, {Quantity::RadialMomentum, 6}, {Quantity::RadialSpeed, 4}};
  for (const auto& [q, key] : keyed)
    out.push_back({q, exponent_from_alpha(q, d, a),
                   q == Quantity::Energy && elastic ? "energy conservation" : rule, key});
  out.push_back({Quantity::Collisions,
                 elastic ? 2.0 * (d + 1) / (d + 2) : std::numeric_limits<double>::quiet_NaN(),
                 elastic ? "Antal, Krapivsky, Redner 2008: collisions ~ t^(2(d+1)/(d+2))" : "",
                 5});
  // The kicked particle, where it is known (a box): its theory is the elastic blast's.
  const std::pair<Quantity, std::size_t> kicked[] = {{Quantity::KickedDisplacement, 7},
                                                     {Quantity::KickedSpeed, 8},
                                                     {Quantity::KickedCollisions, 9}};
  if (elastic && !p.unbounded())
    for (const auto& [q, key] : kicked)
      out.push_back({q, impurity_exponent(q, d),
                     "Kumar, Dhar, Krapivsky, arXiv:2505.02225 (2025): the kicked 'impurity' of "
                     "a hard-sphere blast",
                     key});
  return out;
}

std::size_t curve_index(const char* column) {
  for (std::size_t q = 0; q < kCurveColumns.size(); ++q)
    if (std::string(kCurveColumns[q]) == column) return q;
  GS_CHECK(false);
  return 0;
}

// The time-series column of the quantity; P_r / N_t has none (realisation_curves forms it).
const char* column_of(Quantity q) {
  switch (q) {
    case Quantity::ActiveCount: return "active";
    case Quantity::Energy: return "energy";
    case Quantity::RadiusRms: return "radius_rms";
    case Quantity::FrontRadius: return "front_radius";
    case Quantity::RadialMomentum: return "radial_momentum";
    case Quantity::RadialSpeed: return "radial_speed";
    case Quantity::Collisions: return "collisions";
    case Quantity::KickedDisplacement: return "kicked_displacement";
    case Quantity::KickedSpeed: return "kicked_speed";
    case Quantity::KickedCollisions: return "kicked_collisions";
  }
  return "";
}

// Each realisation's series of the quantity; P_r / N_t is formed per realisation.
std::vector<std::vector<double>> realisation_curves(const EnsembleSums& sums, Quantity q) {
  auto out = curves_of(sums, curve_index(q == Quantity::RadialSpeed ? "radial_momentum"
                                                                    : column_of(q)));
  if (q == Quantity::RadialSpeed) {
    const auto n = curves_of(sums, curve_index("active"));
    for (std::size_t k = 0; k < out.size(); ++k)
      for (std::size_t i = 0; i < out[k].size(); ++i) out[k][i] /= n[k][i];
  }
  return out;
}

double start_time(const Table& ts) {
  const auto& t = ts.column("t");
  for (std::size_t i = 0; i < t.size(); ++i)
    if (ts.column("active")[i] >= kStartActive) return t[i];
  return t.back();
}

// The plateau of e's local slope, inside the user's window if one is given (UserError naming
// where it plateaus otherwise); the window to fit on, or nothing (e.note says why).
std::optional<Window> fit_window(ExponentFit& e, const PlateauOptions& po, const FitOptions& o) {
  if (!o.window) {
    e.plateau = find_plateau(e.slope, po);
    if (!e.plateau.found) {
      e.note = e.plateau.note;
      return std::nullopt;
    }
    return e.plateau.window;
  }
  PlateauOptions inside = po;
  inside.t_min = std::max(po.t_min, o.window->t_lo);
  inside.t_max = std::min(po.t_max, o.window->t_hi);
  e.plateau = find_plateau(e.slope, inside);
  if (!e.plateau.found) {
    const Plateau anywhere = find_plateau(e.slope, po);
    throw UserError("--window " + format_number(o.window->t_lo) + "," +
                    format_number(o.window->t_hi) + ": the local slope of " + e.quantity +
                    " has no plateau inside it; " +
                    (anywhere.found ? "it plateaus over " + window_text(anywhere.window)
                                    : anywhere.note));
  }
  return o.window;
}

ExponentFit fit_exponent(const EnsembleSums& sums, const QuantityPlan& qp, double t_start,
                         const FitOptions& o) {
  const std::size_t key = qp.key;
  const EnsembleSpec& spec = sums.spec();
  const auto t = sums.timeseries().column("t");
  ExponentFit e;
  e.kind = qp.kind;
  e.quantity = quantity_name(qp.kind);
  e.column = column_of(qp.kind);
  e.theory = qp.theory;
  e.theory_source = qp.source;
  const auto curves = realisation_curves(sums, qp.kind);
  SlopeBandOptions so;
  so.resamples = o.band_resamples;
  so.seed = spec.physics.seed;
  so.key = 100 + key;
  e.slope = local_slope_band(t, curves, so);
  PlateauOptions po = o.plateau;
  po.t_min = std::max(po.t_min, t_start);
  e.corrected = corrected_exponent(e.slope, std::max(t_start, t.back() / 100), t.back());
  const std::optional<Window> w = fit_window(e, po, o);
  const int d = spec.physics.dim;
  if (!w) {
    implied_alpha(e, d, std::numeric_limits<double>::quiet_NaN());
    return e;
  }
  try {
    if (curves.size() >= 2) {
      BootstrapOptions bo;
      bo.resamples = o.resamples;
      bo.seed = spec.physics.seed;
      bo.key = key + 1;
      e.fit = fit_power_law_bootstrap(t, curves, *w, bo);
    } else {
      e.fit = fit_power_law(t, curves.front(), *w);
    }
  } catch (const UserError& err) {
    if (o.window) throw;  // a window the user gave must fit
    e.note = err.what();
  }
  e.window_systematic = e.plateau.window_spread;
  const double half =
      e.fit.confidence > 0 ? 0.5 * (e.fit.ci_hi - e.fit.ci_lo) : e.fit.standard_error;
  implied_alpha(e, d, half);
  return e;
}

// Largest |v_rms^2 N / (2 E) - 1| over realisations and samples with N >= 20 (unit masses; the
// particles at rest carry no energy).
double speed_identity_error(const EnsembleSums& sums) {
  const std::size_t n = curve_index("active"), en = curve_index("energy"),
                    v = curve_index("speed_rms");
  double worst = 0;
  bool any = false;
  for (const auto& [k, c] : sums.curves())
    for (std::size_t i = 0; i < c[n].size(); ++i)
      if (c[n][i] >= kStartActive && c[en][i] > 0) {
        worst = std::max(worst, std::fabs(c[v][i] * c[v][i] * c[n][i] / (2 * c[en][i]) - 1));
        any = true;
      }
  return any ? worst : std::numeric_limits<double>::quiet_NaN();
}

void fit_crossovers(EnsembleFits& f, const EnsembleSums& sums, const FitOptions& o,
                    double t_start) {
  const EnsembleSpec& spec = sums.spec();
  const Table ts = sums.timeseries();
  const auto& t = ts.column("t");
  SlopeCrossoverOptions co;
  co.target = f.alpha_theory * spec.physics.dim;
  co.t_lo = t_start;
  const CrossoverPair tc = crossover_pair(t, ts.column("active"), co);
  f.tc1_slope = tc.enter;
  f.tc2 = tc.leave;
  // The same rules on resampled ensembles (realisations drawn with replacement).
  const CrossoverDraws draws =
      crossover_draws(t, curves_of(sums, 0), co, o.band_resamples, spec.physics.seed, 200);
  f.tc1_slope_draws = draws.enter;
  f.tc2_draws = draws.leave;
  if (spec.physics.elastic()) {
    f.tc1.note = "r = 1 has no inelastic regime";
    return;
  }
  // The kick's energy (unit masses), all the blast has before its first collision.
  const double e0 = 0.5 * spec.physics.speed * spec.physics.speed;
  const ExponentFit* energy = find_exponent(f, Quantity::Energy);
  GS_CHECK(energy != nullptr);
  f.tc1 = crossover_energy(energy->fit, e0, t.back(), energy->note);
  if (!f.tc1.found) {
    // No settled plateau for the fitted law: none for this reading either, for that reason.
    f.tc1_theory_b.note = f.tc1.note;
    return;
  }
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
}

// A at the last sample, its isotropic floor, and the weighted least-squares slope of ln A on
// ln t over the last half decade.
void fit_anisotropy(EnsembleFits& f, const Table& ts) {
  const auto& t = ts.column("t");
  const auto& an = ts.column("anisotropy");
  const auto& an_sem = ts.column("anisotropy_sem");
  f.anisotropy = an.back();
  f.anisotropy_sem = an_sem.back();
  f.anisotropy_floor = ts.column("anisotropy_isotropic").back();
  f.anisotropy_floor_sem = ts.column("anisotropy_isotropic_sem").back();
  f.active_last = ts.column("active").back();
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

void last_snapshot_scalars(EnsembleFits& f, const EnsembleSums& sums) {
  const auto& snaps = sums.snapshots();
  if (snaps.empty() || sums.count() == 0) return;
  f.last_scalars = snaps.back().scalars.mean();
  f.last_scalars_sem = snaps.back().scalars.standard_error();
  f.packing_typical = f.last_scalar("packing_typical");
  f.packing_typical_sem = f.last_scalar_sem("packing_typical");
  f.packing_upper = f.last_scalar("packing_upper");
  f.packing_upper_sem = f.last_scalar_sem("packing_upper");
  f.inner_outer_ratio = f.last_scalar("inner_outer_ratio");
  f.inner_outer_ratio_sem = f.last_scalar_sem("inner_outer_ratio");
}

void fit_collapse(EnsembleFits& f, const EnsembleSums& sums, const FitOptions& o) {
  const auto& snaps = sums.snapshots();
  if (snaps.size() < 2 || sums.count() == 0) {
    f.collapse_note = "needs at least two snapshot times";
    return;
  }
  const double a = f.alpha_theory;
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
  cs.seed = sums.spec().physics.seed;
  cs.key = 300;
  f.collapse_alpha_radius = best_collapse_alpha(sr, CollapseVariable::Radius, cs);
  cs.key = 301;
  f.collapse_alpha_speed = best_collapse_alpha(sv, CollapseVariable::Speed, cs);
}

}  // namespace

EnsembleFits fit_ensemble(const EnsembleSums& sums, const FitOptions& o) {
  const EnsembleSpec& spec = sums.spec();
  EnsembleFits f;
  f.alpha_theory = theory_alpha(spec.physics);
  const Table ts = sums.timeseries();
  const double t_start = start_time(ts);
  const auto plan = quantities_of(spec.physics, f.alpha_theory);
  for (const auto& q : plan) f.exponents.push_back(fit_exponent(sums, q, t_start, o));
  f.speed_identity_error = speed_identity_error(sums);
  fit_crossovers(f, sums, o, t_start);
  fit_anisotropy(f, ts);
  last_snapshot_scalars(f, sums);
  fit_collapse(f, sums, o);
  return f;
}

}  // namespace gs
