// The CPU half of rendering, without GL: what a scene holds for a snapshot (colour positions,
// the scaled fields and their fixed range, the inset's profile), and the edge-contrast measure.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "render/contrast.h"
#include "render/field.h"
#include "render/follow_camera.h"
#include "render/overlay.h"
#include "render/scene.h"
#include "sim/error.h"
#include "sim/observables.h"

namespace gs::render {
namespace {

OverlayPainter& painter() {
  static OverlayPainter p(Style{}.font);
  return p;
}

// A ring of active discs between radii 20 and 30 moving outward, speed falling linearly from
// `inner` at r = 20 to `outer` at r = 30, around a centre of particles at rest.
Snapshot ring(double inner, double outer) {
  Snapshot s;
  s.info.dim = 2;
  s.info.set_cubic_box(100);
  s.info.time = 50;
  for (int layer = 0; layer <= 10; ++layer) {
    const double r = 20 + layer;
    const double v = inner + (outer - inner) * layer / 10.0;
    const int n = static_cast<int>(2 * std::numbers::pi * r);
    for (int i = 0; i < n; ++i) {
      const double a = 2 * std::numbers::pi * (i + 0.5 * layer) / n;
      const Eigen::Vector3d d(std::cos(a), std::sin(a), 0);
      s.position.push_back(Eigen::Vector3d(50, 50, 0) + r * d);
      s.velocity.push_back(v * d);
      s.radius.push_back(0.5);
      s.active.push_back(1);
    }
  }
  s.position.push_back({50, 50, 0});  // one at rest in the middle: a kick
  s.velocity.push_back(Eigen::Vector3d::Zero());
  s.radius.push_back(0.5);
  s.active.push_back(0);
  return s;
}

View view(int w = 320, int h = 240) {
  View v;
  v.width = w;
  v.height = h;
  return v;
}

double rms_of_active(const Snapshot& s) {
  double sum = 0;
  int n = 0;
  for (std::size_t i = 0; i < s.size(); ++i)
    if (s.active[i]) sum += s.velocity[i].squaredNorm(), ++n;
  return std::sqrt(sum / n);
}

// One speed written to six decimals (a ring of one speed) varies by round-off only: that is one
// colour, not the whole colour map stretched over the noise. A real spread of 1% keeps its range.
TEST(FieldRange, RoundOffSpreadIsOneValueAndARealSpreadIsKept) {
  const std::vector<std::uint8_t> all(3, 1);
  for (Scale scale : {Scale::Linear, Scale::Log}) {
    const auto [lo, hi] = auto_range({0.999999, 1.0, 1.000001}, all, scale, 0, 100);
    EXPECT_LT(normalise(0.999999, {lo, hi}, scale), 0.51);
    EXPECT_GT(normalise(1.000001, {lo, hi}, scale), 0.49);
    EXPECT_GT(hi / lo, 1.05);  // the colour bar's labels can tell its ends apart
    const auto kept = auto_range({0.995, 1.0, 1.005}, all, scale, 0, 100);
    EXPECT_DOUBLE_EQ(kept.first, 0.995);
    EXPECT_DOUBLE_EQ(kept.second, 1.005);
  }
}

// A frame without a time (LAMMPS without ITEM: TIME, HOOMD) is labelled by its step.
TEST(Scene, FramesWithoutTimeAreLabelledByStep) {
  Snapshot s = ring(2, 1);
  Style st;
  EXPECT_EQ(build_scene({&s}, st, view(), painter()).time_text.rfind("t = 50", 0), 0u);
  s.info.has_time = false;
  s.info.step = 500;
  EXPECT_EQ(build_scene({&s}, st, view(), painter()).time_text, "step 500");
  s.info.step.reset();
  EXPECT_EQ(build_scene({&s}, st, view(), painter()).time_text, "");
}

TEST(Scene, ScaledSpeedIsOverTheActiveRmsAndUsesTheFixedRange) {
  const Snapshot s = ring(2, 1);
  EXPECT_EQ(default_field(s), Field::ScaledSpeed) << "a gas with particles at rest is a kick";
  Style st;
  st.field = Field::ScaledSpeed;
  const Scene sc = build_scene({&s}, st, view(), painter());
  const double rms = rms_of_active(s);
  EXPECT_NEAR(sc.v_rms, rms, 1e-12);
  EXPECT_EQ(sc.range, *default_range(Field::ScaledSpeed, 2));
  EXPECT_EQ(sc.bar_label, "v / v_rms");
  EXPECT_NE(sc.bar_note.find("v_rms = "), std::string::npos);
  // Doubling every speed changes v_rms, not one colour: that is what a fixed scaled range buys.
  Snapshot fast = s;
  for (auto& v : fast.velocity) v *= 2;
  const Scene sf = build_scene({&fast}, st, view(), painter());
  ASSERT_EQ(sf.shade.size(), sc.shade.size());
  for (std::size_t i = 0; i < sc.shade.size(); ++i) EXPECT_FLOAT_EQ(sf.shade[i], sc.shade[i]);
  // The innermost disc (speed 2) sits at 2 / rms on the fixed range.
  const auto [lo, hi] = sc.range;
  const double want = std::clamp((2 / rms - lo) / (hi - lo), 0.0, 1.0);
  EXPECT_NEAR(sc.shade.front(), want, 1e-6);
  // Plain speed with --range-per-frame: the percentiles of this frame.
  st.field = Field::Speed;
  st.range_per_frame = true;
  const Scene sp = build_scene({&s}, st, view(), painter());
  EXPECT_NEAR(sp.range.first, 1.0, 0.05);
  EXPECT_NEAR(sp.range.second, 2.0, 0.05);
  EXPECT_TRUE(sp.bar_note.empty());
}

TEST(Scene, AColourBarTitleGivenInTheStyleReplacesTheFieldsAndKeepsTheLogMark) {
  // Fig. 1b of `figures` says the unit of its speeds ("speed |v| / v_0"), which the field's
  // own title cannot know.
  const Snapshot s = ring(2, 1);
  Style st;
  st.field = Field::Speed;
  EXPECT_EQ(build_scene({&s}, st, view(), painter()).bar_label, "speed |v|");
  st.bar_label = "speed |v| / v_0";
  EXPECT_EQ(build_scene({&s}, st, view(), painter()).bar_label, "speed |v| / v_0");
  st.scale = Scale::Log;
  EXPECT_EQ(build_scene({&s}, st, view(), painter()).bar_label, "speed |v| / v_0 (log)");
}

// Before the first collision only the kicked particle moves and none is active: it is drawn,
// at v / v_rms = 1 of its own speed, and the particles at rest are not.
TEST(Scene, TheKickedParticleIsDrawnBeforeTheFirstCollision) {
  Snapshot s = ring(2, 1);
  for (auto& a : s.active) a = 0;
  for (auto& v : s.velocity) v.setZero();
  s.velocity[5] = Eigen::Vector3d(0.6, 0.8, 0);
  Style st;
  st.field = Field::ScaledSpeed;
  const Scene sc = build_scene({&s}, st, view(), painter());
  ASSERT_EQ(sc.sprites.size(), 1u);
  EXPECT_NEAR(sc.v_rms, 1.0, 1e-12);
  const auto [lo, hi] = sc.range;
  EXPECT_NEAR(sc.shade.front(), (1.0 - lo) / (hi - lo), 1e-6);
}

TEST(Scene, ScaledRadialVelocityIsRelativeToTheDrift) {
  Snapshot s = ring(1, 1);
  for (std::size_t i = 0; i < s.size(); ++i)
    if (s.active[i]) s.velocity[i] += Eigen::Vector3d(0.5, 0, 0);  // a common drift
  const auto v = field_values(s, Field::ScaledRadialVelocity);
  double v_rms = 0;
  field_values(s, Field::ScaledSpeed, &v_rms);
  for (std::size_t i = 0; i + 1 < s.size(); ++i) EXPECT_NEAR(v[i], 1 / v_rms, 1e-9);
}

TEST(Scene, InsetProfileHoldsTheBandAndItsScaledSpeeds) {
  const Snapshot s = ring(2, 1);
  Style st;
  st.field = Field::ScaledSpeed;
  st.inset = true;
  const Scene sc = build_scene({&s}, st, view(), painter());
  ASSERT_TRUE(sc.inset);
  const InsetData& d = *sc.inset;
  ASSERT_FALSE(d.r.empty());
  EXPECT_TRUE(d.scaled);
  // Shells inside the ring are empty; in it the scaled speed falls outward from 2 / rms.
  const double rms = rms_of_active(s);
  double first = NAN, last = NAN;
  for (std::size_t b = 0; b < d.r.size(); ++b) {
    if (d.r[b] < 19) {
      EXPECT_EQ(d.density[b], 0) << d.r[b];
    }
    if (std::isfinite(d.speed[b])) {
      if (std::isnan(first)) first = d.speed[b];
      last = d.speed[b];
    }
  }
  EXPECT_NEAR(first, 2 / rms, 0.1 / rms);
  EXPECT_NEAR(last, 1 / rms, 0.1 / rms);
}

// The scene takes the inset's profile from the active particles it copies as it draws them:
// the same numbers as the profile of the snapshot's active subset, and in a 3D slab those of
// the whole shell, culled particles included.
TEST(Scene, InsetProfileIsThatOfEveryActiveParticle) {
  for (int dim : {2, 3}) {
    Snapshot s = ring(2, 1);
    s.info.dim = dim;
    s.info.set_cubic_box(100);
    if (dim == 3)
      for (std::size_t i = 0; i < s.size(); ++i) s.position[i].z() = 50 + (i % 7) * 4.0 - 12;
    Style st;
    st.field = Field::ScaledSpeed;
    st.inset = true;
    View v = view();
    if (dim == 3) v.slab = 2;
    const Scene sc = build_scene({&s}, st, v, painter());
    ASSERT_TRUE(sc.inset);
    const InsetData want = inset_profile(active_subset(s), sc.v_rms);
    EXPECT_EQ(sc.inset->r, want.r);
    EXPECT_EQ(sc.inset->density, want.density);
    for (std::size_t b = 0; b < want.speed.size(); ++b) {
      if (std::isfinite(want.speed[b])) {
        EXPECT_EQ(sc.inset->speed[b], want.speed[b]) << b;
      }
    }
    if (dim == 3) {
      EXPECT_LT(sc.sprites.size(), s.size() - 1);  // the slab culls most of the ring
    }
  }
}

// A translucent panel blends every pixel but leaves those already of its colour as they are,
// which lets fill_rect skip runs of them.
TEST(Scene, TranslucentPanelBlendsEveryPixelNotOfItsColour) {
  Image img(70, 3);
  const Rgb8 panel = {250, 250, 250};
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      std::uint8_t* p = img.pixel(x, y);
      const bool mark = (x == 5 && y == 1) || x == 69;
      p[0] = mark ? 10 : panel[0], p[1] = mark ? 20 : panel[1], p[2] = mark ? 30 : panel[2];
      p[3] = 255;
    }
  fill_rect(img, 0, 0, img.width, img.height, panel, 0.5f);
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      const bool mark = (x == 5 && y == 1) || x == 69;
      const std::uint8_t* p = img.pixel(x, y);
      EXPECT_EQ(p[0], mark ? 130 : 250) << x << "," << y;  // 10 + 0.5 (250 - 10), rounded
      EXPECT_EQ(p[1], mark ? 135 : 250) << x << "," << y;
      EXPECT_EQ(p[2], mark ? 140 : 250) << x << "," << y;
      EXPECT_EQ(p[3], 255);
    }
}

