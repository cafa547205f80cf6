#include "apps/ensemble_cli.h"

#include <sstream>

#include "analysis/ensemble_output.h"
#include "analysis/json.h"
#include "apps/cli.h"
#include "sim/error.h"

namespace gs::app {

void add_window_option(CLI::App& sub, std::vector<double>& values) {
  sub.add_option("--window", values,
                 "Scaling window T1,T2 (simulation time) for the exponent fits; default: automatic")
      ->delimiter(',')
      ->expected(2);
}

std::optional<Window> window_of(const std::vector<double>& values, const EnsembleSpec& spec) {
  if (values.empty()) return std::nullopt;
  if (values.size() != 2) throw UserError("--window needs two times T1,T2");
  const Window w{values[0], values[1]};
  check_window(spec, w);
  return w;
}

EnsembleFits write_ensemble_folder(const std::filesystem::path& dir, const EnsembleSums& sums,
                                   const FitOptions& fit, double wall_seconds, int threads) {
  const EnsembleFits fits = fit_ensemble(sums, fit);
  write_ensemble_outputs(dir, sums, fits);
  std::ostringstream j;
  j << "{\n  \"wall_seconds\": " << json_number(wall_seconds) << ",\n  \"threads\": " << threads
    << ",\n  \"realisations\": " << sums.count() << ",\n  \"wall_seconds_per_realisation\": "
    << json_number(wall_seconds / double(std::max<std::uint64_t>(1, sums.count()))) << "\n}\n";
  write_file_atomic(dir / "timing.json", j.str());
  return fits;
}

}  // namespace gs::app
