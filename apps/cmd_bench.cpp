// `grainshock bench`: the benchmarks of every area, as a table or JSON.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdio>

#include "analysis/json.h"
#include "apps/cli.h"
#include "apps/commands.h"
#include "bench/bench.h"
#include "io/atomic_file.h"
#include "sim/error.h"

namespace gs::app {

void add_bench_command(CLI::App& app) {
  struct Options {
    std::vector<std::string> filter;
    bool all = false, list = false;
    int repeat = 1;
    std::string json;
  };
  auto opt = std::make_shared<Options>();
  auto* sub = app.add_subcommand("bench", "Run the benchmarks (speed figures, not tests)");
  sub->add_option("filter", opt->filter, "Run only cases whose name contains one of these");
  sub->add_flag("--all", opt->all, "Include the heavy paper-scale cases");
  sub->add_flag("--list", opt->list, "List the cases and exit");
  sub->add_option("--repeat", opt->repeat,
                  "Run each case this many times and report the median of each figure, with the "
                  "range (a shared machine can move a figure by 10% from one minute to the next)")
      ->check(CLI::Range(1, 1000));
  sub->add_option("--json", opt->json, "Also write the figures to this JSON file");
  sub->callback([opt] {
    std::vector<bench::Case> cases;
    bench::add_sim_cases(cases);
    bench::add_run_cases(cases);
    bench::add_render_cases(cases);
    bench::add_movie_cases(cases);
    bench::add_figures_cases(cases);
    bench::add_io_cases(cases);
    bench::add_medium_cases(cases);
    bench::add_memory_cases(cases);
    bench::add_view_cases(cases);
    auto selected = [&](const bench::Case& c) {
      if (opt->filter.empty()) return opt->all || !c.heavy;
      for (const auto& f : opt->filter)
        if (c.name.find(f) != std::string::npos) return true;
      return false;
    };
    if (opt->list) {
      for (const auto& c : cases)
        std::printf("%-28s %s%s\n", c.name.c_str(), c.description.c_str(),
                    c.heavy ? " [heavy]" : "");
      return;
    }
    // Opened before the first case, so that a place it cannot be written is said at once, not
    // after minutes of benchmarks.
    AtomicFileWriter json_file;
    if (!opt->json.empty()) json_file.open(opt->json);
    Json json = Json::array();
    bool any = false;
    for (const auto& c : cases) {
      if (!selected(c)) continue;
      any = true;
      std::printf("%s: %s\n", c.name.c_str(), c.description.c_str());
      std::fflush(stdout);
      std::vector<std::vector<bench::Figure>> runs;
      for (int r = 0; r < opt->repeat; ++r) runs.push_back(c.run());
      for (std::size_t k = 0; k < runs[0].size(); ++k) {
        const bench::Figure& f = runs[0][k];
        std::vector<double> values;
        for (const auto& run : runs) {
          GS_CHECK(run.size() == runs[0].size() && run[k].name == f.name);
          values.push_back(run[k].value);
        }
        std::sort(values.begin(), values.end());
        const std::size_t m = values.size() / 2;
        const double median = values.size() % 2 ? values[m] : 0.5 * (values[m - 1] + values[m]);
        std::printf("  %-34s %14.6g %-4s %s", f.name.c_str(), median, f.unit.c_str(),
                    f.target.empty() ? "" : ("target " + f.target + "  ").c_str());
        if (values.size() > 1) std::printf("range %.4g .. %.4g", values.front(), values.back());
        std::printf("\n");
        json.push_back({{"case", c.name},
                        {"figure", f.name},
                        {"value", median},
                        {"min", values.front()},
                        {"max", values.back()},
                        {"runs", values.size()},
                        {"unit", f.unit}});
      }
      std::fflush(stdout);
    }
    if (!any) throw UserError("bench: no case matches the filter (see --list)");
    if (!opt->json.empty()) {
      json_file.write(json_text(json));
      json_file.finish();
    }
  });
}

}  // namespace gs::app
