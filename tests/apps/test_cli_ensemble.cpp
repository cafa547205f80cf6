// The contract of `grainshock ensemble` and `grainshock merge`: results independent of the thread
// count and of how the ensemble was split; bad input refused in one line with nothing written.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "analysis/table.h"
#include "tests/apps/cli_test_util.h"

namespace gs {
namespace {

using test::grainshock;
using test::read_file;
using test::scratch_dir;
namespace fs = std::filesystem;

// Small enough for a fraction of a second per realisation, long enough for a band to form.
const std::string kPhysics = "--particles 6000 --restitution 0.5 --t-max 1500 --quiet";
const std::vector<std::string> kFiles = {"ensemble.toml", "timeseries_mean.csv",
                                         "distributions_mean.csv", "snapshot_scalars_mean.csv",
                                         "summary.json"};

void expect_same_files(const fs::path& a, const fs::path& b) {
  for (const auto& f : kFiles) {
    ASSERT_TRUE(fs::exists(a / f)) << a / f;
    ASSERT_TRUE(fs::exists(b / f)) << b / f;
    EXPECT_EQ(read_file(a / f), read_file(b / f)) << f;
  }
}

TEST(CliEnsemble, ThreadCountDoesNotChangeTheBytes) {
  const auto one = scratch_dir("k1"), two = scratch_dir("k2"), other = scratch_dir("seed2");
  auto r =
      grainshock("ensemble " + kPhysics + " --realisations 4 --threads 1 --out " + one.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = grainshock("ensemble " + kPhysics + " --realisations 4 --threads 2 --out " + two.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  expect_same_files(one, two);
  // The comparison can fail: another master seed gives other numbers.
  r = grainshock("ensemble " + kPhysics + " --realisations 4 --threads 2 --seed 2 --out " +
                 other.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(read_file(one / "timeseries_mean.csv"), read_file(other / "timeseries_mean.csv"));
  EXPECT_NE(read_file(one / "distributions_mean.csv"), read_file(other / "distributions_mean.csv"));
}

TEST(CliEnsemble, MergeOfSplitJobsEqualsTheOneShotEnsemble) {
  const auto whole = scratch_dir("whole"), a = scratch_dir("a"), b = scratch_dir("b"),
             merged = scratch_dir("merged");
  ASSERT_EQ(
      grainshock("ensemble " + kPhysics + " --realisations 5 --threads 2 --out " + whole.string())
          .exit_code,
      0);
  auto r = grainshock("ensemble " + kPhysics +
                      " --realisations 2 --threads 1 --per-realisation --out " + a.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = grainshock("ensemble " + kPhysics +
                 " --realisation 2 --realisations 3 --threads 2 --per-realisation --out " +
                 b.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // Folders in either order.
  r = grainshock("merge --quiet " + b.string() + " " + a.string() + " --out " + merged.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  expect_same_files(whole, merged);
  // A part alone is not the whole.
  const auto part = scratch_dir("part");
  ASSERT_EQ(grainshock("merge --quiet " + a.string() + " --out " + part.string()).exit_code, 0);
  EXPECT_NE(read_file(whole / "timeseries_mean.csv"), read_file(part / "timeseries_mean.csv"));
}

TEST(CliEnsemble, DistributionsAreNormalisedAndSummaryHasTheFits) {
  const auto dir = scratch_dir("norm");
  auto r =
      grainshock("ensemble " + kPhysics + " --realisations 3 --threads 2 --out " + dir.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Table d = read_csv(dir / "distributions_mean.csv");
  const Table s = read_csv(dir / "snapshot_scalars_mean.csv");
  ASSERT_EQ(s.rows(), 3u);  // default snapshot times t-max/4, /2, 1
  for (std::size_t k = 0; k < s.rows(); ++k) {
    const double t = s.column("t")[k];
    double pr = 0, pv = 0, width_r = 0, width_v = 0;
    std::size_t bins = 0;
    for (std::size_t i = 0; i < d.rows(); ++i) {
      if (d.column("t")[i] != t) continue;
      ++bins;
      pr += d.column("P_R")[i];
      pv += d.column("P_v")[i];
      if (d.column("bin")[i] == 1) {  // uniform bins: centre spacing is the width
        width_r = d.column("R")[i] - d.column("R")[i - 1];
        width_v = d.column("v")[i] - d.column("v")[i - 1];
      }
    }
    ASSERT_GT(bins, 1u);
    // Each realisation's histogram integrates to its fraction inside the range; so does the mean.
    EXPECT_NEAR(pr * width_r, 1 - s.column("R_outside_fraction")[k], 1e-9) << "t = " << t;
    EXPECT_NEAR(pv * width_v, 1 - s.column("v_outside_fraction")[k], 1e-9) << "t = " << t;
  }
  const std::string summary = read_file(dir / "summary.json");
  for (const char* key : {"\"exponents\"", "\"N_t\"", "\"E_t\"", "\"R_t\"", "\"v_t\"", "\"ci_lo\"",
                          "\"t_c1\"", "\"collapse_quality_radius\"", "\"packing_typical\"",
                          "\"packing_upper\"", "\"anisotropy_last\""})
    EXPECT_NE(summary.find(key), std::string::npos) << key;
}

// One line on stderr, a non-zero exit, and the output folder as it was.
void expect_refused(const std::string& args, const fs::path& out, const std::string& before) {
  const auto r = grainshock(args);
  EXPECT_NE(r.exit_code, 0) << args;
  EXPECT_EQ(r.err_lines(), 1) << args << "\n" << r.err;
  if (before.empty())
    EXPECT_FALSE(fs::exists(out)) << args;
  else
    EXPECT_EQ(read_file(out / "summary.json"), before) << args;
}

TEST(CliEnsemble, BadInputIsRefusedInOneLineAndWritesNothing) {
  const auto out = scratch_dir("out");
  const std::string to = " --out " + out.string();
  expect_refused("ensemble " + kPhysics + " --realisations 0" + to, out, "");
  expect_refused("ensemble " + kPhysics + " --realisations -2" + to, out, "");
  expect_refused("ensemble " + kPhysics + " --threads 0" + to, out, "");
  expect_refused("ensemble " + kPhysics + " --window 2000,5000" + to, out, "");  // beyond t-max
  expect_refused("ensemble " + kPhysics + " --window 0.001,100" + to, out, "");  // before the grid
  expect_refused("ensemble " + kPhysics + " --window 800,400" + to, out, "");    // reversed

  // Merging folders of different physics.
  const auto a = scratch_dir("a"), b = scratch_dir("b"), c = scratch_dir("c");
  ASSERT_EQ(
      grainshock("ensemble " + kPhysics + " --realisations 2 --per-realisation --out " + a.string())
          .exit_code,
      0);
  ASSERT_EQ(grainshock("ensemble --particles 6000 --restitution 0.8 --t-max 1500 --quiet "
                       "--realisation 2 --realisations 2 --per-realisation --out " +
                       b.string())
                .exit_code,
            0);
  expect_refused("merge " + a.string() + " " + b.string() + to, out, "");
  // The same realisations twice, and a folder without per-realisation data.
  expect_refused("merge " + a.string() + " " + a.string() + to, out, "");
  ASSERT_EQ(grainshock("ensemble " + kPhysics + " --realisations 2 --out " + c.string()).exit_code,
            0);
  expect_refused("merge " + c.string() + to, out, "");

  // An existing output folder is left alone.
  const std::string before = read_file(a / "summary.json");
  expect_refused("ensemble " + kPhysics + " --realisations 1 --out " + a.string(), a, before);
  expect_refused("merge " + a.string() + " --out " + a.string(), a, before);
}

}  // namespace
}  // namespace gs
