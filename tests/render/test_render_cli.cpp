// `grainshock render` as a user meets it: the built binary, real files, exit codes, stderr.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>

#include "render/png.h"
#include "tests/apps/cli_test_util.h"
#include "render/image_compare.h"

namespace gs {
namespace {

namespace fs = std::filesystem;

using Result = test::CommandResult;

// One folder per test: ctest runs tests in parallel, and they must not share files.
fs::path dir() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const fs::path d = fs::path(GRAINSHOCK_TEST_OUTPUT_DIR) / "render_cli" / info->name();
  fs::create_directories(d);
  return d;
}

Result run(const std::string& args, const std::string& env = "") {
  return test::grainshock("render " + args, env);
}

std::string write(const std::string& name, const std::string& text) {
  const fs::path p = dir() / name;
  std::ofstream(p) << text;
  return p.string();
}

const std::string kHeader =
    "Lattice=\"20 0 0 0 20 0 0 0 20\" "
    "Properties=species:S:1:pos:R:3:velo:R:3:radius:R:1:active:I:1 "
    "Time=12.5 pbc=\"T T T\" Dim=2 Density=0.25 Restitution=0.1 Cutoff=0.0001 Speed=1 Seed=42\n";

std::string good_snapshot() {
  return write(
      "good.xyz",
      "3\n" + kHeader + "X 1 1 0 0.1 0 0 0.5 1\nX 3 1 0 0.5 0 0 0.5 1\nX 5 2 0 0 0 0 0.5 0\n");
}

// No PNG and no temporary file of one may be left in the folder after a failure.
bool no_png_left(const fs::path& png) {
  for (const auto& e : fs::directory_iterator(png.parent_path()))
    if (e.path().filename().string().rfind(png.filename().string(), 0) == 0) return false;
  return true;
}

void expect_one_line_error(const std::string& args, const std::string& needle,
                           const std::string& env = "") {
  const fs::path png = dir() / "out.png";
  fs::remove(png);
  const Result r = run(args + " --out " + png.string(), env);
  EXPECT_NE(r.exit_code, 0) << args;
  EXPECT_EQ(r.err_lines(), 1) << args << ": " << r.err;
  EXPECT_EQ(r.err.rfind("grainshock: error: ", 0), 0u) << r.err;
  EXPECT_NE(r.err.find(needle), std::string::npos) << "expected '" << needle << "' in: " << r.err;
  EXPECT_TRUE(no_png_left(png)) << args;
}

TEST(RenderCli, WritesPngWithTextChunks) {
  const fs::path png = dir() / "good.png";
  fs::remove(png);
  const Result r = run(good_snapshot() + " --width 200 --height 150 --out " + png.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(r.err.empty()) << r.err;
  const render::Image img = render::read_png(png.string());
  EXPECT_EQ(img.width, 200);
  EXPECT_EQ(img.height, 150);
  std::map<std::string, std::string> text;
  for (const auto& [k, v] : render::read_png_text(png.string())) text[k] = v;
  EXPECT_EQ(text["Time"], "12.5");
  EXPECT_EQ(text["Dim"], "2");
  EXPECT_EQ(text["N"], "3");
  EXPECT_EQ(text["Restitution"], "0.1");
  EXPECT_EQ(std::stod(text["Cutoff"]), 1e-4);
  EXPECT_EQ(text["Seed"], "42");
}

TEST(RenderCli, BadInputGivesOneLineAndNoPng) {
  const std::string good = good_snapshot();
  expect_one_line_error((dir() / "missing.xyz").string(), "missing.xyz");
  expect_one_line_error(write("truncated.xyz", "3\n" + kHeader + "X 1 1 0 0.1 0 0 0.5 1\n"),
                        "truncated");
  expect_one_line_error(
      write("malformed.xyz", "2\n" + kHeader + "X 1 1 0 0.1 0 0 0.5 1\nX 1 one 0 0 0 0 0.5 1\n"),
      "line 4");
  expect_one_line_error(
      write("no_velocity.xyz", "1\nProperties=species:S:1:pos:R:3 Dim=2\nX 1 1 0\n") +
          " --color-by speed",
      "no velocities");
  expect_one_line_error(good + " --width 0", "size");
  expect_one_line_error(good + " --height -5", "size");
  expect_one_line_error(good + " --width 16385", "size");
  expect_one_line_error(good + " --colormap jet", "jet");
  expect_one_line_error(good + " --range 1 1", "MIN");
  expect_one_line_error(good + " --range 2 1", "MIN");
  // Mesa refuses a 3.3 core context when told the driver only has 2.1.
  expect_one_line_error(good + " --gl osmesa", "context", "MESA_GL_VERSION_OVERRIDE=2.1");
}

TEST(RenderCli, UnwritableOutputLeavesNothing) {
  const fs::path png = dir() / "no_such_folder" / "out.png";
  const Result r = run(good_snapshot() + " --out " + png.string());
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find("cannot write PNG"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(png.parent_path()));
}

// EGL surfaceless serves the same renderer; where it works, its picture matches OSMesa's.
TEST(RenderCli, EglMatchesOsmesaWhereAvailable) {
  const fs::path a = dir() / "osmesa.png", b = dir() / "egl.png";
  const std::string args = good_snapshot() + " --width 160 --height 120 ";
  ASSERT_EQ(run(args + "--gl osmesa --out " + a.string()).exit_code, 0);
  const Result r = run(args + "--gl egl --out " + b.string());
  if (r.exit_code != 0) GTEST_SKIP() << "no EGL here: " << r.err;
  const auto c = render::compare_images(render::read_png(b.string()), render::read_png(a.string()));
  EXPECT_TRUE(c.match()) << c.differing << " pixels differ";
}

}  // namespace
}  // namespace gs
