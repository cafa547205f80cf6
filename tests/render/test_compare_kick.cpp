// The comparison rule of render/image_compare.h on real frames of a kick drawn by our renderer,
// at 640x480, 1920x1080 and 3840x2160 with discs of 1.5 and 10 px radius: one particle moved by
// a diameter, one recoloured by a tenth of the colour range, a changed or a missing label must
// differ; every particle shifted by a third of a pixel, and a movie re-encoded at CRF 12, must
// not. Each case also goes through `grainshock compare`, whose line the test prints.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>

#include "render/colormap.h"
#include "render/field.h"
#include "render/image_compare.h"
#include "render/movie_reader.h"
#include "render/movie_writer.h"
#include "render/png.h"
#include "render/renderer.h"
#include "render/scene.h"
#include "sim/engine.h"
#include "sim/error.h"
#include "tests/apps/cli_test_util.h"

namespace gs::render {
namespace {

namespace fs = std::filesystem;

Renderer& renderer() {
  static Renderer r;
  return r;
}

// A small 2D kick at three times (t_paper = 250, 500, 1000), the last the one compared.
const std::vector<Snapshot>& kicks() {
  static const std::vector<Snapshot> s = [] {
    PhysicsConfig c;
    c.dim = 2;
    c.particles = 10000;
    c.seed = 5;
    c.t_max = 2000;
    auto sim = make_simulation(c);
    std::vector<Snapshot> out;
    for (double t : {500.0, 1000.0, 2000.0}) {
      sim->run_until(t);
      out.push_back(sim->snapshot());
    }
    return out;
  }();
  return s;
}
const Snapshot& kick() { return kicks().back(); }

Style kick_style() {
  Style st;
  st.field = default_field(kick());
  return st;
}

// Centred on the band (the active particle farthest along +x, 3 diameters in), zoomed so that
// discs have `radius_px`; nothing in it depends on the particles' positions, so a shifted
// snapshot is drawn with the same camera.
View kick_view(int w, int h, double radius_px) {
  const Snapshot& s = kick();
  View v;
  v.width = w;
  v.height = h;
  std::size_t far = 0;
  for (std::size_t i = 0; i < s.size(); ++i)
    if (s.active[i] && s.position[i].x() > s.position[far].x()) far = i;
  v.centre = s.position[far] - Eigen::Vector3d(3, 0, 0);
  renderer().render(s, kick_style(), v);
  v.zoom = 2 * radius_px / renderer().last().camera.pixels_per_unit();
  return v;
}

// The active particle nearest the picture's centre: inside the band.
std::size_t central(const Snapshot& s, const View& v) {
  std::size_t best = 0;
  for (std::size_t i = 0; i < s.size(); ++i)
    if (s.active[i] && (s.position[i] - *v.centre).norm() < (s.position[best] - *v.centre).norm())
      best = i;
  return best;
}

// One particle's v/v_rms moved by a tenth of the colour range, the one (of those near the centre)
// whose colour moves least for it; the other active particles are slowed by a factor of
// 1 - O(1e-5) so that v_rms, printed beside the colour bar, stays the same.
Snapshot recoloured(const Snapshot& s, const View& v, double ppu) {
  const Style st = kick_style();
  renderer().render(s, st, v);
  const auto [lo, hi] = renderer().last().range;
  const double v_rms = renderer().last().v_rms;
  const Colormap cm = picture_colormap(st);
  std::size_t pick = s.size();
  int least = 256;
  double factor = 1;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (!s.active[i] || (s.position[i] - *v.centre).norm() > 0.3 * v.height / ppu) continue;
    const double u = s.velocity[i].norm() / v_rms, t = (u - lo) / (hi - lo);
    if (t < 0 || t > 1) continue;
    const double t2 = t + 0.1 <= 1 ? t + 0.1 : t - 0.1;
    const Rgb8 a = cm.at8(t), b = cm.at8(t2);
    const int d = std::max({std::abs(a[0] - b[0]), std::abs(a[1] - b[1]), std::abs(a[2] - b[2])});
    if (d < least) least = d, pick = i, factor = (lo + t2 * (hi - lo)) / u;
  }
  GS_CHECK(pick < s.size());
  Snapshot r = s;
  const double before = r.velocity[pick].squaredNorm();
  r.velocity[pick] *= factor;
  double others = 0;
  for (std::size_t i = 0; i < s.size(); ++i)
    if (s.active[i] && i != pick) others += s.velocity[i].squaredNorm();
  const double k = std::sqrt((others + before - r.velocity[pick].squaredNorm()) / others);
  for (std::size_t i = 0; i < s.size(); ++i)
    if (s.active[i] && i != pick) r.velocity[i] *= k;
  return r;
}

// Writes both pictures and runs `grainshock compare` on them; prints the command and its line.
test::CommandResult compare_command(const std::string& name, const Image& expected,
                                    const Image& actual) {
  const fs::path dir = test::scratch_dir(name);
  fs::create_directories(dir);
  const std::string e = (dir / "expected.png").string(), a = (dir / (name + ".png")).string();
  write_png(e, expected, {}, 1);  // fast: a 3840x2160 picture at level 6 takes a second
  write_png(a, actual, {}, 1);
  const auto r = test::grainshock("compare " + e + " " + a);
  std::printf("grainshock compare expected.png %s.png (%dx%d)\n  %s", name.c_str(), actual.width,
              actual.height, r.out.c_str());
  return r;
}

void expect_alike(const std::string& name, const Image& expected, const Image& actual) {
  const ImageComparison c = compare_images(expected, actual);
  EXPECT_TRUE(c.match()) << name << ": blob of " << c.largest.pixels << " px, mass "
                         << c.largest.mass << " at " << c.largest.x0 << "," << c.largest.y0;
  const auto r = compare_command(name, expected, actual);
  EXPECT_EQ(r.exit_code, 0) << name << ": " << r.out << r.err;
}

void expect_not_alike(const std::string& name, const Image& expected, const Image& actual) {
  const ImageComparison c = compare_images(expected, actual);
  EXPECT_FALSE(c.match()) << name << ": blob of " << c.largest.pixels << " px, mass "
                          << c.largest.mass;
  const auto r = compare_command(name, expected, actual);
  EXPECT_EQ(r.exit_code, 1) << name << ": " << r.out << r.err;
  EXPECT_EQ(r.out.rfind("not alike: worst blob ", 0), 0u) << r.out;
}

struct Case {
  int width, height;
  double radius_px;
};

class CompareKick : public ::testing::TestWithParam<Case> {};

std::string tag(const Case& c) {
  return std::to_string(c.width) + "x" + std::to_string(c.height) + "_r" +
         std::to_string(static_cast<int>(10 * c.radius_px));
}

// What a new Mesa or LLVM does to the rims, at its worst: every disc drawn a third of a pixel
// (and a fifth, across) away from where it was.
TEST_P(CompareKick, SubPixelShiftOfEveryParticleIsAlike) {
  const Case k = GetParam();
  const View v = kick_view(k.width, k.height, k.radius_px);
  const Image ref = renderer().render(kick(), kick_style(), v);
  const double ppu = renderer().last().camera.pixels_per_unit();
  ASSERT_NEAR(0.5 * ppu, k.radius_px, 1e-6);
  Snapshot shifted = kick();
  for (auto& p : shifted.position) p += Eigen::Vector3d(0.3, 0.2, 0) / ppu;
  const Image img = renderer().render(shifted, kick_style(), v);
  ASSERT_GT(compare_images(ref, img).max_channel_difference, 60) << "the shift changes the rims";
  expect_alike("shifted_" + tag(k), ref, img);
}

TEST_P(CompareKick, OneParticleMovedByADiameterIsNotAlike) {
  const Case k = GetParam();
  const View v = kick_view(k.width, k.height, k.radius_px);
  const Image ref = renderer().render(kick(), kick_style(), v);
  Snapshot moved = kick();
  const std::size_t i = central(moved, v);
  moved.position[i].x() += 2 * moved.radius[i];
  expect_not_alike("moved_" + tag(k), ref, renderer().render(moved, kick_style(), v));
}

TEST_P(CompareKick, OneParticleRecolouredByATenthOfTheRangeIsNotAlike) {
  const Case k = GetParam();
  const View v = kick_view(k.width, k.height, k.radius_px);
  const Image ref = renderer().render(kick(), kick_style(), v);
  const Snapshot r = recoloured(kick(), v, renderer().last().camera.pixels_per_unit());
  expect_not_alike("recoloured_" + tag(k), ref, renderer().render(r, kick_style(), v));
}

INSTANTIATE_TEST_SUITE_P(Sizes, CompareKick,
                         ::testing::Values(Case{640, 480, 1.5}, Case{640, 480, 10},
                                           Case{1920, 1080, 1.5}, Case{1920, 1080, 10},
                                           Case{3840, 2160, 1.5}, Case{3840, 2160, 10}),
                         [](const auto& info) { return tag(info.param); });

class CompareKickLabel : public ::testing::TestWithParam<Case> {};

// The default picture (fitted, discs of whatever size the fit gives): the time label's
// t_paper = 1000 against 1004 ('0' becomes '4', and t = 2000 becomes 2008), and no label.
TEST_P(CompareKickLabel, ChangedOrMissingLabelIsNotAlike) {
  const Case k = GetParam();
  View v;
  v.width = k.width;
  v.height = k.height;
  const Image ref = renderer().render(kick(), kick_style(), v);
  Snapshot later = kick();
  later.info.time += 8;
  expect_not_alike("label_changed_" + tag(k), ref, renderer().render(later, kick_style(), v));
  Style bare = kick_style();
  bare.time_label = false;
  expect_not_alike("label_missing_" + tag(k), ref, renderer().render(kick(), bare, v));
}

INSTANTIATE_TEST_SUITE_P(Sizes, CompareKickLabel,
                         ::testing::Values(Case{640, 480, 0}, Case{1920, 1080, 0},
                                           Case{3840, 2160, 0}),
                         [](const auto& info) { return tag(info.param); });

// Three frames of the kick at 640x480 (discs of about 1.8 px radius) as `movie` encodes them
// (CRF 18), then the same movie re-encoded by ffmpeg at CRF 12, and one with a particle moved
// in the middle frame.
fs::path kick_movie(const fs::path& path, bool move_one) {
  MovieOptions o;
  o.width = 640;
  o.height = 480;
  MovieWriter w(path, o);
  View v;
  v.width = o.width;
  v.height = o.height;
  v.centre = kick().position[central(kick(), kick_view(640, 480, 2))];
  for (std::size_t f = 0; f < kicks().size(); ++f) {
    Snapshot s = kicks()[f];
    if (move_one && f == 1) {
      const std::size_t i = central(s, v);
      s.position[i].x() += 2 * s.radius[i];
    }
    w.add(renderer().render(s, kick_style(), v));
  }
  w.finish();
  return path;
}

TEST(CompareKickMovie, ReencodedAtCrf12IsAlikeAndAMovedParticleIsNot) {
  if (std::system("command -v ffmpeg >/dev/null") != 0)
    GTEST_SKIP() << "no ffmpeg program to re-encode with (Debian package ffmpeg)";
  const fs::path dir = test::scratch_dir("movie");
  fs::create_directories(dir);
  const fs::path ref = kick_movie(dir / "kick.mp4", false);
  const fs::path again = dir / "kick_crf12.mp4";
  const std::string reencode = "ffmpeg -v error -y -i " + ref.string() +
                               " -c:v libx264 -crf 12 -pix_fmt yuv420p " + again.string();
  ASSERT_EQ(std::system(reencode.c_str()), 0) << reencode;
  auto r = test::grainshock("compare " + ref.string() + " " + again.string());
  std::printf("grainshock compare kick.mp4 kick_crf12.mp4\n  %s", r.out.c_str());
  EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("of 3 compared"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("largest channel difference 0,"), std::string::npos) << r.out;

  const fs::path moved = kick_movie(dir / "kick_moved.mp4", true);
  r = test::grainshock("compare " + ref.string() + " " + moved.string());
  std::printf("grainshock compare kick.mp4 kick_moved.mp4\n  %s", r.out.c_str());
  EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
  EXPECT_NE(r.out.find("worst frame 1 of 3"), std::string::npos) << r.out;
}

}  // namespace
}  // namespace gs::render
