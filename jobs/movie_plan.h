#pragma once
// What a movie's options decide, checked (UserError naming the flag) before anything is made: the
// style, the view, the camera, whether the colour range needs a pass over every frame, and the
// times of a live movie's frames.
#include <string>
#include <vector>

#include "jobs/movie.h"
#include "render/gl_context.h"
#include "render/style.h"
#include "render/view.h"
#include "sim/config.h"

namespace gs::jobs {

// Everything the options decide, checked (UserError naming the flag) before anything is made.
struct MoviePlan {
  render::Style style;
  render::View view;
  bool follow = true;
  render::Backend backend = render::Backend::Auto;
  bool field_auto = false;  // colour_by "auto": decided by the first frame (stored snapshots)
  bool need_range = false;  // the colour range spans every frame: the first pass finds it
};

// The flags that do not depend on where the frames come from.
MoviePlan make_plan(const FrontMovieOptions& o);
// A live movie's plan: the field follows from the physics (scaled speed for a kick).
MoviePlan make_live_plan(const PhysicsConfig& physics, const FrontMovieOptions& o);
// UserError unless --orbit is 0 or the frames (`what`) are 3D.
void check_orbit(int dim, const FrontMovieOptions& o, const std::string& what);
// Once the field and dimension are known: does the colour range need every frame?
void settle_range(MoviePlan& p, int dim);
// The simulated times of a live movie's frames (--frames, --frame-spacing, --t-start).
std::vector<double> frame_times(const PhysicsConfig& physics, const FrontMovieOptions& o);

}  // namespace gs::jobs