// The following camera is causal: a front that grows, stalls, shrinks and drifts is always in
// view (2D: its box within the half width and the half height the aspect gives), and the view
// never narrows, so the zoom only ever eases outward.
TEST(Scene, FollowCameraKeepsTheFrontInViewAndNeverZoomsIn) {
  for (int dim : {2, 3}) {
    const double aspect = 16.0 / 9, margin = 0.1;
    FollowCamera cam(dim, aspect, margin, 3);
    double last = 0;
    for (int k = 0; k < 60; ++k) {
      const double r = k < 30 ? 2.0 + k : k < 40 ? 32 : 32 - (k - 40) * 0.5;  // grow, stall, shrink
      const Eigen::Vector3d c(100 + 0.7 * k, 50 - 0.3 * k, dim == 3 ? 20.0 : 0.0);
      const Eigen::Vector3d e(r, r, dim == 3 ? r : 0.0);
      const Eigen::AlignedBox3d front(c - e, c + e);
      const Shot s = cam.next(front, r * std::sqrt(double(dim)));
      EXPECT_GE(s.half, last) << k;
      last = s.half;
      const Eigen::Vector3d far = (front.max() - s.centre).cwiseMax(s.centre - front.min());
      if (dim == 2) {
        EXPECT_LE(far.x(), s.half) << k;
        EXPECT_LE(far.y(), s.half / aspect) << k;
      } else {
        EXPECT_LE((c - s.centre).norm() + r * std::sqrt(3.0), s.half) << k;
      }
    }
  }
}

