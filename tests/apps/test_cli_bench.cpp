// `grainshock bench` as a command: repeated runs report the median and range of each figure, and
// bad input is refused in one line. The figures themselves are speeds and are not tested.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <string>

#include "tests/apps/cli_test_util.h"

namespace gs {
namespace {

using test::grainshock;
using test::read_file;
using test::scratch_dir;
namespace fs = std::filesystem;

TEST(CliBench, RepeatReportsTheMedianWithinTheRange) {
  const auto dir = scratch_dir("repeat");
  fs::create_directories(dir);
  const auto json = dir / "bench.json";
  // The PNG case is the quickest: a second a run. Its sizes in bytes do not vary between runs.
  const auto r = grainshock("bench --repeat 3 render/png_1080p --json " + json.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string text = read_file(json);
  const auto rows = nlohmann::json::parse(text);
  ASSERT_TRUE(rows.is_array()) << text;
  int figures = 0;
  for (const auto& row : rows) {
    const std::string name = row.at("figure");
    const double value = row.at("value"), lo = row.at("min"), hi = row.at("max");
    EXPECT_EQ(row.at("case"), "render/png_1080p") << name;
    EXPECT_EQ(row.at("runs"), 3) << name;
    EXPECT_LE(lo, value) << name;
    EXPECT_LE(value, hi) << name;
    if (name.rfind("bytes_", 0) == 0) {
      EXPECT_EQ(lo, hi) << name;
    }
    ++figures;
  }
  EXPECT_EQ(figures, 4) << text;
}

TEST(CliBench, BadInputIsRefusedInOneLineAndKeepsTheJson) {
  const auto dir = scratch_dir("bad");
  fs::create_directories(dir);
  const auto json = dir / "bench.json";
  { std::ofstream(json) << "earlier figures"; }
  for (const char* args : {"--repeat 0 render/png_1080p", "no_such_case", "--frobnicate"}) {
    const auto r = grainshock(std::string("bench ") + args + " --json " + json.string());
    EXPECT_NE(r.exit_code, 0) << args;
    EXPECT_EQ(r.err_lines(), 1) << args << ": " << r.err;
    EXPECT_EQ(read_file(json), "earlier figures") << args;
  }
}

}  // namespace
}  // namespace gs
