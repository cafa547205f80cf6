#include "jobs/movie_plan.h"

#include <cmath>

#include "render/field.h"
#include "render/movie_writer.h"
#include "render/render_choices.h"
#include "render/renderer.h"
#include "sim/error.h"
#include "sim/format.h"

namespace gs::jobs {

MoviePlan make_plan(const FrontMovieOptions& o) {
  MoviePlan p;
  render::Style& style = p.style;
  render::View& view = p.view;
  style.colormap = o.colormap;
  p.field_auto = o.colour_by == "auto";
  // An unknown field name waits for the first stored frame, whose fields the message lists.
  for (render::Field f : render::all_fields())
    if (o.colour_by == render::field_name(f)) style.field = f;
  style.background = render::parse_background(o.background);
  style.scale = render::parse_scale(o.scale, style.field);
  if (!o.range.empty()) style.range = std::pair{o.range[0], o.range[1]};
  if (!o.range.empty() && o.range_per_frame)
    throw UsageError("--range and --range-per-frame exclude each other");
  style.range_per_frame = o.range_per_frame;
  style.inset = o.inset;
  style.show_inactive = o.show_inactive;
  render::check_style(style);
  render::check_size(o.movie.width, o.movie.height);
  view.width = o.movie.width;
  view.height = o.movie.height;
  view.slab = o.slab.value_or(render::kKickSlab);
  view.clip = o.clip;
  view.azimuth = o.azimuth;
  view.elevation = o.elevation;
  if (!std::isfinite(o.orbit)) throw UsageError("--orbit must be a finite number of degrees");
  const bool follow = p.follow = o.camera == "follow";
  if (!follow && o.camera != "fixed")
    throw UsageError("unknown --camera '" + o.camera + "' (use follow or fixed)");
  view.framing = follow ? render::Framing::Fit : render::Framing::Box;
  if (o.slab && *o.slab < 0) throw UsageError("--slab must be >= 0");
  p.backend = render::parse_backend(o.backend);
  render::check_movie_options(o.movie);
  return p;
}

MoviePlan make_live_plan(const PhysicsConfig& physics, const FrontMovieOptions& o) {
  MoviePlan p = make_plan(o);
  // A fixed camera frames the whole periodic box; the unbounded medium's is an addressable region
  // thousands of diameters wide that is almost all never made.
  if (physics.unbounded() && !p.follow)
    throw UsageError(
        "--camera fixed: frames the whole box, and --medium unbounded (the default for kicks) "
        "has none; use --camera follow, or --medium box");
  if (p.field_auto)
    p.style.field =
        physics.initial == Initial::Kick ? render::Field::ScaledSpeed : render::Field::Speed;
  else
    render::parse_field(o.colour_by);  // names an unknown field
  p.style.scale = render::parse_scale(o.scale, p.style.field);
  render::check_style(p.style);
  check_orbit(physics.dim, o, "this run");
  settle_range(p, physics.dim);
  return p;
}

void check_orbit(int dim, const FrontMovieOptions& o, const std::string& what) {
  if (o.orbit != 0 && dim != 3)
    throw UsageError("--orbit turns the camera about a 3D scene; " + what + " is " +
                     std::to_string(dim) + "D");
}

void settle_range(MoviePlan& p, int dim) {
  p.need_range =
      !p.style.range && !p.style.range_per_frame && !render::default_range(p.style.field, dim);
}

std::vector<double> frame_times(const PhysicsConfig& physics, const FrontMovieOptions& o) {
  const int n = o.frames;
  const double t_max = physics.t_max;
  if (n < 1) throw UsageError("--frames must be at least 1 (got " + std::to_string(n) + ")");
  // Bounded before anything is allocated: a million frames is a nine-hour movie at 30 fps.
  if (n > 1000000)
    throw UsageError("--frames " + std::to_string(n) + ": too many frames (at most 1000000)");
  std::vector<double> t(n);
  if (o.spacing == "lin") {
    for (int k = 0; k < n; ++k) t[k] = t_max * (k + 1) / n;
  } else if (o.spacing == "log") {
    if (!(o.t_start > 0 && o.t_start < t_max))
      throw UsageError("--t-start " + format_number(o.t_start) + " must be in (0, --t-max " +
                       format_number(t_max) + ") for --frame-spacing log");
    for (int k = 0; k < n; ++k)
      t[k] = n == 1 ? t_max : o.t_start * std::pow(t_max / o.t_start, double(k) / (n - 1));
    t.back() = t_max;
  } else {
    throw UsageError("unknown --frame-spacing '" + o.spacing + "' (use lin or log)");
  }
  // Frames closer than the clock can tell apart would repeat the same picture.
  for (int k = 1; k < n; ++k)
    if (!(t[k] - t[k - 1] > 1e-9 * t[k]))
      throw UsageError("--frames " + std::to_string(n) + ": more frames than the run can give (" +
                       format_number(t[k - 1]) + " and " + format_number(t[k]) +
                       " are not distinct times); use fewer frames or a longer --t-max");
  return t;
}

}  // namespace gs::jobs