TEST(Scene, MissingDataAndUnknownFieldsNameTheFile) {
  Snapshot s = ring(2, 1);
  s.velocity.clear();
  Style st;
  st.field = Field::ScaledSpeed;
  EXPECT_THROW(build_scene({&s}, st, view(), painter()), UserError);
  try {
    choose_field("speed", s, "a.xyz");
    ADD_FAILURE() << "no velocities";
  } catch (const UserError& e) {
    EXPECT_NE(std::string(e.what()).find("a.xyz"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("no velocities"), std::string::npos) << e.what();
  }
  try {
    choose_field("temperature", ring(2, 1), "b.xyz");
    ADD_FAILURE() << "unknown field";
  } catch (const UserError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("temperature"), std::string::npos) << m;
    EXPECT_NE(m.find("scaled-speed, speed"), std::string::npos) << m;
    EXPECT_EQ(m.find("first-collision"), std::string::npos) << "the ring has no such column";
  }
}

// Points of a ring at pixel radii 40..80 whose colour position falls linearly outward from 1 to
// 0: the inner quarter's mean is 0.875 and the outer quarter's 0.125, so the measure is 0.75.
TEST(EdgeContrast, ReadsTheInnerEdgeOfARing) {
  std::vector<ShadedPoint> pts;
  for (int i = 0; i <= 400; ++i)
    for (int k = 0; k < 360; ++k) {
      const double r = 40 + 40 * i / 400.0, a = 2 * std::numbers::pi * (k + 0.5) / 360;
      pts.push_back({200 + r * std::cos(a), 150 + r * std::sin(a), 1 - i / 400.0});
    }
  EXPECT_NEAR(edge_contrast(pts), 0.75, 0.01);
  for (auto& p : pts) p.t = 1 - p.t;
  EXPECT_NEAR(edge_contrast(pts), -0.75, 0.01);
  for (auto& p : pts) p.t = 0.5;
  EXPECT_NEAR(edge_contrast(pts), 0, 1e-12);
  EXPECT_TRUE(std::isnan(edge_contrast({})));
}

