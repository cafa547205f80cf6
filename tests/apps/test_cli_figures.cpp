// Smoke test of `grainshock figures` at the seconds-long --tiny size: every promised file is
// written and summary.json carries the comparisons other tools read. The numbers of a tiny run
// are not physics; their values are not tested here.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <thread>

#include "analysis/json.h"
#include "analysis/table.h"
#include "tests/apps/cli_test_util.h"

namespace gs {
namespace {

using test::grainshock;
using test::read_file;
using test::scratch_dir;
namespace fs = std::filesystem;

bool is_png(const fs::path& p) {
  const std::string s = read_file(p);
  return s.size() > 1000 && s.compare(0, 8, "\x89PNG\r\n\x1a\n") == 0;
}

// Every file name the text mentions (a word ending .csv, .png, .json, .gp, .md) exists in `dir`
// or in a case's folder, <case> standing for d2_r0.1; prints the missing ones.
bool names_only_existing_files(const std::string& text, const fs::path& dir) {
  const std::regex name(R"([A-Za-z0-9_<>.-]+\.(csv|png|json|gp|md))");
  bool ok = true;
  for (auto it = std::sregex_iterator(text.begin(), text.end(), name); it != std::sregex_iterator();
       ++it) {
    std::string file = it->str();
    if (file.starts_with(".")) continue;  // ".gp script": a kind of file, not a name
    if (const auto c = file.find("<case>"); c != std::string::npos) file.replace(c, 6, "d2_r0.1");
    if (fs::exists(dir / file) || fs::exists(dir / "ensembles" / "d2_r0.1" / file)) continue;
    ADD_FAILURE() << "names " << it->str() << ", which is not in " << dir;
    ok = false;
  }
  return ok;
}

// What the figures show, read from their scripts and CSVs (no pixels): one time unit, the
// paper's, on every axis; Fig. 3's curves shifted apart with a theory line each; Fig. 6 without
// key entries for sets that have no point, showing the phi1 reading the verdict uses; Fig. 8's
// y-ranges on the scale of an exponent, not of the first collisions' noise.
void expect_figure_scripts_as_drawn(const fs::path& dir) {
  for (const auto& f : fs::directory_iterator(dir)) {
    if (f.path().extension() != ".gp") continue;
    const std::string gp = read_file(f.path());
    EXPECT_EQ(gp.find("simulation units"), std::string::npos) << f.path().filename();
    if (gp.find("set xlabel 't") != std::string::npos) {
      EXPECT_NE(gp.find("paper units"), std::string::npos) << f.path().filename();
    }
    if (f.path().filename().string().starts_with("fig8_local_slopes_")) {
      // The panels of ensemble means are on an exponent's scale. The kicked particle's (x, v,
      // C_kick) are one particle's per realisation, whose slope swings by units in a tiny run:
      // their range must hold the slope's theory line instead.
      const std::regex panel(
          R"(set title '([^']*)'\n[^\n]*\nset yrange \[([-0-9.e]+):([-0-9.e]+)\]\n(?:set label[^\n]*\n)?(?:plot [^\n]*?, ([-0-9.e]+) with lines)?)");
      int ranges = 0;
      for (auto it = std::sregex_iterator(gp.begin(), gp.end(), panel);
           it != std::sregex_iterator(); ++it, ++ranges) {
        const double lo = std::stod((*it)[2]), hi = std::stod((*it)[3]);
        if ((*it)[1].str().find("kick") == std::string::npos) {
          EXPECT_LT(hi - lo, 4) << f.path().filename() << " " << it->str();
        } else if ((*it)[4].matched) {
          const double theory = std::stod((*it)[4]);
          EXPECT_TRUE(lo < theory && theory < hi) << f.path().filename() << " " << it->str();
        }
      }
      EXPECT_GT(ranges, 0) << f.path().filename();
    }
  }
  {  // Fig. 3: six curves (r = 0.1, 0.5, 0.8 in 2D and 3D), each a decade apart, each with its
     // theory line, where one line per dimension hung on the r = 0.1 curve's last point.
    const std::string gp = read_file(dir / "fig3_active_energy.gp");
    std::set<std::string> shifts;
    const std::regex shift(R"(:\(\$5\*(1e\d)\))");
    for (auto it = std::sregex_iterator(gp.begin(), gp.end(), shift); it != std::sregex_iterator();
         ++it)
      shifts.insert((*it)[1]);
    EXPECT_EQ(shifts.size(), 6u);
    for (int k = 0; k < 6; ++k)
      EXPECT_NE(gp.find(std::string("N") + std::to_string(k) + "(x) with lines"), std::string::npos)
          << k;
  }
  {  // Fig. 6: every set of points drawn has a row in the CSV, and panel (b) names the value of
     // the counted phi1 row of summary.json in each dimension.
    const std::string gp = read_file(dir / "fig6_crossover.gp");
    const Table t = read_csv(dir / "fig6_crossover.csv");
    const std::regex set(R"(\(\$1==(\d+) \? \$3 : 1/0\))");
    for (auto it = std::sregex_iterator(gp.begin(), gp.end(), set); it != std::sregex_iterator();
         ++it) {
      const double k = std::stod((*it)[1]);
      EXPECT_NE(std::count(t.column("set").begin(), t.column("set").end(), k), 0)
          << "a key entry for set " << k << ", which has no point";
    }
    const Json j = Json::parse(read_file(dir / "summary.json"));
    int declared = 0;
    for (const Json& c : j.at("comparisons"))
      if (c.at("quantity") == "phi1 (E_t/E_0 collapse, the two largest r)" &&
          c.at("measured").is_number()) {
        char value[32];
        std::snprintf(value, sizeof value, "%.3g", c.at("measured").get<double>());
        EXPECT_NE(gp.find(std::string("d = ") + std::to_string(c.at("d").get<int>()) +
                          ", declared (the verdict): φ_1 = " + value),
                  std::string::npos)
            << c.dump();
        ++declared;
      }
    EXPECT_GT(declared, 0);
  }
}

TEST(CliFigures, TinyRunWritesEveryPromisedFile) {
  // A folder whose name has a quote and a space: gnuplot runs without a shell.
  const auto dir = scratch_dir("it's tiny");
  const auto r = grainshock("figures --tiny --threads 2 --quiet --format png,svg --out \"" +
                            dir.string() + "\"");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* png : {"fig1a_overlay_r0.1.png", "fig1b_elastic_r1.png"})
    EXPECT_TRUE(is_png(dir / png)) << png;
  for (const char* base :
       {"fig2_anisotropy", "fig3_active_energy", "fig4_collapse_2d", "fig5_collapse_3d",
        "fig6_crossover", "fig7_tc2_delta", "fig8_local_slopes_d2_r0.1",
        "fig8_local_slopes_d3_r1_large", "fig9_packing", "fig10_energy_fraction_times",
        "fig12_inner_edge"}) {
    const std::string b(base);
    EXPECT_TRUE(is_png(dir / (b + ".png"))) << b;
    EXPECT_NE(read_file(dir / (b + ".svg")).find("<svg"), std::string::npos) << b;
    EXPECT_TRUE(fs::exists(dir / (b + ".csv"))) << b;
    // The script draws from the CSV beside it, so that a user can restyle the plot.
    const std::string gp = read_file(dir / (b + ".gp"));
    EXPECT_NE(gp.find(b + ".csv"), std::string::npos) << b;
    EXPECT_NE(gp.find(b + ".png"), std::string::npos) << b;
  }
  // The snowplow figure, from one CSV per 3D r < 1 case, and its section of the report.
  EXPECT_TRUE(is_png(dir / "fig11_snowplow_3d.png"));
  EXPECT_TRUE(fs::exists(dir / "fig11_snowplow_3d_d3_r0.1.csv"));
  EXPECT_NE(read_file(dir / "report.md").find("## The snowplow question"), std::string::npos);
  EXPECT_NE(read_file(dir / "report.md").find("### Where the runs end"), std::string::npos);
  // Greek letters as symbols, not words.
  EXPECT_NE(read_file(dir / "fig4_collapse_2d.gp").find("α"), std::string::npos);
  EXPECT_EQ(read_file(dir / "fig4_collapse_2d.gp").find("alpha"), std::string::npos);
  for (const char* c : {"d2_r0.1", "d2_r0.3", "d2_r0.5", "d2_r0.7", "d2_r0.8", "d2_r0.9", "d2_r1",
                        "d3_r0.1", "d3_r0.5", "d3_r0.8", "d3_r1", "d3_r1_large"})
    EXPECT_TRUE(fs::exists(dir / "ensembles" / c / "timeseries_mean.csv")) << c;

