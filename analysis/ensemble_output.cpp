#include "analysis/ensemble_output.h"

#include <toml++/toml.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>

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
                                          "P_packing_sem"};
  for (const auto& n : names) out.add_column(n, {});
  for (const auto& s : sums.snapshots()) {
    const Histogram pr = s.radius.mean(), pv = s.speed.mean(), pp = s.packing.mean();
    const auto pr_se = s.radius.standard_error(), pv_se = s.speed.standard_error(),
               pp_se = s.packing.standard_error();
    const Histogram fr = scaled_radial_distribution(pr, s.t, a);
    const Histogram fv = scaled_speed_distribution(pv, s.t, a);
    const RadialProfile prof = s.profile.mean();
    const auto prof_se = s.profile.density_standard_error();
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
                                       pp_se[b]};
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

std::string crossover_json(const Crossover& c) {
  return "{\"found\": " + std::string(c.found ? "true" : "false") +
         ", \"time\": " + json_number(c.time) + ", \"note\": " + json_string(c.note) + "}";
}

}  // namespace

void check_fit_options(const EnsembleSpec& spec, const FitOptions& fit) {
  // Fewer resamples than 10 give no 95% interval at all; the cap keeps a typo from running for
  // days.
  if (fit.resamples < 10 || fit.resamples > 1000000)
    throw UserError("--resamples must be in [10, 1000000], not " + std::to_string(fit.resamples));
  if (fit.window) check_window(spec, *fit.window);
}

