// A colour must mean one speed throughout and a following camera must never lose the front, so
// both need the whole run ahead of time. Runs are reproducible from (config, seed), so a first,
// picture-less pass over the same trajectory finds the colour range and the camera path; the
// second pass renders. The first pass is skipped when neither is needed (a fixed range and a
// fixed camera).
#include "apps/front_movie.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "apps/progress.h"
#include "render/camera.h"
#include "render/field.h"
#include "render/png.h"
#include "render/renderer.h"
#include "sim/engine.h"
#include "sim/error.h"
#include "sim/format.h"
#include "sim/stop.h"

namespace gs::app {
namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

std::vector<double> frame_times(const PhysicsConfig& physics, const FrontMovieOptions& o) {
  const int n = o.frames;
  const double t_max = physics.t_max;
  if (n < 1) throw UserError("--frames must be at least 1 (got " + std::to_string(n) + ")");
  // Bounded before anything is allocated: a million frames is a nine-hour movie at 30 fps.
  if (n > 1000000)
    throw UserError("--frames " + std::to_string(n) + ": too many frames (at most 1000000)");
  std::vector<double> t(n);
  if (o.spacing == "lin") {
    for (int k = 0; k < n; ++k) t[k] = t_max * (k + 1) / n;
  } else if (o.spacing == "log") {
    if (!(o.t_start > 0 && o.t_start < t_max))
      throw UserError("--t-start " + format_number(o.t_start) + " must be in (0, --t-max " +
                      format_number(t_max) + ") for --frame-spacing log");
    for (int k = 0; k < n; ++k)
      t[k] = n == 1 ? t_max : o.t_start * std::pow(t_max / o.t_start, double(k) / (n - 1));
    t.back() = t_max;
  } else {
    throw UserError("unknown --frame-spacing '" + o.spacing + "' (use lin or log)");
  }
  // Frames closer than the clock can tell apart would repeat the same picture.
  for (int k = 1; k < n; ++k)
    if (!(t[k] - t[k - 1] > 1e-9 * t[k]))
      throw UserError("--frames " + std::to_string(n) + ": more frames than the run can give (" +
                      format_number(t[k - 1]) + " and " + format_number(t[k]) +
                      " are not distinct times); use fewer frames or a longer --t-max");
  return t;
}

// Advances to each frame time in slices that depend only on the times, so that both passes see
// the same trajectory, and a stop request is noticed within a fraction of a second. Returns
// false if stopped.
template <class Visit>
bool for_each_frame(Simulation& sim, const std::vector<double>& times, Progress& progress,
                    const char* pass, Visit visit) {
  const auto t0 = std::chrono::steady_clock::now();
  for (std::size_t k = 0; k < times.size(); ++k) {
    while (sim.time() < times[k]) {
      sim.run_until(std::min(times[k], sim.time() + std::max(1.0, 0.01 * sim.time())));
      if (stop_requested()) return false;
    }
    visit(k);
    char what[160];
    std::snprintf(what, sizeof what, "%s: frame %zu of %zu, t = %.4g, %.3g events/s", pass, k + 1,
                  times.size(), times[k],
                  double(sim.stats().events) / std::max(1e-9, seconds_since(t0)));
    progress.update(double(k + 1) / times.size(), what);
    if (stop_requested()) return false;
  }
  return true;
}

// What the first pass learns about one frame: the colour range of its particles, where the
// front is (unwrapped), and the box the renderer's fitted framing will use.
struct FrameScan {
  bool any_active = false;
  std::pair<double, double> range{0, 1};
  Eigen::AlignedBox3d front;  // active particles, else the moving ones (the kicked particle)
  double radius = 0;          // of the sphere about front.center() holding the same particles
  Eigen::AlignedBox3d fit;    // the renderer's rule: active particles, else all
};

FrameScan scan(const Snapshot& s, const render::Style& style, bool with_range) {
  FrameScan f;
  f.any_active = std::find(s.active.begin(), s.active.end(), 1) != s.active.end();
  auto in_front = [&](std::size_t i) {
    return f.any_active ? s.active[i] != 0 : s.has_velocity() && s.velocity[i].squaredNorm() > 0;
  };
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (in_front(i)) f.front.extend(s.position[i]);
    if (s.active[i] || !f.any_active) f.fit.extend(s.position[i]);
  }
  if (f.front.isEmpty()) f.front.extend(s.info.origin + s.info.box / 2);
  for (std::size_t i = 0; i < s.size(); ++i)
    if (in_front(i)) f.radius = std::max(f.radius, (s.position[i] - f.front.center()).norm());
  if (f.any_active && with_range) {
    const auto values = render::field_values(s, style.field);
    f.range = render::auto_range(values, s.active, style.scale, style.percentile_low,
                                 style.percentile_high);
  }
  return f;
}

