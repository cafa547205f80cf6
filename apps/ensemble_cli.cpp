#include "apps/ensemble_cli.h"

#include <cstdio>

#include "apps/cli.h"
#include "apps/exit_code.h"
#include "apps/progress.h"
#include "sim/error.h"

namespace gs::app {

void add_fit_options(CLI::App& sub, int& resamples, std::vector<double>& window) {
  sub.add_option("--resamples", resamples,
                 "Bootstrap resamples of the exponent intervals, in [10, 1000000]")
      ->check(CLI::Range(10, 1000000))  // before any folder is read, as every range (exit 2)
      ->capture_default_str();
  sub.add_option("--window", window,
                 "Scaling window T1,T2 (simulation time) for the exponent fits; default: automatic")
      ->delimiter(',')
      ->expected(2);
}

int finish_ensemble_command(const jobs::EnsembleResult& r) {
  if (r.served >= 0) return r.served;
  std::fputs(r.exponent_table.c_str(), stdout);
  std::fflush(stdout);
  return r.interrupted ? kExitInterrupted : kExitSuccess;
}

int resume_ensemble_command(const std::filesystem::path& dir, int threads, bool quiet) {
  return finish_ensemble_command(
      jobs::resume_ensemble(dir, threads, quiet, terminal_progress(quiet), terminal_messages()));
}

}  // namespace gs::app
