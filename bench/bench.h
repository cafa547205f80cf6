#pragma once
// Benchmarks behind `grainshock bench`. Each area contributes named cases; a case measures
// itself and returns rows of figures, which the command prints as a table (and JSON with --json).
#include <functional>
#include <string>
#include <vector>

namespace gs::bench {

struct Figure {
  std::string name;  // e.g. "collisions_per_cpu_second"
  double value = 0;
  std::string unit;  // e.g. "1/s", "ms"
  std::string
      target;  // the target the case was built to meet, in words, or empty ("< 1 s", ">= 2x EDMD")
};

struct Case {
  std::string name;  // e.g. "sim/thermal3d_phi0.2"
  std::string description;
  bool heavy = false;  // paper-scale cases, skipped unless asked for
  std::function<std::vector<Figure>()> run;
};

// Each area appends its cases.
void add_sim_cases(std::vector<Case>& cases);
void add_run_cases(std::vector<Case>& cases);
void add_render_cases(std::vector<Case>& cases);
void add_movie_cases(std::vector<Case>& cases);
void add_figures_cases(std::vector<Case>& cases);
void add_io_cases(std::vector<Case>& cases);
void add_medium_cases(std::vector<Case>& cases);
void add_memory_cases(std::vector<Case>& cases);
void add_view_cases(std::vector<Case>& cases);

// CPU seconds of this process (user + system), for "per CPU-second" figures.
double cpu_seconds();
double wall_seconds();
// The machine's 1-minute load average (getloadavg), reported beside wall-clock rates.
double load_average();

}  // namespace gs::bench