  const std::string summary = read_file(dir / "summary.json");
  ASSERT_NE(summary.find("\"comparisons\""), std::string::npos);
  for (const char* key : {"\"quantity\"", "\"d\"", "\"r\"", "\"measured\"", "\"sigma_stat\"",
                          "\"sigma_sys\"", "\"z\"", "\"role\"", "\"theory\"", "\"agrees\"",
                          "\"wall_seconds\"", "\"figure\""})
    EXPECT_NE(summary.find(key), std::string::npos) << key;
  for (const char* q : {"exponent of R_t",
                        "exponent of N_t",
                        "exponent of E_t",
                        "exponent of R_front",
                        "exponent of P_r",
                        "exponent of P_r/N_t",
                        "exponent of C_t",
                        "v_rms^2 = 2E/N (identity)",
                        "phi1",
                        "phi2",
                        "band packing (typical, cells of 10)",
                        "band number density (typical, cells of 10)",
                        "alpha best collapsing P(R,t)",
                        "alpha best collapsing P(v,t)",
                        "A(t) constant: d ln A / d ln t, last half decade",
                        "band packing (upper, 90% quantile)",
                        "band packing (densest cell, shifted grids)",
                        "band packing (local, 90% quantile)",
                        "band number density (shell peak, no pi/4)",
                        "shell peak density / ambient",
                        "A(t_max) -> 0: against an isotropic cloud's (angle-shuffled)"})
    EXPECT_NE(summary.find(std::string("\"") + q + "\""), std::string::npos) << q;
  // One reading per number: the small d3_r1's alpha rows are superseded by d3_r1_large's and
  // not counted; t_c2 is a crossover only where the delta scan puts it inside the run.
  const Json j = Json::parse(summary);
  int superseded = 0, large = 0;
  for (const Json& c : j.at("comparisons")) {
    if (!c.at("quantity").get<std::string>().starts_with("exponent of")) continue;
    if (c.at("case") == "d3_r1") {
      EXPECT_FALSE(c.at("counted").get<bool>()) << c.dump();
      ++superseded;
    }
    if (c.at("case") == "d3_r1_large" && c.at("counted").get<bool>()) ++large;
  }
  EXPECT_GT(superseded, 0);
  EXPECT_GT(large, 0);
  for (const Json& c : j.at("cases")) {
    const bool scan = c.at("name").get<std::string>().find("_delta") != std::string::npos;
    if (!scan) {
      EXPECT_TRUE(c.at("t_c2").is_null()) << c.dump();
    }
    EXPECT_EQ(c.at("superseded_for_alpha").get<bool>(), c.at("name") == "d3_r1") << c.dump();
  }
  // Figs. 4 and 5 in the paper's time unit, said on the axes: the CSV's t_paper is t v_0 n^(1/d)
  // (n = 0.25) and its scaled columns use it, the x-range is set from the data, and the error
  // bars are the CSV's standard errors (columns 5 and 8).
  for (const auto& [base, d] :
       {std::pair{"fig4_collapse_2d", 2}, std::pair{"fig5_collapse_3d", 3}}) {
    const Table t = read_csv(dir / (std::string(base) + ".csv"));
    ASSERT_GT(t.rows(), 0u) << base;
    const double a = 1.0 / (d + 1);
    for (std::size_t i = 0; i < t.rows(); ++i) {
      const double tp = t.column("t")[i] * std::pow(0.25, 1.0 / d);
      EXPECT_NEAR(t.column("t_paper")[i], tp, 1e-9 * tp) << base;
      EXPECT_GE(t.column("f1_sem")[i], 0) << base;
      EXPECT_GE(t.column("f2_sem")[i], 0) << base;
      if (i == 1) {  // x_R = R t_paper^-alpha: against distributions_mean.csv's R
        const Table m = read_csv(dir / "ensembles" / (d == 2 ? "d2_r0.1" : "d3_r0.1") /
                                 "distributions_mean.csv");
        EXPECT_NEAR(t.column("x_R")[i], m.column("R")[i] * std::pow(tp, -a), 1e-9) << base;
      }
    }
    const std::string gp = read_file(dir / (std::string(base) + ".gp"));
    EXPECT_NE(gp.find("R t^{-" + std::string(d == 2 ? "1/3" : "1/4") + "} (t in paper units)"),
              std::string::npos)
        << base;
    EXPECT_NE(gp.find("} (t in paper units)'\nset ylabel 't^{-"), std::string::npos) << base;
    EXPECT_EQ(gp.find("set xrange [*"), std::string::npos) << base;
    EXPECT_NE(gp.find(":4:5 with yerrorlines"), std::string::npos) << base;
    EXPECT_NE(gp.find(":8 with yerrorlines"), std::string::npos) << base;
  }
  // Fig. 2's A(t) on log axes; Fig. 3's 2D and 3D curves share no colour.
  EXPECT_NE(read_file(dir / "fig2_anisotropy.gp").find("set logscale xy"), std::string::npos);
  {
    const std::string gp = read_file(dir / "fig3_active_energy.gp");
    std::set<std::string> colours[2];
    const std::regex curve(R"(\$1==([23]) && \$2==[0-9.]+ \? \$4 : 1/0\):\(\$[57]\*1e\d\) lc (\d+))");
    for (auto it = std::sregex_iterator(gp.begin(), gp.end(), curve); it != std::sregex_iterator();
         ++it)
      colours[(*it)[1] == "2" ? 0 : 1].insert((*it)[2]);
    EXPECT_FALSE(colours[0].empty());
    EXPECT_FALSE(colours[1].empty());
    for (const auto& c : colours[0]) EXPECT_EQ(colours[1].count(c), 0u) << "lc " << c;
  }

