// grainshock compare through the binary: PNGs and movies of antialiased discs, one disc moved or
// recoloured, a sub-pixel shift and a high-quality re-encode within tolerance, the diff image,
// --update, and exit codes 0 / 1 / 2.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <optional>

#include "render/image_compare.h"
#include "render/movie_writer.h"
#include "render/png.h"
#include "tests/apps/cli_test_util.h"

namespace gs::test {
namespace {

namespace fs = std::filesystem;
using render::Image;

struct Disc {
  double x, y, r;
  std::uint8_t rgb[3];
};

// 64 discs of radius 6 px on a dark ground, antialiased with 8x8 samples per pixel (the frames of
// a kick at 1.5 to 10 px radius are in tests/render/test_compare_kick.cpp).
std::vector<Disc> scene(double shift = 0) {
  std::vector<Disc> d;
  for (int i = 0; i < 8; ++i)
    for (int j = 0; j < 8; ++j)
      d.push_back({20 + 30.0 * i + shift,
                   20 + 30.0 * j + shift,
                   6,
                   {std::uint8_t(40 + 25 * i), std::uint8_t(200 - 20 * j), std::uint8_t(90)}});
  return d;
}

Image draw(const std::vector<Disc>& discs, int w = 256, int h = 256) {
  Image img(w, h);
  for (int i = 0; i < w * h; ++i) {
    img.rgba[4 * i] = img.rgba[4 * i + 1] = 20;
    img.rgba[4 * i + 2] = 30;
    img.rgba[4 * i + 3] = 255;
  }
  for (const Disc& d : discs)  // the discs do not overlap
    for (int y = std::max(0, int(d.y - d.r) - 1); y <= std::min(h - 1, int(d.y + d.r) + 1); ++y)
      for (int x = std::max(0, int(d.x - d.r) - 1); x <= std::min(w - 1, int(d.x + d.r) + 1); ++x) {
        int inside = 0;
        for (int s = 0; s < 64; ++s)
          inside += std::hypot(x + (s % 8 + 0.5) / 8 - d.x, y + (s / 8 + 0.5) / 8 - d.y) <= d.r;
        std::uint8_t* p = img.pixel(x, y);
        for (int k = 0; k < 3; ++k)
          p[k] = static_cast<std::uint8_t>(std::lround(p[k] + inside / 64.0 * (d.rgb[k] - p[k])));
      }
  return img;
}

std::string png(const fs::path& dir, const std::string& name, const Image& img) {
  fs::create_directories(dir);
  const fs::path p = dir / name;
  render::write_png(p.string(), img);
  return p.string();
}

std::string compare(const std::string& args) {
  return "compare " + args;
}

TEST(CliCompare, IdenticalPicturesAreAlikeWithInfinitePsnr) {
  const fs::path dir = scratch_dir("png");
  const Image img = draw(scene());
  const auto r = grainshock(compare(png(dir, "a.png", img) + " " + png(dir, "b.png", img)));
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out,
            "alike: no pixel off its neighbours' blends by more than 10; largest channel "
            "difference 0, PSNR inf dB, SSIM 1.0000\n");
}

// A twentieth-of-a-pixel shift of every disc changes only rim pixels, by a few levels: what a
// rasterizer update does, and what the rule lets pass.
TEST(CliCompare, SubPixelShiftPasses) {
  const fs::path dir = scratch_dir("png");
  const auto r = grainshock(
      compare(png(dir, "a.png", draw(scene())) + " " + png(dir, "b.png", draw(scene(0.05)))));
  EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("alike: "), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("largest channel difference 0,"), std::string::npos) << r.out;
}

TEST(CliCompare, OneMovedOrRecolouredDiscFailsAndTheDiffMarksIt) {
  const fs::path dir = scratch_dir("png");
  const std::string ref = png(dir, "ref.png", draw(scene()));
  auto moved = scene();
  moved[27].x += 2 * moved[27].r;
  auto recoloured = scene();
  recoloured[27].rgb[0] = 255;
  recoloured[27].rgb[1] = 0;
  for (const auto& [name, discs] :
       {std::pair{"moved", moved}, std::pair{"recoloured", recoloured}}) {
    const fs::path diff = dir / (std::string(name) + ".diff.png");
    const auto r =
        grainshock(compare(ref + " " + png(dir, std::string(name) + ".png", draw(discs)) +
                           " --diff " + diff.string()));
    EXPECT_EQ(r.exit_code, 1) << name << ": " << r.out << r.err;
    EXPECT_EQ(r.out.rfind("not alike: ", 0), 0u) << r.out;
    EXPECT_NE(r.out.find("PSNR "), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("SSIM "), std::string::npos) << r.out;
    // Red where disc 27 was or went, and nowhere far from it.
    const Image d = render::read_png(diff.string());
    long red = 0, red_far = 0;
    for (int y = 0; y < d.height; ++y)
      for (int x = 0; x < d.width; ++x) {
        const std::uint8_t* p = d.pixel(x, y);
        if (p[0] == 255 && p[1] == 0 && p[2] == 0) {
          ++red;
          red_far += std::hypot(x - discs[27].x, y - discs[27].y) > 20;
        }
      }
    EXPECT_GT(red, 5) << name;  // more than one blob may have
    EXPECT_EQ(red_far, 0) << name;
  }
}