TEST(EdgeContrast, PixelsMapBackToTheirColormapPosition) {
  const Colormap cm = Colormap::by_name("viridis");
  Image img(64, 8);
  for (int x = 0; x < 64; ++x)
    for (int y = 0; y < 8; ++y) {
      const Rgb8 c = x < 56 ? cm.at8(x / 55.0) : Rgb8{255, 255, 255};
      std::copy(c.begin(), c.end(), img.pixel(x, y));
    }
  const auto all = shaded_pixels(img, cm, {});
  EXPECT_EQ(all.size(), 56u * 8) << "the white pixels are background";
  for (const auto& p : all) EXPECT_NEAR(p.t, (p.x - 0.5) / 55.0, 1.0 / 255 + 1e-9);
  const auto some = shaded_pixels(img, cm, {Rect{0, 0, 32, 8}});
  EXPECT_EQ(some.size(), 24u * 8) << "excluded rectangles are left out";
}

// WCAG 2.1 relative luminance of an 8-bit sRGB colour, written out independently of colormap.cpp.
double wcag_luminance(const Rgb8& c) {
  double y = 0;
  const double w[3] = {0.2126, 0.7152, 0.0722};
  for (int k = 0; k < 3; ++k) {
    const double u = c[k] / 255.0;
    y += w[k] * (u <= 0.04045 ? u / 12.92 : std::pow((u + 0.055) / 1.055, 2.4));
  }
  return y;
}

