#include "analysis/ensemble_output.h"

#include <toml++/toml.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "analysis/json.h"
#include "io/atomic_file.h"
#include "sim/error.h"
#include "sim/format.h"

namespace gs {
namespace {

Table distributions(const EnsembleSums& sums) {
  const double a = theory_alpha(sums.spec().physics);
  Table out;
  const std::vector<std::string> names = {"t",
                                          "bin",
                                          "R",
                                          "P_R",
                                          "P_R_sem",
                                          "x_R",
                                          "f1",
                                          "v",
                                          "P_v",
                                          "P_v_sem",
                                          "x_v",
                                          "f2",
                                          "profile_density",
                                          "profile_density_sem",
                                          "profile_count",
                                          "profile_mean_speed",
                                          "profile_mean_radial_velocity",
                                          "packing",
                                          "P_packing",
                                          "P_packing_sem",
                                          "pressure_x",
                                          "pressure",
                                          "pressure_sem"};
  for (const auto& n : names) out.add_column(n, {});
  for (const auto& s : sums.snapshots()) {
    const Histogram pr = s.radius.mean(), pv = s.speed.mean(), pp = s.packing.mean();
    const auto pr_se = s.radius.standard_error(), pv_se = s.speed.standard_error(),
               pp_se = s.packing.standard_error();
    const Histogram fr = scaled_radial_distribution(pr, s.t, a);
    const Histogram fv = scaled_speed_distribution(pv, s.t, a);
    const RadialProfile prof = s.profile.mean();
    const auto prof_se = s.profile.density_standard_error();
    // The kinetic pressure against rho / R_front (analysis/core_energy.h); NaN when no
    // realisation measured it (folders from before it).
    const Binning xb = pressure_binning(sums.spec());
    const bool has_p = s.pressure.count() > 0 && s.pressure.length() == pr.bins();
    const std::vector<double> p = has_p ? s.pressure.mean() : std::vector<double>{};
    const std::vector<double> p_se = has_p ? s.pressure.standard_error() : std::vector<double>{};
    const double nan = std::numeric_limits<double>::quiet_NaN();
    for (std::size_t b = 0; b < pr.bins(); ++b) {
      const std::vector<double> row = {s.t,
                                       double(b),
                                       pr.centre(b),
                                       pr.values[b],
                                       pr_se[b],
                                       fr.centre(b),
                                       fr.values[b],
                                       pv.centre(b),
                                       pv.values[b],
                                       pv_se[b],
                                       fv.centre(b),
                                       fv.values[b],
                                       prof.density[b],
                                       prof_se[b],
                                       double(prof.count[b]),
                                       prof.mean_speed[b],
                                       prof.mean_radial_velocity[b],
                                       pp.centre(b),
                                       pp.values[b],
                                       pp_se[b],
                                       xb.lo + (double(b) + 0.5) * (xb.hi - xb.lo) / xb.bins,
                                       has_p ? p[b] : nan,
                                       has_p ? p_se[b] : nan};
      out.add_row(row);
    }
  }
  return out;
}

Table snapshot_scalars(const EnsembleSums& sums) {
  Table out;
  out.add_column("t", {});
  for (const char* n : kSnapshotScalars) {
    out.add_column(n, {});
    out.add_column(std::string(n) + "_sem", {});
  }
  for (const auto& s : sums.snapshots()) {
    const auto m = s.scalars.mean(), se = s.scalars.standard_error();
    std::vector<double> row = {s.t};
    for (std::size_t k = 0; k < m.size(); ++k) {
      row.push_back(m[k]);
      row.push_back(se[k]);
    }
    out.add_row(row);
  }
  return out;
}

Json crossover_json(const Crossover& c) {
  return {{"found", c.found}, {"time", c.time}, {"note", c.note}};
}

Json window_json(const Window& w) {
  return Json::array({w.t_lo, w.t_hi});
}

}  // namespace

void check_fit_options(const EnsembleSpec& spec, const FitOptions& fit) {
  // Fewer resamples than 10 give no 95% interval at all; the cap keeps a typo from running for
  // days.
  if (fit.resamples < 10 || fit.resamples > 1000000)
    throw UsageError("--resamples must be in [10, 1000000], not " + std::to_string(fit.resamples));
  if (fit.window) check_window(spec, *fit.window);
}

std::string job_toml(const EnsembleJob& job) {
  std::string s = spec_toml(job.spec);
  s += "resamples = " + std::to_string(job.fit.resamples) + "\n";
  if (job.fit.window)
    s += "window = [" + format_double(job.fit.window->t_lo) + ", " +
         format_double(job.fit.window->t_hi) + "]\n";
  if (job.keep_realisations) s += "per-realisation = true\n";
  if (job.checkpoint_minutes != kCheckpointMinutes)
    s += "checkpoint-minutes = " + format_double(job.checkpoint_minutes) + "\n";
  return s;
}

EnsembleJob read_job(const std::filesystem::path& file) {
  EnsembleJob job;
  job.spec = read_spec(file);
  const std::string where = file.string();
  toml::table t;
  try {
    t = toml::parse_file(where);
  } catch (const toml::parse_error& e) {
    throw UserError(where + ": malformed TOML at line " + std::to_string(e.source().begin.line));
  }
  if (const auto* n = t.get("resamples")) {
    const auto v = n->value<std::int64_t>();
    if (!v || *v < 0 || *v > std::numeric_limits<int>::max())
      throw UserError(where + ": key 'resamples' is not a count");
    job.fit.resamples = static_cast<int>(*v);
  }
  if (const auto* n = t.get("window")) {
    const auto* a = n->as_array();
    if (a == nullptr || a->size() != 2 || !(*a)[0].value<double>() || !(*a)[1].value<double>())
      throw UserError(where + ": key 'window' is not two times [T1, T2]");
    job.fit.window = Window{*(*a)[0].value<double>(), *(*a)[1].value<double>()};
  }
  if (const auto* n = t.get("per-realisation")) {
    const auto v = n->value<bool>();
    if (!v) throw UserError(where + ": key 'per-realisation' is not true or false");
    job.keep_realisations = *v;
  }
  if (const auto* n = t.get("checkpoint-minutes")) {
    const auto v = n->value<double>();
    if (!v || !(*v >= 0) || !std::isfinite(*v))
      throw UserError(where + ": key 'checkpoint-minutes' is not a number of minutes >= 0");
    job.checkpoint_minutes = *v;
  }
  try {
    check_fit_options(job.spec, job.fit);
  } catch (const UserError& e) {
    throw UserError(where + ": " + e.what());
  }
  return job;
}

EnsembleSpec held_spec(const EnsembleSums& sums) {
  EnsembleSpec s = sums.spec();
  if (!sums.indices().empty()) s.physics.realisation = sums.indices().front();
  s.realisations = sums.count();
  return s;
}

std::string summary_json(const EnsembleSums& sums, const EnsembleFits& f) {
  const EnsembleSpec spec = held_spec(sums);
  const auto& p = spec.physics;
  Json j;
  j["version"] = GRAINSHOCK_VERSION;
  j.update(physics_json(p));
  j["t_max"] = p.t_max;
  j["t_max_paper"] = p.paper_time(p.t_max);
  j["realisations"] = sums.count();
  j["realisation_indices"] = sums.indices();
  j["alpha_theory"] = f.alpha_theory;
  j["alpha_theory_rule"] = !p.elastic() ? "1/(d+1) for r < 1" : "2/(d+2) for r = 1";
  Json& exponents = j["exponents"] = Json::array();
  for (const auto& e : f.exponents)
    exponents.push_back({{"quantity", e.quantity},
                         {"column", e.column},
                         {"exponent", e.fit.exponent},
                         {"ci_lo", e.fit.ci_lo},
                         {"ci_hi", e.fit.ci_hi},
                         {"confidence", e.fit.confidence},
                         {"standard_error", e.fit.standard_error},
                         {"theory", e.theory},
                         {"window", window_json(e.fit.window)},
                         {"points", e.fit.points},
                         {"plateau_drift", e.plateau.drift},
                         {"plateau_drift_error", e.plateau.drift_error},
                         {"plateau_curvature", e.plateau.curvature},
                         {"plateau_curvature_error", e.plateau.curvature_error},
                         {"window_systematic", e.window_systematic},
                         {"passing_windows", e.plateau.passing_windows},
                         {"corrected_exponent", e.corrected.b},
                         {"corrected_ci", Json::array({e.corrected.ci_lo, e.corrected.ci_hi})},
                         {"corrected_omega", e.corrected.omega},
                         {"alpha", e.alpha},
                         {"alpha_uncertainty", e.alpha_uncertainty},
                         {"note", e.note}});
  j["exponent_definition"] =
      "least-squares slope of ln <y> vs ln t over the window (automatic: the plateau of "
      "the local slope, analysis/effective_exponent.h: the latest window of >= 1 "
      "decade, after <N_t> >= 20, whose drift D (mean local slope of its last third "
      "minus that of its first), curvature K (middle third minus the mean of the "
      "outer two) and distance from the last decade's mean slope are each within 2 "
      "bootstrap standard deviations over realisations (+ 1e-3) and within 0.005; none: "
      "no fit); plateau_drift = D, plateau_drift_error = its standard deviation; "
      "window_systematic: standard deviation of the mean local slope over the "
      "passing_windows; interval: 95% percentile bootstrap over realisations";
  // v_t is no fit of its own: v_rms^2 = 2 E / N holds exactly (analysis/ensemble_fits.h).
  j["v_t"] = {{"identity", "v_rms^2 = 2 E_t / N_t"},
              {"max_relative_deviation", f.speed_identity_error}};
  j["t_c1"] = crossover_json(f.tc1);
  j["t_c1_theory_b"] = crossover_json(f.tc1_theory_b);
  j["t_c1_slope_rule"] = crossover_json(f.tc1_slope);
  j["t_c2"] = crossover_json(f.tc2);
  j["crossover_definition"] =
      "t_c1 (intersection rule, r < 1) = (a / E_0)^(1/b), where the power law a t^-b "
      "fitted to <E_t> on the plateau of its local slope meets the kick's energy E_0 (the "
      "elastic regime conserves it); t_c1_theory_b = the same with b fixed at the "
      "theory's and a fitted on that plateau; t_c1_slope_rule = time from which the local "
      "slope of <N_t> stays at or below the upper edge of a 10% band around alpha d, up to "
      "t_c2 where the run reaches it; t_c2 = time from which that slope stays above the band "
      "(towards the elastic regime)";
  j["collapse_quality_radius"] = f.collapse_radius;
  j["collapse_quality_speed"] = f.collapse_speed;
  j["collapse_note"] = f.collapse_note;
  auto scan = [&](const CollapseAlpha& c) {
    return Json{{"best", c.best},
                {"ci_lo", c.ci_lo},
                {"ci_hi", c.ci_hi},
                {"q_best", c.q_best},
                {"theory_inside", c.contains(f.alpha_theory)},
                {"note", c.note}};
  };
  j["collapse_alpha_radius"] = scan(f.collapse_alpha_radius);
  j["collapse_alpha_speed"] = scan(f.collapse_alpha_speed);
  j["collapse_alpha_definition"] =
      "the alpha of [0.1, 0.6] (step 0.0025) minimising chi^2 per point of the mean scaled "
      "distributions against their mean (q_best: Q there); 95% interval over 200 parametric "
      "resamples of every bin (normal, its standard error over realisations)";
  j["anisotropy_last"] = f.anisotropy;
  j["anisotropy_last_sem"] = f.anisotropy_sem;
  j["anisotropy_slope"] = f.anisotropy_slope;
  j["anisotropy_slope_error"] = f.anisotropy_slope_error;
  j["anisotropy_slope_window"] = window_json(f.anisotropy_window);
  j["anisotropy_isotropic_last"] = f.anisotropy_floor;
  j["anisotropy_isotropic_last_sem"] = f.anisotropy_floor_sem;
  j["packing_typical"] = f.packing_typical;
  j["packing_typical_sem"] = f.packing_typical_sem;
  j["packing_upper"] = f.packing_upper;
  j["packing_upper_sem"] = f.packing_upper_sem;
  j["packing_definition"] = BandPacking::definition;
  j["packing_upper_definition"] =
      "active-weighted 90% quantile of the band cells' packing fractions";
  j["inner_outer_speed_ratio"] = f.inner_outer_ratio;
  j["inner_outer_speed_ratio_sem"] = f.inner_outer_ratio_sem;
  return json_text(j);
}

std::string exponent_table(const EnsembleSums& sums, const EnsembleFits& fits) {
  char line[256];
  std::snprintf(line, sizeof line,
                "# %llu realisations; <y> ~ t^exponent, 95%% bootstrap interval [ci_lo, ci_hi]; "
                "theory alpha = %.4f\n",
                static_cast<unsigned long long>(sums.count()), fits.alpha_theory);
  std::string s = line;
  int width = 8;
  for (const auto& e : fits.exponents) width = std::max(width, int(e.quantity.size()));
  std::snprintf(line, sizeof line, "%-*s %9s %9s %9s %9s %9s %9s  note\n", width, "quantity",
                "exponent", "ci_lo", "ci_hi", "theory", "alpha", "alpha_err");
  s += line;
  for (const auto& e : fits.exponents) {
    std::snprintf(line, sizeof line, "%-*s %9.4f %9.4f %9.4f %9.4f %9.4f %9.4f", width,
                  e.quantity.c_str(), e.fit.exponent, e.fit.ci_lo, e.fit.ci_hi, e.theory, e.alpha,
                  e.alpha_uncertainty);
    s += line;
    s += (e.note.empty() ? "" : "  " + e.note) + "\n";
  }
  return s;
}

void write_ensemble_outputs(const std::filesystem::path& dir, const EnsembleSums& sums,
                            const EnsembleFits& fits) {
  GS_CHECK(sums.count() >= 1);
  write_csv(sums.timeseries(), dir / "timeseries_mean.csv");
  write_csv(distributions(sums), dir / "distributions_mean.csv");
  write_csv(snapshot_scalars(sums), dir / "snapshot_scalars_mean.csv");
  write_file_atomic(dir / "summary.json", summary_json(sums, fits));
}

}  // namespace gs
