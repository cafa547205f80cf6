// One frame loop for every movie. A colour must mean one value throughout: when the range is
// not fixed ahead (plain speed without --range), a first, picture-less pass finds it (runs are
// reproducible from (config, seed), so it replays the same trajectory). The following camera is
// aimed from each frame and those before it (render/follow_camera.h), so it needs no pass ahead.
// Stored snapshots are drawn in the order given, each read once, while they prove to be in order
// of time; if they are not, the movie starts again after a pass that orders them. A live movie
// can keep checkpoints: its movie is then written in parts (render/movie_parts.h), cut where a
// checkpoint is taken, and a resume goes on from the last one and joins the parts at the end.
#include "jobs/movie.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <utility>

#include "jobs/frame_loop.h"
#include "jobs/movie_checkpoints.h"
#include "jobs/movie_frames.h"
#include "jobs/movie_plan.h"
#include "jobs/progress.h"
#include "render/field.h"
#include "render/follow_camera.h"
#include "render/movie_parts.h"
#include "render/render_choices.h"
#include "render/renderer.h"
#include "sim/error.h"
#include "sim/stop.h"

namespace gs::jobs {

void check_front_movie(const PhysicsConfig& physics, const FrontMovieOptions& o) {
  frame_times(physics, o);
  make_live_plan(physics, o);
}

std::filesystem::path movie_checkpoint_path(const std::filesystem::path& dir) {
  return dir / "movie.checkpoint.bin";
}

std::filesystem::path previous_movie_checkpoint_path(const std::filesystem::path& dir) {
  return dir / "movie.checkpoint.prev.bin";
}

namespace {

// Every live movie: the range pass if one is needed, then the movie; with `checkpoints`, in
// parts and with checkpoints; with `resume` too, from dir's checkpoint on.
FrontMovieResult live_movie(const PhysicsConfig& physics, const FrontMovieOptions& o,
                            const std::filesystem::path& dir, const MovieCheckpoints* checkpoints,
                            bool resume) {
  Prepared p;
  p.plan = make_live_plan(physics, o);
  LiveFrames frames(physics, frame_times(physics, o));
  std::optional<LiveCheckpoints> ck;
  if (checkpoints) ck.emplace(dir, *checkpoints, physics);
  Pass pass = p.plan.need_range ? kRangePass : kMoviePass;
  Resumed r;
  if (resume) {
    const auto movie = dir / "movie.mp4";
    if (std::filesystem::exists(movie) && !std::filesystem::exists(movie_checkpoint_path(dir)) &&
        !std::filesystem::exists(previous_movie_checkpoint_path(dir))) {
      if (!std::filesystem::exists(render::MovieParts::folder(movie)))
        throw UserError("'" + dir.string() +
                        "' holds a finished movie (movie.mp4): nothing to resume");
      return remove_leftovers_of_finished(dir, o.quiet,
                                          o.messages);  // killed before its parts went
    }
    r = read_live_checkpoint(dir, *checkpoints, physics, p.plan, frames.size(),
                             make_follow(physics.dim, p.plan.view, o));
    // The parts are removed only once the movie is joined: the kill came after that.
    if (!render::MovieParts::on_disk(movie, r.parts) && std::filesystem::exists(movie))
      return remove_leftovers_of_finished(dir, o.quiet, o.messages);
    check_parts(movie, r.part_sums);
    pass = r.pass;
    p.scans = std::move(r.scans);
    frames.start_at(std::move(r.sim), r.next);
    ck->resumed(std::move(r.part_sums));
  }
  KeptFrames pngs(dir, o.keep_frames);
  // Opened now so that an unwritable folder is reported before any work.
  render::MovieParts movie(dir / "movie.mp4", o.movie, r.parts, r.part_frames);
  std::optional<render::FollowCamera>& follow = r.follow;
  render::Renderer renderer(p.plan.backend);
  install_stop_handlers();
  auto due = [&] { return ck->due(); };
  if (pass == kRangePass) {
    if (ck)
      frames.hook = {due, [&](std::size_t next, const Simulation& sim) {
                       ck->write(kRangePass, next, frames.size(), p.scans, follow, movie, sim);
                     }};
    const auto progress_line = open_progress(o.progress);
    ProgressLine& progress = *progress_line;
    p.stopped = !frames.each(progress, "pass 1 of 2 (range)", [&](std::size_t, const Snapshot& s) {
      p.scans.push_back(scan(s, p.plan.style, true));
    });
    progress.done();
  }
  finish_first_pass(p);
  if (ck)
    frames.hook = {due, [&](std::size_t next, const Simulation& sim) {
                     // Only at a part's end: a part cut anywhere else would be encoded otherwise
                     // than in a movie never stopped. A stop elsewhere leaves the last checkpoint,
                     // and a resume draws the frames since it again.
                     if (!movie.at_part_end()) return;
                     movie.cut();  // the parts a checkpoint names are on disk before it
                     ck->write(kMoviePass, next, frames.size(), p.scans, follow, movie, sim);
                   }};
  const FrontMovieResult result =
      render_pass(frames, p, o, pngs, movie, follow, renderer,
                  p.scans.empty() ? "movie" : "pass 2 of 2 (movie)", ck.has_value());
  // The movie is in place; the parts go after the checkpoints, with `movie`.
  if (ck && !result.stopped) remove_movie_checkpoints(dir);
  return result;
}

}  // namespace

FrontMovieResult write_front_movie(const PhysicsConfig& physics, const FrontMovieOptions& o,
                                   const std::filesystem::path& dir,
                                   const MovieCheckpoints* checkpoints) {
  return live_movie(physics, o, dir, checkpoints, false);
}

FrontMovieResult resume_front_movie(const PhysicsConfig& physics, const FrontMovieOptions& o,
                                    const std::filesystem::path& dir,
                                    const MovieCheckpoints& checkpoints) {
  return live_movie(physics, o, dir, &checkpoints, true);
}

bool movie_in_one_pass(const PhysicsConfig& physics, const FrontMovieOptions& o) {
  return !make_live_plan(physics, o).need_range;
}

FrontMovieResult write_run_movie(RunLoop& loop, const PhysicsConfig& physics,
                                 const FrontMovieOptions& o, const std::filesystem::path& dir) {
  Prepared p;
  p.plan = make_live_plan(physics, o);
  GS_CHECK(!p.plan.need_range);
  // Kept PNGs name the particles of their snapshot; the movie's pictures draw the active ones.
  RunFrames frames(loop, frame_times(physics, o), !p.plan.style.show_inactive && !o.keep_frames);
  KeptFrames pngs(dir, o.keep_frames);
  render::MovieParts movie(dir / "movie.mp4", o.movie);
  std::optional<render::FollowCamera> follow;
  render::Renderer renderer(p.plan.backend);
  return render_pass(frames, p, o, pngs, movie, follow, renderer, "movie", false);
}

struct StoredMovie::Impl {
  Impl(const std::vector<std::string>& files, const FrontMovieOptions& o)
      : frames(files, o.read), options(o) {}
  StoredFrames frames;
  Prepared prepared;
  FrontMovieOptions options;
  std::string first_name;  // the first frame given, which the others must fit
  int first_dim = 2;
  Eigen::Vector3d first_box = Eigen::Vector3d::Zero(), first_origin = Eigen::Vector3d::Zero();
  bool ordered = false;  // the frames are known to be in order of time
};

namespace {

// Thrown by the drawing pass when frames given in the order of their files turn out not to be
// in order of time, or a fixed camera meets a box unlike the first frame's (it must frame the
// union of every frame's box): the movie then starts again after a pass over every frame.
struct OutOfOrder {};

// UserError naming the frame unless it fits the first: dimension, the field's data. Its box may
// differ (finish_first_pass frames the union of the boxes).
void check_stored_frame(const StoredMovie::Impl& m, std::size_t k, const Snapshot& s) {
  const std::string name = m.frames.name(k);
  const render::Style& style = m.prepared.plan.style;
  if (s.info.dim != m.first_dim)
    throw UserError(name + " is " + std::to_string(s.info.dim) + "D but " + m.first_name + " is " +
                    std::to_string(m.first_dim) + "D: a movie's frames share one dimension");
  if (s.size() > 0 && render::needs_velocity(style.field) && !s.has_velocity())
    throw UserError(name + " has no velocities (no velo property); cannot colour by " +
                    render::field_name(style.field));
  if (style.field == render::Field::Column && !s.column(style.column))
    throw UserError(name + " has no column '" + style.column + "' but " + m.first_name +
                    " has: a movie's frames share one field");
}

// A pass over every frame that checks them, puts them in order of their Time, then of their
// time step (a LAMMPS dump without ITEM: TIME has only steps; frames of equal time and step keep
// the order they were given in), and finds the colour range if one spans them all.
void order_frames(StoredMovie::Impl& m) {
  Prepared& p = m.prepared;
  const auto progress_line = open_progress(m.options.progress);
  ProgressLine& progress = *progress_line;
  std::vector<FrameScan> scans;
  p.stopped =
      !m.frames.each(progress, "pass 1 of 2 (order, range)", [&](std::size_t k, const Snapshot& s) {
        check_stored_frame(m, k, s);
        scans.push_back(scan(s, p.plan.style, p.plan.need_range));
      });
  progress.done();
  if (p.stopped) return;
  std::vector<std::size_t> order(scans.size());
  for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return std::pair{scans[a].time, scans[a].step} < std::pair{scans[b].time, scans[b].step};
  });
  m.frames.reorder(order);
  p.scans.clear();
  for (std::size_t k : order) p.scans.push_back(scans[k]);
  finish_first_pass(p);
  m.ordered = true;
}

}  // namespace