double contrast_ratio(const Rgb8& a, const Rgb8& b) {
  const double x = wcag_luminance(a), y = wcag_luminance(b);
  return (std::max(x, y) + 0.05) / (std::min(x, y) + 0.05);
}

// A picture's colormap keeps the part that stands out from its background by 1.5:1. Grey on white
// has an answer in closed form: luminance 0.65 ((1 + 0.05) / (0.65 + 0.05) = 1.5), the sRGB
// value 1.055 * 0.65^(1 / 2.4) - 0.055 = 0.830; the tolerance is the search's step (1/1020) plus
// the 8-bit rounding of the grey levels around it.
TEST(PictureColormap, KeepsThePartThatStandsOutFromTheBackground) {
  const Rgb8 white = palette(Background::Light).background;
  const Rgb8 dark = palette(Background::Dark).background;
  const auto grey = Colormap::by_name("grey").against(white).span();
  EXPECT_EQ(grey.first, 0);
  EXPECT_NEAR(grey.second, 1.055 * std::pow(0.65, 1 / 2.4) - 0.055, 1.0 / 1020 + 1.0 / 255);
  for (const std::string name : {"magma", "viridis", "inferno"})
    for (const Rgb8 bg : {white, dark}) {
      Style st;
      st.colormap = name;
      st.background = bg == white ? Background::Light : Background::Dark;
      const Colormap c = picture_colormap(st);
      const auto [lo, hi] = c.span();
      EXPECT_LT(lo, hi) << name;
      EXPECT_GE(contrast_ratio(c.at8(0), bg), 1.49) << name << " low end";
      EXPECT_GE(contrast_ratio(c.at8(1), bg), 1.49) << name << " high end";
      // Just beyond a cut end, the full map no longer stands out.
      const Colormap full = Colormap::by_name(name);
      if (lo > 0) {
        EXPECT_LT(contrast_ratio(full.at8(lo - 0.01), bg), 1.5) << name;
      }
      if (hi < 1) {
        EXPECT_LT(contrast_ratio(full.at8(hi + 0.01), bg), 1.5) << name;
      }
    }
  // Magma's cream end is cut on white, its black end on the dark background.
  Style magma;
  EXPECT_NEAR(picture_colormap(magma).span().second, 0.88, 0.02);
  EXPECT_EQ(picture_colormap(magma).span().first, 0);
  magma.background = Background::Dark;
  EXPECT_EQ(picture_colormap(magma).span().second, 1);
  EXPECT_NEAR(picture_colormap(magma).span().first, 0.23, 0.02);
}

}  // namespace
}  // namespace gs::render