TEST(CliCompare, ToleranceAndBlobFlagsMoveTheVerdict) {
  const fs::path dir = scratch_dir("png");
  auto moved = scene();
  moved[27].x += 2 * moved[27].r;
  const std::string args = png(dir, "a.png", draw(scene())) + " " + png(dir, "b.png", draw(moved));
  EXPECT_EQ(grainshock(compare(args)).exit_code, 1);
  EXPECT_EQ(grainshock(compare(args + " --max-blob 1000 --max-mass 1000000")).exit_code, 0);
  EXPECT_EQ(grainshock(compare(args + " --max-blob 1000")).exit_code, 1);
  EXPECT_EQ(grainshock(compare(args + " --tolerance 255")).exit_code, 0);
}

TEST(CliCompare, BadInputExitsTwoInOneLine) {
  const fs::path dir = scratch_dir("bad");
  const std::string a = png(dir, "a.png", draw(scene()));
  const std::string small = png(dir, "small.png", draw(scene(), 128, 128));
  std::ofstream(dir / "text.png") << "not a picture\n";
  for (const std::string& args :
       {a + " " + (dir / "missing.png").string(), a + " " + small,
        a + " " + (dir / "text.png").string(), (dir / "missing.png").string() + " " + a, a,
        a + " " + a + " --tolerance 300"}) {
    const auto r = grainshock(compare(args));
    EXPECT_EQ(r.exit_code, 2) << args << ": " << r.err;
    EXPECT_EQ(r.err_lines(), 1) << args << ": " << r.err;
  }
  EXPECT_NE(grainshock(compare(a + " " + small)).err.find("sizes differ: "), std::string::npos);
}

TEST(CliCompare, UpdateCreatesOrReplacesExpected) {
  const fs::path dir = scratch_dir("update");
  const std::string actual = png(dir, "actual.png", draw(scene()));
  const fs::path expected = dir / "expected.png";
  auto r = grainshock(compare(expected.string() + " " + actual + " --update"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(read_file(expected), read_file(actual));

  auto moved = scene();
  moved[5].y += 12;
  const std::string changed = png(dir, "changed.png", draw(moved));
  EXPECT_EQ(grainshock(compare(expected.string() + " " + changed)).exit_code, 1);
  r = grainshock(compare(expected.string() + " " + changed + " --update"));
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("updated "), std::string::npos) << r.out;
  EXPECT_EQ(read_file(expected), read_file(changed));
}

// Frames 0..n-1 of a scene whose discs drift by a pixel per frame; `edit` changes one frame.
fs::path movie(const fs::path& path, int frames, int crf,
               const std::function<void(int, std::vector<Disc>&)>& edit = {}) {
  render::MovieOptions o;
  o.width = 256;
  o.height = 256;
  o.crf = crf;
  render::MovieWriter w(path, o);
  for (int k = 0; k < frames; ++k) {
    auto discs = scene(k);
    if (edit) edit(k, discs);
    w.add(draw(discs));
  }
  w.finish();
  return path;
}

TEST(CliCompare, MovieReencodedAtHighQualityPasses) {
  if (std::system("command -v ffmpeg >/dev/null") != 0)
    GTEST_SKIP() << "no ffmpeg program to re-encode with (Debian package ffmpeg)";
  const fs::path dir = scratch_dir("movie");
  fs::create_directories(dir);
  const fs::path ref = movie(dir / "ref.mp4", 6, 18), again = dir / "again.mp4";
  // Re-encoded at high quality by the ffmpeg program, as a user would.
  const std::string reencode = "ffmpeg -v error -y -i " + ref.string() +
                               " -c:v libx264 -crf 10 -pix_fmt yuv420p " + again.string();
  ASSERT_EQ(std::system(reencode.c_str()), 0) << reencode;
  const auto r = grainshock(compare(ref.string() + " " + again.string()));
  EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("of 6 compared"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("largest channel difference 0,"), std::string::npos) << r.out;
}

TEST(CliCompare, MovieWithOneChangedFrameOrFewerFramesFails) {
  const fs::path dir = scratch_dir("movie");
  fs::create_directories(dir);
  const fs::path ref = movie(dir / "ref.mp4", 6, 18);
  const fs::path changed = movie(dir / "changed.mp4", 6, 18, [](int k, std::vector<Disc>& d) {
    if (k == 4) d[27].x += 2 * d[27].r;
  });
  const fs::path diff = dir / "diff.png";
  auto r = grainshock(compare(ref.string() + " " + changed.string() + " --diff " + diff.string()));
  EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
  EXPECT_NE(r.out.find("worst frame 4 of 6"), std::string::npos) << r.out;
  EXPECT_EQ(render::read_png(diff.string()).width, 256);

  const fs::path shorter = movie(dir / "shorter.mp4", 5, 18);
  r = grainshock(compare(ref.string() + " " + shorter.string()));
  EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
  EXPECT_NE(r.out.find("6 frames against 5"), std::string::npos) << r.out;

  r = grainshock(compare(ref.string() + " " + diff.string()));
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("is a movie but"), std::string::npos) << r.err;
}

