// Wall time of `grainshock figures`: --quick measured end to end, --full estimated from a sample
// of realisations of every case (the targets the plan was sized for: < 3 min and < 30 min on 2
// cores). The command runs as a child process of this binary, exactly as a user would run it.
#include <unistd.h>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>

#include "analysis/json.h"
#include "bench/bench.h"
#include "sim/error.h"

namespace gs::bench {
namespace {

namespace fs = std::filesystem;

std::string self() {
  return fs::read_symlink("/proc/self/exe").string();
}

fs::path scratch(const std::string& name) {
  auto d =
      fs::temp_directory_path() / ("grainshock_bench_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(d);
  return d;
}

double run_figures(const std::string& args, const fs::path& out) {
  const auto t0 = std::chrono::steady_clock::now();
  // Built with append: GCC 12 warns falsely (-Wrestrict) on "literal" + std::string&&.
  std::string cmd = "'";
  cmd.append(self()).append("' figures ").append(args).append(" --quiet --out '");
  cmd.append(out.string()).append("'");
  if (std::system(cmd.c_str()) != 0)
    throw UserError("bench: `grainshock figures " + args + "` failed");
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// A top-level number of a JSON file the command wrote.
double json_value(const fs::path& file, const std::string& key) {
  std::ifstream f(file);
  const Json j = Json::parse(f, nullptr, false);
  if (!j.is_object() || !j.contains(key) || !j[key].is_number())
    throw UserError(file.string() + ": no number " + key);
  return j[key].get<double>();
}

int threads() {
  return std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
}

}  // namespace

void add_figures_cases(std::vector<Case>& cases) {
  cases.push_back({"figures/tiny", "grainshock figures --tiny end to end (smoke size)", false, [] {
                     const auto out = scratch("tiny");
                     const double s = run_figures("--tiny", out);
                     fs::remove_all(out);
                     return std::vector<Figure>{{"wall_seconds", s, "s", ""}};
                   }});
  cases.push_back({"figures/quick", "grainshock figures --quick end to end", true, [] {
                     const auto out = scratch("quick");
                     const double s = run_figures("--quick", out);
                     fs::remove_all(out);
                     return std::vector<Figure>{{"wall_seconds", s, "s", "< 180 s on 2 cores"},
                                                {"threads", double(threads()), "", ""}};
                   }});
  cases.push_back({"figures/full_estimate",
                   "grainshock figures --full --estimate: 2 realisations per case, extrapolated",
                   true, [] {
                     const auto out = scratch("full");
                     const double s = run_figures("--full --estimate --sample 2", out);
                     const double est = json_value(out / "estimate.json", "estimated_wall_seconds");
                     const double est_cpu =
                         json_value(out / "estimate.json", "estimated_wall_seconds_from_cpu");
                     const double cpu = json_value(out / "estimate.json", "estimated_cpu_seconds");
                     fs::remove_all(out);
                     return std::vector<Figure>{
                         {"sample_wall_seconds", s, "s", ""},
                         {"full_estimated_wall_seconds", est, "s", "< 1800 s on 2 cores"},
                         {"full_estimated_from_cpu_seconds", est_cpu, "s", "< 1800 s on 2 cores"},
                         {"full_estimated_cpu_seconds", cpu, "s", ""},
                         {"threads", double(threads()), "", ""}};
                   }});
}

}  // namespace gs::bench