std::string job_toml(const EnsembleJob& job) {
  std::string s = spec_toml(job.spec);
  s += "resamples = " + std::to_string(job.fit.resamples) + "\n";
  if (job.fit.window)
    s += "window = [" + format_double(job.fit.window->t_lo) + ", " +
         format_double(job.fit.window->t_hi) + "]\n";
  if (job.keep_realisations) s += "per-realisation = true\n";
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
  std::ostringstream j;
  j << "{\n";
  j << "  \"version\": " << json_string(GRAINSHOCK_VERSION) << ",\n";
  j << "  \"dim\": " << p.dim << ",\n";
  j << "  \"particles\": " << p.particles << ",\n";
  j << "  \"density\": " << json_number(p.density) << ",\n";
  j << "  \"restitution\": " << json_number(p.restitution) << ",\n";
  j << "  \"cutoff\": " << json_number(p.cutoff) << ",\n";
  j << "  \"seed\": " << p.seed << ",\n";
  j << "  \"t_max\": " << json_number(p.t_max) << ",\n";
  j << "  \"t_max_paper\": " << json_number(p.paper_time(p.t_max)) << ",\n";
  j << "  \"realisations\": " << sums.count() << ",\n";
  j << "  \"realisation_indices\": [";
  for (std::size_t k = 0; k < sums.indices().size(); ++k) j << (k ? ", " : "") << sums.indices()[k];
  j << "],\n";
  j << "  \"alpha_theory\": " << json_number(f.alpha_theory) << ",\n";
  j << "  \"alpha_theory_rule\": "
    << json_string(p.restitution < 1 ? "1/(d+1) for r < 1" : "2/(d+2) for r = 1") << ",\n";
  j << "  \"exponents\": [\n";
  for (std::size_t k = 0; k < f.exponents.size(); ++k) {
    const auto& e = f.exponents[k];
    j << "    {\"quantity\": " << json_string(e.quantity)
      << ", \"column\": " << json_string(e.column)
      << ", \"exponent\": " << json_number(e.fit.exponent)
      << ", \"ci_lo\": " << json_number(e.fit.ci_lo) << ", \"ci_hi\": " << json_number(e.fit.ci_hi)
      << ", \"confidence\": " << json_number(e.fit.confidence)
      << ", \"standard_error\": " << json_number(e.fit.standard_error)
      << ", \"theory\": " << json_number(e.theory) << ", \"window\": ["
      << json_number(e.fit.window.t_lo) << ", " << json_number(e.fit.window.t_hi)
      << "], \"points\": " << e.fit.points
      << ", \"plateau_drift\": " << json_number(e.plateau.drift)
      << ", \"plateau_drift_error\": " << json_number(e.plateau.drift_error)
      << ", \"plateau_curvature\": " << json_number(e.plateau.curvature)
      << ", \"plateau_curvature_error\": " << json_number(e.plateau.curvature_error)
      << ", \"corrected_exponent\": " << json_number(e.corrected.b)
      << ", \"corrected_ci\": [" << json_number(e.corrected.ci_lo) << ", "
      << json_number(e.corrected.ci_hi) << "], \"corrected_omega\": "
      << json_number(e.corrected.omega)
      << ", \"alpha\": " << json_number(e.alpha)
      << ", \"alpha_uncertainty\": " << json_number(e.alpha_uncertainty)
      << ", \"note\": " << json_string(e.note) << "}" << (k + 1 < f.exponents.size() ? "," : "")
      << "\n";
  }
  j << "  ],\n";
  j << "  \"exponent_definition\": "
    << json_string(
           "least-squares slope of ln <y> vs ln t over the window (automatic: the plateau of "
           "the local slope, analysis/effective_exponent.h: the latest window of >= 0.5 "
           "decades, after <N_t> >= 20, whose drift D (mean local slope of its last third "
           "minus that of its first) and curvature K (middle third minus the mean of the "
           "outer two) are both within 2 bootstrap standard deviations over realisations "
           "(+ 1e-3); none: no fit); plateau_drift = D, plateau_drift_error = its standard "
           "deviation; interval: 95% percentile bootstrap over realisations")
    << ",\n";
  // v_t is no fit of its own: v_rms^2 = 2 E / N holds exactly (analysis/ensemble_fits.h).
  j << "  \"v_t\": {\"identity\": \"v_rms^2 = 2 E_t / N_t\", \"max_relative_deviation\": "
    << json_number(f.speed_identity_error) << "},\n";
  j << "  \"t_c1\": " << crossover_json(f.tc1) << ",\n";
  j << "  \"t_c1_theory_b\": " << crossover_json(f.tc1_theory_b) << ",\n";
  j << "  \"t_c1_slope_rule\": " << crossover_json(f.tc1_slope) << ",\n";
  j << "  \"t_c2\": " << crossover_json(f.tc2) << ",\n";
  j << "  \"crossover_definition\": "
    << json_string(
           "t_c1 (intersection rule, r < 1) = (a / E_0)^(1/b), where the power law a t^-b "
           "fitted to <E_t> on the plateau of its local slope meets the kick's energy E_0 (the "
           "elastic regime conserves it); t_c1_theory_b = the same with b fixed at the "
           "theory's and a fitted on that plateau; t_c1_slope_rule = time from which the local "
           "slope of <N_t> stays at or below the upper edge of a 10% band around alpha d, up to "
           "t_c2 "
           "where the run reaches it; t_c2 = time from which that slope stays above the band "
           "(towards the elastic regime)")
    << ",\n";
  j << "  \"collapse_quality_radius\": " << json_number(f.collapse_radius) << ",\n";
  j << "  \"collapse_quality_speed\": " << json_number(f.collapse_speed) << ",\n";
  j << "  \"collapse_note\": " << json_string(f.collapse_note) << ",\n";
  auto scan = [&](const char* key, const CollapseAlpha& c) {
    j << "  \"" << key << "\": {\"best\": " << json_number(c.best)
      << ", \"ci_lo\": " << json_number(c.ci_lo) << ", \"ci_hi\": " << json_number(c.ci_hi)
      << ", \"q_best\": " << json_number(c.q_best)
      << ", \"theory_inside\": " << (c.contains(f.alpha_theory) ? "true" : "false")
      << ", \"note\": " << json_string(c.note) << "},\n";
  };
  scan("collapse_alpha_radius", f.collapse_alpha_radius);
  scan("collapse_alpha_speed", f.collapse_alpha_speed);
  j << "  \"collapse_alpha_definition\": "
    << json_string("the alpha of [0.1, 0.6] (step 0.0025) minimising chi^2 per point of the "
                   "mean scaled distributions against their mean (q_best: Q there); 95% interval over 200 parametric resamples of every bin "
                   "(normal, its standard error over realisations)")
    << ",\n";
  j << "  \"anisotropy_last\": " << json_number(f.anisotropy) << ",\n";
  j << "  \"anisotropy_last_sem\": " << json_number(f.anisotropy_sem) << ",\n";
  j << "  \"anisotropy_slope\": " << json_number(f.anisotropy_slope)
    << ", \"anisotropy_slope_error\": " << json_number(f.anisotropy_slope_error)
    << ", \"anisotropy_slope_window\": [" << json_number(f.anisotropy_window.t_lo) << ", "
    << json_number(f.anisotropy_window.t_hi) << "],\n";
  j << "  \"packing_typical\": " << json_number(f.packing_typical) << ",\n";
  j << "  \"packing_typical_sem\": " << json_number(f.packing_typical_sem) << ",\n";
  j << "  \"packing_upper\": " << json_number(f.packing_upper) << ",\n";
  j << "  \"packing_upper_sem\": " << json_number(f.packing_upper_sem) << ",\n";
  j << "  \"packing_definition\": " << json_string(BandPacking::definition)
    << ", \"packing_upper_definition\": "
    << json_string("active-weighted 90% quantile of the band cells' packing fractions") << ",\n";
  j << "  \"inner_outer_speed_ratio\": " << json_number(f.inner_outer_ratio) << ",\n";
  j << "  \"inner_outer_speed_ratio_sem\": " << json_number(f.inner_outer_ratio_sem) << "\n";
  j << "}\n";
  return j.str();
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
