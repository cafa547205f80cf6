#include "jobs/frame_loop.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "render/camera.h"
#include "render/field.h"

namespace gs::jobs {
void aim(render::View& view, const render::Shot& shot, int dim) {
  view.centre = shot.centre;
  view.zoom = 1;
  if (dim == 3) {
    const double tan_y = std::tan(view.fov * std::numbers::pi / 360);
    const double tan_x = tan_y * view.width / view.height;
    view.distance = shot.half / std::sin(std::atan(std::min(tan_x, tan_y)));
    return;
  }
  view.half_width = shot.half;
}

FrameScan scan(const Snapshot& s, const render::Style& style, bool with_range) {
  FrameScan f;
  f.time = s.info.time;
  f.step = s.info.step.value_or(0);
  f.dim = s.info.dim;
  f.box = s.info.box;
  f.origin = s.info.origin;
  f.any_active = std::find(s.active.begin(), s.active.end(), 1) != s.active.end();
  auto in_front = [&](std::size_t i) {
    return f.any_active ? s.active[i] != 0 : s.has_velocity() && s.velocity[i].squaredNorm() > 0;
  };
  for (std::size_t i = 0; i < s.size(); ++i)
    if (in_front(i)) f.front.extend(s.position[i]);
  if (f.front.isEmpty()) f.front.extend(s.info.origin + s.info.box / 2);
  for (std::size_t i = 0; i < s.size(); ++i)
    if (in_front(i)) f.radius = std::max(f.radius, (s.position[i] - f.front.center()).norm());
  if (f.any_active && with_range) {
    const auto values = render::field_values(s, style.field, nullptr, style.column);
    f.range = render::auto_range(values, s.active, style.scale, style.percentile_low,
                                 style.percentile_high);
  }
  return f;
}

std::pair<double, double> fixed_range(const std::vector<FrameScan>& frames, render::Scale scale) {
  double lo = INFINITY, hi = -INFINITY;
  for (const auto& f : frames)
    if (f.any_active) lo = std::min(lo, f.range.first), hi = std::max(hi, f.range.second);
  if (!(lo < hi)) return scale == render::Scale::Log ? std::pair{0.1, 1.0} : std::pair{0.0, 1.0};
  return {lo, hi};
}

bool same_box(const Eigen::Vector3d& a_box, const Eigen::Vector3d& a_origin,
              const Eigen::Vector3d& b_box, const Eigen::Vector3d& b_origin) {
  return (b_box - a_box).cwiseAbs().maxCoeff() + (b_origin - a_origin).cwiseAbs().maxCoeff() <=
         1e-9 * std::max(1.0, a_box.maxCoeff());
}

// The union of the frames' boxes, when they are not all the first one's (else nullopt).
std::optional<Eigen::AlignedBox3d> moving_box(const std::vector<FrameScan>& frames) {
  Eigen::AlignedBox3d all;
  bool moves = false;
  for (const auto& f : frames) {
    if (!(f.box.head(f.dim).minCoeff() > 0)) continue;  // a frame without a box
    all.extend(f.origin);
    all.extend(f.origin + f.box);
    moves |= !same_box(frames.front().box, frames.front().origin, f.box, f.origin);
  }
  if (!moves) return std::nullopt;
  return all;
}

void finish_first_pass(Prepared& p) {
  if (p.stopped) return;
  if (p.plan.need_range) p.plan.style.range = fixed_range(p.scans, p.plan.style.scale);
  // A fixed camera frames every box a frame has (an NPT run, a compression, LAMMPS fix deform):
  // the camera stays put and each frame's box is outlined in it, as the particles move with it.
  if (!p.plan.follow && !p.scans.empty())
    if (const auto region = moving_box(p.scans)) {
      p.plan.view.region = region;
      p.plan.style.box_outline = true;
    }
}

KeptFrames::KeptFrames(const std::filesystem::path& dir, bool keep)
    : dir_(dir / "frames"), keep_(keep) {
  if (keep_) made_ = std::filesystem::create_directories(dir_);
}

KeptFrames::~KeptFrames() {
  if (kept_) return;
  std::error_code ec;
  for (const auto& f : written_) std::filesystem::remove(f, ec);
  if (made_) std::filesystem::remove(dir_, ec);
}

void KeptFrames::write(std::size_t k, const render::Image& img, const render::PngText& text) {
  char name[32];
  std::snprintf(name, sizeof name, "frame_%05zu.png", k);
  written_.push_back(dir_ / name);
  render::write_png(written_.back().string(), img, text);
}

render::FollowCamera make_follow(int dim, const render::View& view, const FrontMovieOptions& o) {
  return render::FollowCamera(dim, double(view.width) / view.height, view.margin,
                              static_cast<int>(o.movie.fps / 2));
}

FrontMovieResult render_pass(Frames& frames, const Prepared& p, const FrontMovieOptions& o,
                             KeptFrames& pngs, render::MovieParts& movie,
                             std::optional<render::FollowCamera>& follow,
                             render::Renderer& renderer, const char* pass, bool resumable) {
  const render::Style& style = p.plan.style;
  render::View view = p.plan.view;
  const std::size_t n = frames.size();
  double render_s = 0, png_s = 0, encode_s = 0;
  bool stopped = p.stopped;
  if (!stopped) {
    const auto progress_line = open_progress(o.progress);
    ProgressLine& progress = *progress_line;
    stopped = !frames.each(progress, pass, [&](std::size_t k, const Snapshot& snap) {
      auto t0 = std::chrono::steady_clock::now();
      if (p.check) p.check(k, snap);
      const bool cut = snap.info.dim == 3 && (view.slab > 0 || view.clip);
      const FrameScan f = p.plan.follow || cut ? scan(snap, style, false) : FrameScan{};
      if (p.plan.follow) {
        if (!follow) follow.emplace(make_follow(snap.info.dim, view, o));
        aim(view, follow->next(f.front, f.radius), snap.info.dim);
      } else if (cut) {
        // A fixed camera sees the wrapped box: the cut goes through the front's wrapped centre.
        Eigen::Vector3d c = f.front.center();
        const Eigen::Vector3d& box = snap.info.box;
        const Eigen::Vector3d& lo = snap.info.origin;
        for (int a = 0; a < 3; ++a)
          if (box[a] > 0) c[a] -= box[a] * std::floor((c[a] - lo[a]) / box[a]);
        view.cut_centre = c;
      }
      if (o.orbit != 0) view.azimuth = o.azimuth + o.orbit * (n > 1 ? double(k) / (n - 1) : 0.0);
      render::Image img = renderer.render(snap, style, view);
      render_s += seconds_since(t0);
      if (pngs.on()) {
        t0 = std::chrono::steady_clock::now();
        pngs.write(k, img, render::png_text({&snap}, renderer.last().disc_radius_px));
        png_s += seconds_since(t0);
      }
      t0 = std::chrono::steady_clock::now();
      movie.add(std::move(img));
      if (render::Image done = movie.spare(); !done.rgba.empty()) renderer.recycle(std::move(done));
      encode_s += seconds_since(t0);
    });
    progress.done();
  }
  const auto t0 = std::chrono::steady_clock::now();
  const auto written = movie.frames_added();
  if (written > 0)
    movie.finish(stopped && resumable);
  else
    movie.discard();  // a movie without a frame would only pretend to be one
  pngs.keep();
  encode_s += seconds_since(t0);
  if (!o.quiet) {
    if (written > 0) {
      char png_note[48] = "";
      if (o.keep_frames) std::snprintf(png_note, sizeof png_note, ", write PNGs %.3g s", png_s);
      char times[160];
      std::snprintf(times, sizeof times, "; render %.3g s, wait for the encoder %.3g s%s", render_s,
                    encode_s, png_note);
      tell(o.messages, MessageKind::Note,
           std::string(stopped ? "interrupted" : "finished") + ": " + std::to_string(written) +
               " frames (" + movie.encoder_name() + ", " + std::to_string(movie.encoded_width()) +
               "x" + std::to_string(movie.encoded_height()) + ") in " + movie.path().string() +
               times);
    } else
      tell(o.messages, MessageKind::Note, "interrupted before the first frame; no movie written");
  }
  return {written, stopped};
}

}  // namespace gs::jobs