StoredMovie::StoredMovie(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
StoredMovie::~StoredMovie() = default;
StoredMovie::StoredMovie(StoredMovie&&) noexcept = default;

std::size_t StoredMovie::frames() const {
  return impl_->frames.size();
}

StoredMovie prepare_stored_movie(const std::vector<std::string>& files,
                                 const FrontMovieOptions& o) {
  if (files.empty()) throw UserError("a movie of stored snapshots needs at least one file");
  auto impl = std::make_unique<StoredMovie::Impl>(files, o);
  StoredMovie::Impl& m = *impl;
  Prepared& p = m.prepared;
  p.plan = make_plan(o);
  install_stop_handlers();
  // Every file is opened (its frames indexed) and the first frame read, so that a file that
  // cannot be read, and flags that do not fit the frames, are named before anything is made.
  m.frames.list();
  const Snapshot s = m.frames.read_frame(0);
  m.first_name = m.frames.name(0);
  m.first_dim = s.info.dim;
  m.first_box = s.info.box;
  m.first_origin = s.info.origin;
  if (!p.plan.follow && s.info.unbounded)
    throw UserError("--camera fixed: " + m.first_name +
                    " is of the unbounded medium, which has no box to frame; use --camera follow");
  p.plan.style.field = render::choose_field(o.colour_by, s, files.front());
  if (p.plan.style.field == render::Field::Column) p.plan.style.column = o.colour_by;
  if (!o.slab) p.plan.view.slab = render::default_slab(s);
  p.plan.style.scale = render::parse_scale(o.scale, p.plan.style.field);
  render::check_style(p.plan.style);
  check_orbit(s.info.dim, o, m.first_name);
  settle_range(p.plan, s.info.dim);
  check_stored_frame(m, 0, s);
  // What the reader assumed (masses, time from steps, wrapping), said once for the movie.
  if (!o.quiet)
    for (const auto& note : s.notes)
      tell(o.messages, MessageKind::Note, m.first_name + ": " + note);
  // A range that spans every frame needs them all first; that pass orders them too. Otherwise
  // the frames are drawn as given, each read once, while they prove to be in order of time.
  if (p.plan.need_range) order_frames(m);
  return StoredMovie(std::move(impl));
}

FrontMovieResult write_stored_movie(StoredMovie& m, const std::filesystem::path& dir) {
  StoredMovie::Impl& impl = *m.impl_;
  const FrontMovieOptions& o = impl.options;
  Prepared& p = impl.prepared;
  render::Renderer renderer(p.plan.backend);
  if (!impl.ordered && !p.stopped) {
    KeptFrames pngs(dir, o.keep_frames);
    render::MovieParts movie(dir / "movie.mp4", o.movie);
    std::optional<render::FollowCamera> follow;
    // (time, step) of the frame before; held by the check, which outlives this call.
    auto before = std::make_shared<std::pair<double, std::int64_t>>(-INFINITY, 0);
    p.check = [&impl, before](std::size_t k, const Snapshot& s) {
      check_stored_frame(impl, k, s);
      const std::pair<double, std::int64_t> at{s.info.time, s.info.step.value_or(0)};
      if (at < *before) throw OutOfOrder{};
      *before = at;
      if (!impl.prepared.plan.follow &&
          !same_box(impl.first_box, impl.first_origin, s.info.box, s.info.origin))
        throw OutOfOrder{};
    };
    try {
      return render_pass(impl.frames, p, o, pngs, movie, follow, renderer, "movie", false);
    } catch (const OutOfOrder&) {
      movie.discard();  // and the PNGs go with `pngs`
    }
    order_frames(impl);
  }
  p.check = nullptr;  // the pass that ordered the frames checked them
  KeptFrames pngs(dir, o.keep_frames);
  render::MovieParts movie(dir / "movie.mp4", o.movie);
  std::optional<render::FollowCamera> follow;
  return render_pass(impl.frames, p, o, pngs, movie, follow, renderer,
                     impl.ordered ? "pass 2 of 2 (movie)" : "movie", false);
}

}  // namespace gs::jobs
