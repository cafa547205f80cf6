#pragma once
// The one frame loop of every movie: each frame is scanned (where the front is, its colour range),
// the camera aimed (the following camera, render/follow_camera.h, needs no pass ahead), the frame
// drawn and encoded. The pass before it, when the colour range must span every frame, scans them
// all first.
#include <cstddef>
#include <filesystem>
#include <functional>
#include <optional>
#include <utility>
#include <vector>

#include <Eigen/Geometry>

#include "jobs/movie.h"
#include "jobs/movie_frames.h"
#include "jobs/movie_plan.h"
#include "render/follow_camera.h"
#include "render/image.h"
#include "render/movie_parts.h"
#include "render/png.h"
#include "render/renderer.h"

namespace gs::jobs {

// What the first pass learns about one frame: the colour range of its particles and where the
// front is (unwrapped).
struct FrameScan {
  double time = 0;
  std::int64_t step = 0;  // LAMMPS and HOOMD files: orders frames of equal (or no) time
  int dim = 2;
  Eigen::Vector3d box = Eigen::Vector3d::Zero();  // edges of the periodic box
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();  // its lower corner
  bool any_active = false;
  std::pair<double, double> range{0, 1};
  Eigen::AlignedBox3d front;  // active particles, else the moving ones (the kicked particle)
  double radius = 0;          // of the sphere about front.center() holding the same particles
};

FrameScan scan(const Snapshot& s, const render::Style& style, bool with_range);

// True when box b (edges, lower corner) is box a's, to a part in 1e9 of a's largest edge.
bool same_box(const Eigen::Vector3d& a_box, const Eigen::Vector3d& a_origin,
              const Eigen::Vector3d& b_box, const Eigen::Vector3d& b_origin);

// The union of the frames' robust ranges: no frame's bulk is clamped, one colour is one value.
std::pair<double, double> fixed_range(const std::vector<FrameScan>& frames, render::Scale scale);

// The first pass, when one is needed: the colour range that spans every frame. `check` (stored
// snapshots) is called on every frame the movie draws, before it is drawn.
struct Prepared {
  MoviePlan plan;
  std::vector<FrameScan> scans;
  std::function<void(std::size_t, const Snapshot&)> check;
  bool stopped = false;
};

// Fixes the colour range that spans the scanned frames, if the plan needs one; and, for a fixed
// camera over frames whose boxes differ, frames the union of the boxes and outlines each.
void finish_first_pass(Prepared& p);

// The PNGs of --keep-frames in DIR/frames. Made before the movie starts, so that an unwritable
// folder is reported before any work; removed again (the folder too, if made here) unless the
// movie is kept, so that a movie that fails leaves the output folder as it was.
class KeptFrames {
 public:
  KeptFrames(const std::filesystem::path& dir, bool keep);
  ~KeptFrames();
  KeptFrames(const KeptFrames&) = delete;
  KeptFrames& operator=(const KeptFrames&) = delete;
  bool on() const { return keep_; }
  void write(std::size_t k, const render::Image& img, const render::PngText& text);
  void keep() { kept_ = true; }

 private:
  std::filesystem::path dir_;
  bool keep_ = false, made_ = false, kept_ = false;
  std::vector<std::filesystem::path> written_;
};

// The following camera as a movie of these options makes it.
render::FollowCamera make_follow(int dim, const render::View& view, const FrontMovieOptions& o);
// Points the renderer's view at a shot of it. 2D: the shot's half width, which the scene fits
// into the part of the frame the colour bar leaves free (View::half_width); 3D: an explicit
// camera distance.
void aim(render::View& view, const render::Shot& shot, int dim);

// The second pass, the one frame loop of every movie: aims the camera (`follow`, made at the
// first frame unless a resumed movie brings its own), renders, encodes. A stopped movie that
// will be resumed (`resumable`) keeps its parts beside the movie of its frames so far.
FrontMovieResult render_pass(Frames& frames, const Prepared& p, const FrontMovieOptions& o,
                             KeptFrames& pngs, render::MovieParts& movie,
                             std::optional<render::FollowCamera>& follow,
                             render::Renderer& renderer, const char* pass, bool resumable);

}  // namespace gs::jobs
