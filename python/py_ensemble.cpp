// grainshock.ensemble: the realisations of `grainshock ensemble` run on threads in this process
// (analysis/ensemble_runner.h) with the same spec checks and fits (analysis/ensemble_fits.h),
// returned as numpy arrays and dicts; the folder and its files stay the command's job. Ctrl-C
// asks the runner to stop (sim/stop.h) and raises KeyboardInterrupt once it has.
#include <chrono>
#include <future>
#include <mutex>
#include <string>
#include <vector>

#include "analysis/ensemble_fits.h"
#include "analysis/ensemble_runner.h"
#include "jobs/ensemble_job.h"
#include "python/py_module.h"
#include "sim/stop.h"

namespace gs::py {
namespace {

pb::dict fit_dict(const ExponentFit& e) {
  pb::dict d;
  d["column"] = e.column;
  d["theory"] = e.theory;
  d["exponent"] = e.fit.exponent;
  d["prefactor"] = e.fit.prefactor;
  d["ci_lo"] = e.fit.ci_lo;
  d["ci_hi"] = e.fit.ci_hi;
  d["window"] = pb::make_tuple(e.fit.window.t_lo, e.fit.window.t_hi);
  d["alpha"] = e.alpha;
  d["alpha_uncertainty"] = e.alpha_uncertainty;
  d["plateau"] = e.plateau.found;
  d["note"] = e.note;
  d["local_slope_t"] = copy(e.slope.t);
  d["local_slope"] = copy(e.slope.slope);
  return d;
}

pb::dict ensemble(int realisations, int threads, int per_decade, int bins, int resamples,
                  std::vector<double> window, const pb::kwargs& kw) {
  EnsembleSpec spec;
  spec.physics = physics(kw);
  spec.realisations = static_cast<std::uint64_t>(std::max(realisations, 0));
  spec.per_decade = per_decade;
  spec.bins = bins;
  spec = checked(spec);
  const FitOptions fit = jobs::fit_options(resamples, window, spec);
  RunnerOptions options;
  options.threads = threads;
  // The runner's warnings come from its worker threads; they are kept and given to Python's
  // warnings module from this thread, holding the GIL, once the ensemble is done.
  std::mutex warned_mutex;
  std::vector<std::string> warned;
  options.on_warning = [&](const std::string& what) {
    std::lock_guard lock(warned_mutex);
    warned.push_back(what);
  };
  // The runner polls the stop flag; Python's SIGINT handler stays in place, and a Ctrl-C seen
  // by PyErr_CheckSignals is passed on to the runner as a stop request.
  auto job = std::async(std::launch::async, [&] { return run_ensemble(spec, options); });
  bool interrupted = false;
  {
    pb::gil_scoped_release release;
    while (job.wait_for(std::chrono::milliseconds(50)) != std::future_status::ready) {
      pb::gil_scoped_acquire acquire;
      if (!interrupted && PyErr_CheckSignals() != 0) {
        interrupted = true;
        detail::stop_signal.store(SIGINT);
      }
    }
  }
  RunnerResult r = job.get();
  for (const std::string& w : warned)
    if (PyErr_WarnEx(PyExc_RuntimeWarning, w.c_str(), 1) != 0) throw pb::error_already_set();
  if (interrupted) {
    detail::stop_signal.store(0);
    throw pb::error_already_set();
  }
  EnsembleFits fits;
  {
    pb::gil_scoped_release release;
    fits = fit_ensemble(r.sums, fit);
  }
  pb::dict out;
  out["realisations"] = r.sums.count();
  pb::dict series;
  const Table t = r.sums.timeseries();
  for (std::size_t j = 0; j < t.names.size(); ++j) series[pb::str(t.names[j])] = copy(t.columns[j]);
  out["timeseries"] = series;
  pb::dict exps;
  for (const auto& e : fits.exponents) exps[pb::str(e.quantity)] = fit_dict(e);
  out["fits"] = exps;
  out["alpha_theory"] = theory_alpha(spec.physics);
  return out;
}

}  // namespace

void bind_ensemble(pb::module_& m) {
  m.def("ensemble", &ensemble, pb::kw_only(), pb::arg("realisations") = 8,
        pb::arg("threads") = 1, pb::arg("per_decade") = 20, pb::arg("bins") = 60,
        pb::arg("resamples") = 200, pb::arg("window") = std::vector<double>{},
        R"(Runs `realisations` kicks on `threads` threads and averages them as `grainshock ensemble`.

The physics are keyword arguments with the flags' names and defaults (dim, particles, density,
restitution, cutoff, speed, seed, initial, ..., t_max). Returns a dict: 'realisations',
'timeseries' (column -> numpy array: t, t_paper, the means and their standard errors '_sem'),
'fits' (quantity N_t, E_t, R_t, ... -> exponent, ci_lo, ci_hi, theory, window, alpha, local
slope), 'alpha_theory'. No files are written. The result does not depend on `threads`.)");
}

}  // namespace gs::py