// The union of the frames' robust ranges: no frame's bulk is clamped, one colour is one value.
std::pair<double, double> fixed_range(const std::vector<FrameScan>& frames, render::Scale scale) {
  double lo = INFINITY, hi = -INFINITY;
  for (const auto& f : frames)
    if (f.any_active) lo = std::min(lo, f.range.first), hi = std::max(hi, f.range.second);
  if (!(lo < hi)) return scale == render::Scale::Log ? std::pair{0.1, 1.0} : std::pair{0.0, 1.0};
  return {lo, hi};
}

// A following camera: centres are a moving average of the front's centre; the visible size is
// the running maximum of what each frame needs, averaged over the frames ahead. The running
// maximum never shrinks and the average ahead is never below it, so the front always fits and
// the zoom only ever eases outward.
struct Shot {
  Eigen::Vector3d centre;
  double half = 1;  // 2D: half the visible width; 3D: radius of the sphere to frame
};

std::vector<Shot> camera_path(const std::vector<FrameScan>& frames, int dim, double aspect,
                              double margin, int window) {
  const int n = static_cast<int>(frames.size());
  std::vector<Eigen::Vector3d> raw(n);
  for (int k = 0; k < n; ++k) raw[k] = frames[k].front.center();
  std::vector<Shot> shots(n);
  for (int k = 0; k < n; ++k) {
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
    const int a = std::max(0, k - window), b = std::min(n - 1, k + window);
    for (int j = a; j <= b; ++j) c += raw[j];
    shots[k].centre = c / (b - a + 1);
  }
  // At least 12 diameters across the shorter side, so the first collisions are not a blur.
  const double min_half = dim == 3 ? 6 : 6 * std::max(1.0, aspect);
  std::vector<double> need(n);
  for (int k = 0; k < n; ++k) {
    const auto& box = frames[k].front;
    const Eigen::Vector3d c = shots[k].centre;
    const Eigen::Vector3d reach =
        (box.max() - c).cwiseMax(c - box.min()) + Eigen::Vector3d::Constant(0.5);
    const double pad = 1 + margin;
    const double sphere = frames[k].radius + (box.center() - c).norm() + 0.5;
    double h = dim == 3 ? sphere * pad : std::max(reach.x() * pad, reach.y() * pad * aspect);
    need[k] = std::max(h, min_half);
  }
  for (int k = 1; k < n; ++k) need[k] = std::max(need[k], need[k - 1]);
  for (int k = 0; k < n; ++k) {
    const int b = std::min(n - 1, k + window);
    double sum = 0;
    for (int j = k; j <= b; ++j) sum += need[j];
    shots[k].half = sum / (b - k + 1);
  }
  return shots;
}

// Points the renderer's view at a shot. 2D: the zoom that turns the renderer's fitted framing of
// this frame into the shot's width; 3D: an explicit camera distance.
void aim(render::View& view, const Shot& shot, const Snapshot& s, const FrameScan& f) {
  view.centre = shot.centre;
  if (s.info.dim == 3) {
    const double tan_y = std::tan(view.fov * std::numbers::pi / 360);
    const double tan_x = tan_y * view.width / view.height;
    view.distance = shot.half / std::sin(std::atan(std::min(tan_x, tan_y)));
    view.zoom = 1;
    return;
  }
  render::View fitted = view;
  fitted.zoom = 1;
  double r_max = 0;
  for (double r : s.radius) r_max = std::max(r_max, r);
  const render::Camera base = render::make_camera_2d(f.fit, r_max, fitted);
  view.zoom = base.half_w / shot.half;
}

// Everything the options decide, checked (UserError naming the flag) before anything is made.
struct Plan {
  std::vector<double> times;
  render::Style style;
  render::View view;
  bool follow = true;
  render::Backend backend = render::Backend::Auto;
};

Plan make_plan(const PhysicsConfig& physics, const FrontMovieOptions& o) {
  Plan p;
  p.times = frame_times(physics, o);
  render::Style& style = p.style;
  render::View& view = p.view;
  style.colormap = o.colormap;
  if (o.colour_by == "auto")
    style.field =
        physics.initial == Initial::Kick ? render::Field::ScaledSpeed : render::Field::Speed;
  else
    style.field = render::parse_field(o.colour_by);
  style.background = render::parse_background(o.background);
  style.scale = render::parse_scale(o.scale, style.field);
  if (!o.range.empty()) style.range = std::pair{o.range[0], o.range[1]};
  if (!o.range.empty() && o.range_per_frame)
    throw UserError("--range and --range-per-frame exclude each other");
  style.range_per_frame = o.range_per_frame;
  style.inset = o.inset;
  style.show_inactive = o.show_inactive;
  render::check_style(style);
  render::check_size(o.movie.width, o.movie.height, 16384);
  view.width = o.movie.width;
  view.height = o.movie.height;
  view.slab = o.slab;
  view.azimuth = o.azimuth;
  view.elevation = o.elevation;
  const bool follow = p.follow = o.camera == "follow";
  if (!follow && o.camera != "fixed")
    throw UserError("unknown --camera '" + o.camera + "' (use follow or fixed)");
  view.framing = follow ? render::Framing::Fit : render::Framing::Box;
  if (o.slab < 0) throw UserError("--slab must be >= 0");
  p.backend = render::parse_backend(o.backend);
  render::check_movie_options(o.movie);
  return p;
}

}  // namespace

