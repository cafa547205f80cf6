// A movie's following camera at a small size keeps the front off the colour
// bar and leaves a free border around it, as a still does. Frames of a real 2D kick are aimed
// as the movie's frame loop aims them (make_plan, make_follow, scan, aim) and every drawn disc's
// pixels are checked against the colour bar's panel and the border.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>

#include "jobs/frame_loop.h"
#include "jobs/movie_plan.h"
#include "render/overlay.h"
#include "render/scene.h"
#include "sim/engine.h"

namespace gs::jobs {
namespace {

struct Worst {
  double into_bar = -1e9;  // largest overlap of a disc's pixels with the colour bar's panel
  double border = 1e9;     // smallest distance of a disc's pixels from the open area's edge
};

// Measures one frame: the discs' pixel boxes against the panel on the right and the edges of the
// part of the picture the panel leaves free.
Worst measure(const render::Scene& sc, int bar_px) {
  Worst w;
  const render::Camera& c = sc.camera;
  const double ppu = c.pixels_per_unit();
  const double right_edge = c.width - bar_px;
  for (const auto& s : sc.sprites) {
    const double x = c.width / 2.0 + s.x * ppu, y = c.height / 2.0 - s.y * ppu, r = s.r * ppu;
    w.into_bar = std::max(w.into_bar, x + r - right_edge);
    w.border = std::min({w.border, x - r, right_edge - (x + r), y - r, c.height - (y + r)});
  }
  return w;
}

Worst worst_over_a_kick(int width, int height) {
  PhysicsConfig c;
  c.dim = 2;
  c.particles = 40000;
  c.restitution = 0.8;
  c.seed = 5;
  c.kick_site = KickSite::Centre;
  c.t_max = 4000;
  auto sim = make_simulation(c);

  FrontMovieOptions o;
  o.movie.width = width;
  o.movie.height = height;
  MoviePlan p = make_plan(o);
  p.style.field = render::Field::ScaledSpeed;  // what "auto" picks for a kick
  settle_range(p, 2);
  render::OverlayPainter painter(p.style.font);
  std::optional<render::FollowCamera> follow;
  render::View view = p.view;
  Worst worst;
  Snapshot snap;
  for (int k = 1; k <= 16; ++k) {
    sim->run_until(250.0 * k);
    sim->snapshot(snap);
    const FrameScan f = scan(snap, p.style, false);
    if (!follow) follow.emplace(make_follow(2, view, o));
    aim(view, follow->next(f.front, f.radius), 2);
    const render::Scene sc = render::build_scene({&snap}, p.style, view, painter);
    EXPECT_GT(sc.sprites.size(), 0u) << "frame " << k;
    const int bar = painter.colorbar_width(width, height, sc.range, p.style.scale, sc.bar_label,
                                           sc.bar_note);
    EXPECT_GT(bar, 0);
    const Worst w = measure(sc, bar);
    worst.into_bar = std::max(worst.into_bar, w.into_bar);
    worst.border = std::min(worst.border, w.border);
  }
  return worst;
}

// The free border a still of the same front has: View::margin of the front's larger extent,
// which is about a seventh of the shorter half side when the front fills it. A quarter of that
// share of the height is asked for: the camera's centre lags the front by design.
TEST(FollowFraming, SmallMovieKeepsTheFrontOffTheColourBarAndAwayFromTheEdges) {
  const Worst w = worst_over_a_kick(640, 360);
  EXPECT_LT(w.into_bar, 0) << "a disc reaches " << w.into_bar << " px into the colour bar";
  EXPECT_GE(w.border, 0.04 * 360) << "a disc comes within " << w.border << " px of the edge";
}

TEST(FollowFraming, FullHdMovieKeepsTheSameBorder) {
  const Worst w = worst_over_a_kick(1920, 1080);
  EXPECT_LT(w.into_bar, 0) << "a disc reaches " << w.into_bar << " px into the colour bar";
  EXPECT_GE(w.border, 0.04 * 1080) << "a disc comes within " << w.border << " px of the edge";
}

// A square frame: the round front is as wide as the picture allows, so only the reserve keeps
// the colour bar off it.
TEST(FollowFraming, SquareMovieKeepsTheFrontOffTheColourBar) {
  const Worst w = worst_over_a_kick(360, 360);
  EXPECT_LT(w.into_bar, 0) << "a disc reaches " << w.into_bar << " px into the colour bar";
  EXPECT_GE(w.border, 0.04 * 360) << "a disc comes within " << w.border << " px of the edge";
}

}  // namespace
}  // namespace gs::jobs