  expect_figure_scripts_as_drawn(dir);
  const std::string report = read_file(dir / "report.md");
  EXPECT_TRUE(names_only_existing_files(report, dir)) << "report.md";
  // Every script ran to its end: a gnuplot error (a quote in a title) leaves a panel out of a
  // PNG that is still written.
  EXPECT_EQ(report.find("- problem: "), std::string::npos)
      << report.substr(report.find("- problem: "));
  for (const char* q : {"exponent of R_t", "phi1", "band packing", "Definitions", "declared reading",
                        "Rankine-Hugoniot", "fig8_local_slopes_d2_r0.1.png", "## Summary",
                        "numbers compared", "Sensitivity", "Plateaus and their drift",
                        "corrected b", "Checks and reported numbers", "The snowplow question",
                        "agree within 2 sigma"})
    EXPECT_NE(report.find(q), std::string::npos) << q;

  // The realisations stay, so that a newer build fits them again without running any: report.md
  // removed, resume reads them back and writes the same report but for the wall times (its first
  // lines and the table of runs).
  fs::remove(dir / "report.md");
  const auto again = grainshock("resume --quiet \"" + dir.string() + "\"");
  ASSERT_EQ(again.exit_code, 0) << again.err;
  const auto timeless = [](const std::string& text) {
    const auto summary = text.find("## Summary"), runs = text.find("## Runs"),
               measured = text.find("## Measured against the paper");
    if (summary > runs || runs > measured || measured == std::string::npos) return text;
    return text.substr(summary, runs - summary) + text.substr(measured);
  };
  EXPECT_EQ(timeless(read_file(dir / "report.md")), timeless(report));
  EXPECT_NE(read_file(dir / "ensembles/d3_r0.1/timing.json").find("\"realisations_run\": 0"),
            std::string::npos);
}

TEST(CliFigures, TinyLimitJoinsThePhi1TablesFromTheUnboundedMedium) {
  // --limit's cases scaled down: r = 0.9 and 0.95 in the unbounded medium, their own ensemble
  // folders and slope figures, and the phi1 readings between neighbouring r running on to 0.95
  // in both dimensions (the tiny paper plan stops at 0.9), 0.9 read from the *_limit case.
  const auto dir = scratch_dir("limit");
  const auto r =
      grainshock("figures --tiny --limit --threads 2 --quiet --format png --out " + dir.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* c : {"d2_r0.9_limit", "d2_r0.95_limit", "d3_r0.9_limit", "d3_r0.95_limit"}) {
    const std::string toml = read_file(dir / "ensembles" / c / "ensemble.toml");
    EXPECT_NE(toml.find("medium = \"unbounded\""), std::string::npos) << c << "\n" << toml;
    EXPECT_TRUE(is_png(dir / ("fig8_local_slopes_" + std::string(c) + ".png"))) << c;
  }
  const std::string report = read_file(dir / "report.md");
  for (const char* row : {"| 2 | r = 0.9 and r = 0.95 |", "| 3 | r = 0.9 and r = 0.95 |",
                          "| 3 | r = 0.85 and r = 0.9 |"})
    EXPECT_NE(report.find(row), std::string::npos) << row;
  // One reading per neighbouring pair: r = 0.9 once in 3D (the limit case in the paper case's
  // place), not twice.
  EXPECT_EQ(report.find("| 3 | r = 0.9 and r = 0.9 |"), std::string::npos);
  // The answer's table: the declared reading nearest the limit, weighed, in each dimension.
  for (const char* row : {"| 2 | E_t/E_0 collapse (declared) | r = 0.9 and r = 0.95 |",
                          "| 3 | E_t/E_0 collapse (declared) | r = 0.9 and r = 0.95 |"})
    EXPECT_NE(report.find(row), std::string::npos) << row;
}

TEST(CliFigures, EstimateTimesEveryStageOfTheJob) {
  // --estimate runs the job on a sample and times each stage: the cases, the phi1/phi2
  // readings, and Fig. 1 with the plots; its CPU total is their sum, and it leaves no figures.
  // --limit's cases are sampled to a shorter time and their cost extrapolated to t_max.
  const auto dir = scratch_dir("estimate");
  // Into the folder of a job's results with --force: the estimate replaces only its own files.
  fs::create_directories(dir / "ensembles" / "d2_r0.1");
  { std::ofstream(dir / "summary.json") << "results\n"; }
  const auto r = grainshock(
      "figures --tiny --limit --estimate --sample 1 --threads 2 --quiet "
      "--force --out " +
      dir.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(read_file(dir / "summary.json"), "results\n");
  EXPECT_TRUE(fs::is_directory(dir / "ensembles" / "d2_r0.1"));
  const Json j = Json::parse(read_file(dir / "estimate.json"));
  double sum =
      j.at("readings_cpu_seconds").get<double>() + j.at("figures_cpu_seconds").get<double>();
  EXPECT_GT(j.at("figures_cpu_seconds").get<double>(), 0);  // Fig. 1's runs, gnuplot
  int shortened = 0;
  for (const Json& c : j.at("cases")) {
    EXPECT_GT(c.at("cpu_seconds_per_realisation").get<double>(), 0) << c.dump();
    sum += c.at("estimated_cpu_seconds").get<double>();
    if (c.at("sample_t_max").get<double>() == c.at("t_max").get<double>()) continue;
    ++shortened;
    EXPECT_TRUE(c.at("case").get<std::string>().ends_with("_limit")) << c.dump();
    EXPECT_LT(c.at("sample_t_max").get<double>(), c.at("t_max").get<double>()) << c.dump();
    EXPECT_GE(c.at("collision_growth").get<double>(), 0.5) << c.dump();
  }
  EXPECT_EQ(shortened, 4);
  EXPECT_EQ(j.at("cases").size(), 27u);  // every case of the tiny plan (3 at the paper's delta for
                                          // the packing), and --limit's 4
  EXPECT_NEAR(j.at("estimated_cpu_seconds").get<double>(), sum, 1e-9 * sum);
  // On 2 threads the realisations share the cores; the serial stages do not.
  EXPECT_LE(j.at("estimated_wall_seconds_from_cpu").get<double>(),
            j.at("estimated_cpu_seconds").get<double>());
  const std::string md = read_file(dir / "estimate.md");
  for (const char* q : {"Fig. 1", "phi1 and phi2 readings", "CPU-s", "quiet 2-core machine"})
    EXPECT_NE(md.find(q), std::string::npos) << q;
  EXPECT_FALSE(fs::exists(dir / "estimate_sample"));
  EXPECT_FALSE(fs::exists(dir / "report.md"));
}

// A killed job whose figures.toml was edited since (here its seed) is refused naming the setting
// that changed, not blamed on "another version of grainshock".
TEST(CliFigures, AnEditedSettingOfAnUnfinishedJobIsNamed) {
  const auto dir = scratch_dir("edited");
  const pid_t pid = test::spawn_grainshock("figures --tiny --threads 1 --out " + dir.string());
  ASSERT_GT(pid, 0);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  auto started = [&] {
    std::error_code ec;
    for (const auto& e : fs::recursive_directory_iterator(dir / "ensembles", ec))
      if (e.path().filename() == "case.toml") return true;
    return false;
  };
  while (!started() && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  ::kill(pid, SIGKILL);
  int status = 0;
  ::waitpid(pid, &status, 0);
  ASSERT_FALSE(fs::exists(dir / "report.md")) << "the job finished before the kill";
  std::string settings = read_file(dir / "figures.toml");
  const auto at = settings.find("\nseed = ");
  ASSERT_NE(at, std::string::npos) << settings;
  settings.replace(at, settings.find('\n', at + 1) - at, "\nseed = 4242");
  std::ofstream(dir / "figures.toml") << settings;
  const auto r = grainshock("resume --quiet " + dir.string());
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_EQ(r.err_lines(), 1) << r.err;
  EXPECT_NE(r.err.find("now plan 'seed = 4242'"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("another version"), std::string::npos) << r.err;
}

TEST(CliFigures, BadInputIsRefusedInOneLine) {
  const auto dir = scratch_dir("bad");
  auto r = grainshock("figures --tiny --full --out " + dir.string());
  EXPECT_NE(r.exit_code, 0);
  EXPECT_EQ(r.err_lines(), 1) << r.err;
  EXPECT_FALSE(fs::exists(dir));
  r = grainshock("figures --tiny --format png,gif --out " + dir.string());
  EXPECT_NE(r.exit_code, 0);
  EXPECT_EQ(r.err_lines(), 1) << r.err;
  EXPECT_NE(r.err.find("--format"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir));
  r = grainshock("figures --tiny --threads 0 --out " + dir.string());
  EXPECT_NE(r.exit_code, 0);
  EXPECT_EQ(r.err_lines(), 1) << r.err;
  EXPECT_FALSE(fs::exists(dir));
  for (const char* limit : {"--limit --limit-dim 4", "--limit-dim 2"}) {
    r = grainshock(std::string("figures --tiny ") + limit + " --out " + dir.string());
    EXPECT_EQ(r.exit_code, 2) << limit;
    EXPECT_EQ(r.err_lines(), 1) << r.err;
    EXPECT_NE(r.err.find("--limit-dim"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir));
  }
  fs::create_directories(dir);
  { std::ofstream(dir / "keep.txt") << "mine"; }
  r = grainshock("figures --tiny --out " + dir.string());
  EXPECT_NE(r.exit_code, 0);
  EXPECT_EQ(r.err_lines(), 1) << r.err;
  EXPECT_EQ(read_file(dir / "keep.txt"), "mine");
  EXPECT_FALSE(fs::exists(dir / "summary.json"));
}

}  // namespace
}  // namespace gs