void check_front_movie(const PhysicsConfig& physics, const FrontMovieOptions& o) {
  make_plan(physics, o);
}

FrontMovieResult write_front_movie(const PhysicsConfig& physics, const FrontMovieOptions& o,
                                   const std::filesystem::path& dir) {
  Plan plan = make_plan(physics, o);
  const std::vector<double>& times = plan.times;
  render::Style& style = plan.style;
  render::View& view = plan.view;
  const bool follow = plan.follow;
  if (o.keep_frames) std::filesystem::create_directories(dir / "frames");
  // Opened now so that an unwritable folder is reported before any work.
  render::MovieWriter movie(dir / "movie.mp4", o.movie);
  render::Renderer renderer(plan.backend);
  install_stop_handlers();

  std::vector<FrameScan> scans;
  std::vector<Shot> shots;
  Snapshot snap;  // reused frame after frame
  bool stopped = false;
  // The colour range over all frames needs the first pass only for a field without a fixed one.
  const bool need_range =
      !style.range && !style.range_per_frame && !render::default_range(style.field, physics.dim);
  if (need_range || follow) {
    auto sim = make_simulation(physics);
    Progress progress(o.quiet);
    scans.reserve(times.size());
    stopped =
        !for_each_frame(*sim, times, progress, "pass 1 of 2 (range, camera)", [&](std::size_t) {
          sim->snapshot(snap);
          scans.push_back(scan(snap, style, need_range));
        });
    progress.done();
    if (!stopped) {
      if (need_range) style.range = fixed_range(scans, style.scale);
      if (follow)
        shots = camera_path(scans, physics.dim, double(view.width) / view.height, view.margin,
                            std::max(1, static_cast<int>(o.movie.fps / 2)));
    }
  }

  double sim_s = 0, render_s = 0, encode_s = 0, png_s = 0;
  if (!stopped) {
    auto sim = make_simulation(physics);
    Progress progress(o.quiet);
    auto clock = std::chrono::steady_clock::now();
    stopped = !for_each_frame(*sim, times, progress,
                              shots.empty() ? "movie" : "pass 2 of 2 (movie)", [&](std::size_t k) {
                                sim_s += seconds_since(clock);
                                auto t0 = std::chrono::steady_clock::now();
                                sim->snapshot(snap);
                                if (follow) aim(view, shots[k], snap, scans[k]);
                                render::Image img = renderer.render(snap, style, view);
                                render_s += seconds_since(t0);
                                if (o.keep_frames) {
                                  t0 = std::chrono::steady_clock::now();
                                  char name[32];
                                  std::snprintf(name, sizeof name, "frame_%05zu.png", k);
                                  render::write_png((dir / "frames" / name).string(), img,
                                                    render::png_text(snap.info, snap.size()));
                                  png_s += seconds_since(t0);
                                }
                                t0 = std::chrono::steady_clock::now();
                                movie.add(std::move(img));
                                encode_s += seconds_since(t0);
                                clock = std::chrono::steady_clock::now();
                              });
    progress.done();
  }

  const auto t0 = std::chrono::steady_clock::now();
  const auto written = movie.frames_added();
  if (written > 0)
    movie.finish();
  else
    movie.discard();  // a movie without a frame would only pretend to be one
  encode_s += seconds_since(t0);
  if (!o.quiet) {
    if (written > 0) {
      char pngs[48] = "";
      if (o.keep_frames) std::snprintf(pngs, sizeof pngs, ", write PNGs %.3g s", png_s);
      std::fprintf(stderr,
                   "grainshock: %s: %lld frames (%s, %dx%d) in %s; simulate %.3g s, render %.3g s, "
                   "wait for the encoder %.3g s%s\n",
                   stopped ? "interrupted" : "finished", static_cast<long long>(written),
                   movie.encoder_name().c_str(), movie.encoded_width(), movie.encoded_height(),
                   movie.path().c_str(), sim_s, render_s, encode_s, pngs);
    } else
      std::fprintf(stderr, "grainshock: interrupted before the first frame; no movie written\n");
  }
  return {written, stopped};
}

}  // namespace gs::app
