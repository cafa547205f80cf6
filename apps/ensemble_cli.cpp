#include "apps/ensemble_cli.h"

#include <sstream>

#include "analysis/json.h"
#include "apps/cli.h"
#include "io/atomic_file.h"
#include "sim/error.h"

namespace gs::app {

void add_fit_options(CLI::App& sub, int& resamples, std::vector<double>& window) {
  sub.add_option("--resamples", resamples,
                 "Bootstrap resamples of the exponent intervals, in [10, 1000000]")
      ->capture_default_str();
  sub.add_option("--window", window,
                 "Scaling window T1,T2 (simulation time) for the exponent fits; default: automatic")
      ->delimiter(',')
      ->expected(2);
}

FitOptions fit_options(int resamples, const std::vector<double>& window, const EnsembleSpec& spec) {
  FitOptions fit;
  fit.resamples = resamples;
  if (!window.empty()) {
    if (window.size() != 2) throw UserError("--window needs two times T1,T2");
    fit.window = Window{window[0], window[1]};
  }
  check_fit_options(spec, fit);
  return fit;
}

EnsembleFits write_ensemble_folder(const std::filesystem::path& dir, const EnsembleSums& sums,
                                   const EnsembleJob& job, const RunTiming& t) {
  const EnsembleFits fits = fit_ensemble(sums, job.fit);
  write_file_atomic(dir / "ensemble.toml", job_toml(job));
  write_ensemble_outputs(dir, sums, fits);
  std::ostringstream j;
  j << "{\n  \"wall_seconds\": " << json_number(t.wall_seconds) << ",\n  \"threads\": " << t.threads
    << ",\n  \"ranks\": " << t.ranks << ",\n  \"realisations_run\": " << t.realisations
    << ",\n  \"wall_seconds_per_realisation\": "
    << json_number(t.wall_seconds / double(std::max<std::uint64_t>(1, t.realisations))) << "\n}\n";
  write_file_atomic(dir / "timing.json", j.str());
  return fits;
}

EnsembleFits write_ensemble_folder(const std::filesystem::path& dir, const EnsembleSums& sums,
                                   const FitOptions& fit, double wall_seconds, int threads) {
  return write_ensemble_folder(dir, sums, EnsembleJob{held_spec(sums), fit},
                               RunTiming{wall_seconds, threads, 1, sums.count()});
}

}  // namespace gs::app