// A 2D periodic box of side `side` holding per_side^2 discs of radius 0.5 on a jittered grid,
// in extended XYZ; disc `moved` shifted by `dx` along x.
fs::path box_of_discs(const fs::path& path, int per_side, double side, int moved, double dx) {
  std::ofstream f(path);
  f << per_side * per_side << "\nLattice=\"" << side << " 0 0 0 " << side
    << " 0 0 0 1\" Properties=species:S:1:pos:R:3 Dim=2 pbc=\"T T F\"\n";
  const double step = side / per_side;
  for (int i = 0; i < per_side * per_side; ++i) {
    const double jitter = 0.2 * step * std::sin(1.7 * i);
    const double x = (i % per_side + 0.5) * step + jitter + (i == moved ? dx : 0);
    f << "A " << x << " " << (i / per_side + 0.5) * step - jitter << " 0\n";
  }
  return path;
}

// A box drawn whole so small that its discs are under a pixel: compare says, in its line, that
// it cannot see one particle move (from the radius `render` records in the PNG's text), and
// says nothing of the kind once the picture is zoomed to discs of several pixels, where the
// same move is not alike.
TEST(CliCompare, SaysWhenDiscsAreTooSmallToSeeOneParticle) {
  const fs::path dir = scratch_dir("blind");
  fs::create_directories(dir);
  // 40 x 40 discs in a box of side 80 drawn whole at 160x120: 0.64 px radius.
  const fs::path a = box_of_discs(dir / "a.xyz", 40, 80, 820, 1.0);
  const fs::path b = box_of_discs(dir / "b.xyz", 40, 80, 820, 0.0);
  const std::string draw = " --color-by none --framing box --width 160 --height 120 --out ";
  for (const char* name : {"a", "b"}) {
    const auto r = grainshock("render " + (dir / name).string() + ".xyz" + draw +
                              (dir / name).string() + ".png");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.err.find("warning: discs of 0."), std::string::npos) << r.err;
  }
  const std::optional<double> px =
      render::disc_radius_of(render::read_png_text((dir / "a.png").string()));
  ASSERT_TRUE(px.has_value());
  EXPECT_GT(*px, 0.6);
  EXPECT_LT(*px, 0.9);
  auto r = grainshock(compare((dir / "a.png").string() + " " + (dir / "b.png").string()));
  EXPECT_NE(r.exit_code, 2) << r.err;
  EXPECT_NE(r.out.find("alike: blind to one particle: both have discs of 0."), std::string::npos)
      << r.out;
  // Against a picture that records discs large enough, only the small one is named.
  render::Image big = render::read_png((dir / "b.png").string());
  render::write_png((dir / "big.png").string(), big, {{render::kDiscRadiusKey, "3"}});
  r = grainshock(compare((dir / "a.png").string() + " " + (dir / "big.png").string()));
  EXPECT_NE(r.out.find("blind to one particle: " + (dir / "a.png").string() + " has discs of 0."),
            std::string::npos)
      << r.out;
  EXPECT_EQ(r.out.find("big.png has"), std::string::npos) << r.out;

  // The same move seen at 3 px radius: not alike, and nothing said of blindness.
  const std::string zoomed = " --color-by none --framing box --centre 41 41 --zoom 4 --width 160 --height 120 "
                             "--out ";
  for (const char* name : {"a", "b"}) {
    const auto z = grainshock("render " + (dir / name).string() + ".xyz" + zoomed +
                              (dir / name).string() + "_zoom.png");
    ASSERT_EQ(z.exit_code, 0) << z.err;
  }
  r = grainshock(compare((dir / "a_zoom.png").string() + " " + (dir / "b_zoom.png").string()));
  EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
  EXPECT_EQ(r.out.find("blind"), std::string::npos) << r.out;
}

}  // namespace
}  // namespace gs::test
