// A colour must mean one value throughout and a following camera must never lose the front, so
// both need every frame ahead of time. Runs are reproducible from (config, seed), so a first,
// picture-less pass over the same trajectory finds the colour range and the camera path; the
// second pass renders. The first pass is skipped when neither is needed (a fixed range and a
// fixed camera). Stored snapshots take the same two passes over the files (the first also puts
// them in order of time and checks them), and the same frame loop.
#include "apps/front_movie.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstdio>
#include <functional>
#include <mutex>
#include <numbers>
#include <optional>
#include <thread>

#include "apps/progress.h"
#include "render/camera.h"
#include "render/field.h"
#include "render/png.h"
#include "render/renderer.h"
#include "sim/engine.h"
#include "sim/error.h"
#include "sim/format.h"
#include "sim/snapshot_file.h"
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
  double time = 0;
  std::int64_t step = 0;  // LAMMPS and HOOMD files: orders frames of equal (or no) time
  int dim = 2;
  Eigen::Vector3d box = Eigen::Vector3d::Zero();  // edges of the periodic box
  bool any_active = false;
  std::pair<double, double> range{0, 1};
  Eigen::AlignedBox3d front;  // active particles, else the moving ones (the kicked particle)
  double radius = 0;          // of the sphere about front.center() holding the same particles
  Eigen::AlignedBox3d fit;    // the renderer's rule: active particles, else all
};

FrameScan scan(const Snapshot& s, const render::Style& style, bool with_range) {
  FrameScan f;
  f.time = s.info.time;
  f.step = s.info.step.value_or(0);
  f.dim = s.info.dim;
  f.box = s.info.box;
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
    const auto values = render::field_values(s, style.field, nullptr, style.column);
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
  render::Style style;
  render::View view;
  bool follow = true;
  render::Backend backend = render::Backend::Auto;
  bool field_auto = false;  // colour_by "auto": decided by the first frame (stored snapshots)
  bool need_range = false;  // the colour range spans every frame: the first pass finds it
};

// The flags that do not depend on where the frames come from.
Plan make_plan(const FrontMovieOptions& o) {
  Plan p;
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
    throw UserError("--range and --range-per-frame exclude each other");
  style.range_per_frame = o.range_per_frame;
  style.inset = o.inset;
  style.show_inactive = o.show_inactive;
  render::check_style(style);
  render::check_size(o.movie.width, o.movie.height, 16384);
  view.width = o.movie.width;
  view.height = o.movie.height;
  view.slab = o.slab;
  view.clip = o.clip;
  view.azimuth = o.azimuth;
  view.elevation = o.elevation;
  if (!std::isfinite(o.orbit)) throw UserError("--orbit must be a finite number of degrees");
  const bool follow = p.follow = o.camera == "follow";
  if (!follow && o.camera != "fixed")
    throw UserError("unknown --camera '" + o.camera + "' (use follow or fixed)");
  view.framing = follow ? render::Framing::Fit : render::Framing::Box;
  if (o.slab < 0) throw UserError("--slab must be >= 0");
  p.backend = render::parse_backend(o.backend);
  render::check_movie_options(o.movie);
  return p;
}

void check_orbit(int dim, const FrontMovieOptions& o, const std::string& what) {
  if (o.orbit != 0 && dim != 3)
    throw UserError("--orbit turns the camera about a 3D scene; " + what + " is " +
                    std::to_string(dim) + "D");
}

// Once the field and dimension are known: does the colour range need every frame?
void settle_range(Plan& p, int dim) {
  p.need_range =
      !p.style.range && !p.style.range_per_frame && !render::default_range(p.style.field, dim);
}

// The frames of a movie, visited in order, as often as the passes need them.
class Frames {
 public:
  virtual ~Frames() = default;
  virtual std::size_t size() const = 0;
  // Calls visit(k, snapshot) for k = 0, 1, ...; false if a stop request ended the pass.
  virtual bool each(Progress& progress, const char* pass,
                    const std::function<void(std::size_t, const Snapshot&)>& visit) = 0;
};

// A running simulation, replayed from the start on each pass.
class LiveFrames final : public Frames {
 public:
  LiveFrames(const PhysicsConfig& physics, std::vector<double> times)
      : physics_(physics), times_(std::move(times)) {}
  std::size_t size() const override { return times_.size(); }
  bool each(Progress& progress, const char* pass,
            const std::function<void(std::size_t, const Snapshot&)>& visit) override {
    auto sim = make_simulation(physics_);
    return for_each_frame(*sim, times_, progress, pass, [&](std::size_t k) {
      sim->snapshot(snap_);
      visit(k, snap_);
    });
  }

 private:
  PhysicsConfig physics_;
  std::vector<double> times_;
  Snapshot snap_;  // reused frame after frame
};

// Every frame of stored snapshot files in a chosen order. A second thread reads frame k + 1 while
// frame k is drawn; it waits for the slot to empty first, so at most two frames are in memory
// at once. The first pass walks the files in the order given, every frame of each, and learns
// the frames; later passes visit them in the order reorder() set, keeping the last file opened
// (its frame index) for the frames after it.
class StoredFrames final : public Frames {
 public:
  explicit StoredFrames(std::vector<std::string> paths) : paths_(std::move(paths)) {}
  std::size_t size() const override { return entries_.size(); }
  // "'file'", or "frame 3 of 'file'" for a file of several frames (frames count from 0).
  std::string name(std::size_t k) const {
    const Entry& e = entries_[k];
    const std::string file = "'" + paths_[e.file] + "'";
    return counts_[e.file] == 1 ? file : "frame " + std::to_string(e.frame) + " of " + file;
  }
  // Reorders the frames: frame k becomes the one that was frame `order[k]`.
  void reorder(const std::vector<std::size_t>& order) {
    std::vector<Entry> e;
    for (std::size_t k : order) e.push_back(entries_[k]);
    entries_ = std::move(e);
  }
  bool each(Progress& progress, const char* pass,
            const std::function<void(std::size_t, const Snapshot&)>& visit) override {
    const bool first = counts_.empty();
    struct Item {
      Entry entry;
      std::size_t count;  // frames in its file
      double done;        // fraction of the pass once this frame is drawn
      Snapshot snap;
    };
    std::mutex m;
    std::condition_variable cv;
    std::optional<Item> slot;
    std::exception_ptr error;
    bool quit = false;
    // Hands one frame to the drawing thread; false when the pass is over.
    auto put = [&](Item item) {
      std::unique_lock lock(m);
      cv.wait(lock, [&] { return !slot || quit; });
      if (quit) return false;
      slot = std::move(item);
      cv.notify_all();
      return true;
    };
    // A file's frames, counted by the first pass: a file that changed since reads as an error.
    std::vector<std::size_t> counted = counts_;
    auto open = [&](std::size_t file) {
      SnapshotFile f = open_snapshots(paths_[file]);
      if (!first && f.frame_count() != counted[file])
        throw UserError(
            "snapshot '" + paths_[file] + "' changed while the movie was made: it had " +
            std::to_string(counted[file]) + " frames, it has " + std::to_string(f.frame_count()));
      return f;
    };
    std::thread reader([&] {
      try {
        if (first) {
          for (std::size_t file = 0; file < paths_.size(); ++file) {
            const SnapshotFile f = open(file);
            const std::size_t n = f.frame_count();
            if (n == 0) throw UserError("snapshot '" + paths_[file] + "' holds no frame");
            for (std::size_t j = 0; j < n; ++j)
              if (!put({{file, j}, n, (file + (j + 1.0) / n) / paths_.size(), read(f, j)})) return;
          }
        } else {
          std::optional<SnapshotFile> f;
          std::size_t open_file = 0;
          for (std::size_t k = 0; k < entries_.size(); ++k) {
            const Entry e = entries_[k];
            if (!f || open_file != e.file) f.reset(), f.emplace(open(e.file)), open_file = e.file;
            if (!put({e, counted[e.file], (k + 1.0) / entries_.size(), read(*f, e.frame)})) return;
          }
        }
        put({{0, kEnd}, 0, 1, {}});
      } catch (...) {
        std::lock_guard lock(m);
        error = std::current_exception();
        cv.notify_all();
      }
    });
    struct Join {  // the reader stops and is joined however this pass ends
      std::thread& t;
      std::mutex& m;
      std::condition_variable& cv;
      bool& quit;
      ~Join() {
        {
          std::lock_guard lock(m);
          quit = true;
        }
        cv.notify_all();
        t.join();
      }
    } join{reader, m, cv, quit};
    for (std::size_t k = 0;; ++k) {
      Item item;
      {
        std::unique_lock lock(m);
        cv.wait(lock, [&] { return slot || error; });
        if (!slot) std::rethrow_exception(error);
        item = std::move(*slot);
        slot.reset();
      }
      cv.notify_all();
      if (item.entry.frame == kEnd) return true;
      if (first) {
        entries_.push_back(item.entry);
        if (item.entry.file == counts_.size()) counts_.push_back(item.count);
      }
      visit(k, item.snap);
      char what[160];
      if (first)
        std::snprintf(what, sizeof what, "%s: frame %zu, t = %.4g", pass, k + 1,
                      item.snap.info.time);
      else
        std::snprintf(what, sizeof what, "%s: frame %zu of %zu, t = %.4g", pass, k + 1,
                      entries_.size(), item.snap.info.time);
      progress.update(item.done, what);
      if (stop_requested()) return false;
    }
  }

 private:
  struct Entry {
    std::size_t file, frame;
  };
  static constexpr std::size_t kEnd = std::size_t(-1);  // the frame of the item ending a pass
  // Frame j; a reader's error (which names the file and line) also names the frame.
  static Snapshot read(const SnapshotFile& f, std::size_t j) {
    try {
      return f.read(j);
    } catch (const UserError& e) {
      if (f.frame_count() == 1) throw;
      throw UserError(std::string(e.what()) + " (frame " + std::to_string(j) + " of " +
                      std::to_string(f.frame_count()) + ")");
    }
  }
  std::vector<std::string> paths_;
  std::vector<Entry> entries_;       // frame k of the movie is frame entries_[k].frame of a file
  std::vector<std::size_t> counts_;  // frames in each file, as the first pass found them
};

// The first pass: what every frame needs of all the others (range, camera path).
struct Prepared {
  Plan plan;
  std::vector<FrameScan> scans;
  std::vector<Shot> shots;
  bool stopped = false;
};

void finish_first_pass(Prepared& p, int dim, double fps) {
  if (p.stopped) return;
  if (p.plan.need_range) p.plan.style.range = fixed_range(p.scans, p.plan.style.scale);
  if (p.plan.follow)
    p.shots = camera_path(p.scans, dim, double(p.plan.view.width) / p.plan.view.height,
                          p.plan.view.margin, std::max(1, static_cast<int>(fps / 2)));
}

// The PNGs of --keep-frames in DIR/frames. Made before the movie starts, so that an unwritable
// folder is reported before any work; removed again (the folder too, if made here) unless the
// movie is kept, so that a movie that fails leaves the output folder as it was.
class KeptFrames {
 public:
  KeptFrames(const std::filesystem::path& dir, bool keep) : dir_(dir / "frames"), keep_(keep) {
    if (keep_) made_ = std::filesystem::create_directories(dir_);
  }
  ~KeptFrames() {
    if (kept_) return;
    std::error_code ec;
    for (const auto& f : written_) std::filesystem::remove(f, ec);
    if (made_) std::filesystem::remove(dir_, ec);
  }
  KeptFrames(const KeptFrames&) = delete;
  KeptFrames& operator=(const KeptFrames&) = delete;
  bool on() const { return keep_; }
  void write(std::size_t k, const render::Image& img, const render::PngText& text) {
    char name[32];
    std::snprintf(name, sizeof name, "frame_%05zu.png", k);
    written_.push_back(dir_ / name);
    render::write_png(written_.back().string(), img, text);
  }
  void keep() { kept_ = true; }

 private:
  std::filesystem::path dir_;
  bool keep_ = false, made_ = false, kept_ = false;
  std::vector<std::filesystem::path> written_;
};

// The second pass, the one frame loop of every movie: aims the camera, renders, encodes.
FrontMovieResult render_pass(Frames& frames, const Prepared& p, const FrontMovieOptions& o,
                             KeptFrames& pngs, render::MovieWriter& movie,
                             render::Renderer& renderer, const char* pass) {
  const render::Style& style = p.plan.style;
  render::View view = p.plan.view;
  const std::size_t n = frames.size();
  double render_s = 0, png_s = 0, encode_s = 0;
  bool stopped = p.stopped;
  if (!stopped) {
    Progress progress(o.quiet);
    stopped = !frames.each(progress, pass, [&](std::size_t k, const Snapshot& snap) {
      auto t0 = std::chrono::steady_clock::now();
      if (p.plan.follow) {
        aim(view, p.shots[k], snap, p.scans[k]);
      } else if (snap.info.dim == 3 && k < p.scans.size()) {
        // A fixed camera sees the wrapped box: the cut goes through the front's wrapped centre.
        Eigen::Vector3d c = p.scans[k].front.center();
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
        pngs.write(k, img, render::png_text(snap.info, snap.size()));
        png_s += seconds_since(t0);
      }
      t0 = std::chrono::steady_clock::now();
      movie.add(std::move(img));
      encode_s += seconds_since(t0);
    });
    progress.done();
  }
  const auto t0 = std::chrono::steady_clock::now();
  const auto written = movie.frames_added();
  if (written > 0)
    movie.finish();
  else
    movie.discard();  // a movie without a frame would only pretend to be one
  pngs.keep();
  encode_s += seconds_since(t0);
  if (!o.quiet) {
    if (written > 0) {
      char png_note[48] = "";
      if (o.keep_frames) std::snprintf(png_note, sizeof png_note, ", write PNGs %.3g s", png_s);
      std::fprintf(stderr,
                   "grainshock: %s: %lld frames (%s, %dx%d) in %s; render %.3g s, wait for the "
                   "encoder %.3g s%s\n",
                   stopped ? "interrupted" : "finished", static_cast<long long>(written),
                   movie.encoder_name().c_str(), movie.encoded_width(), movie.encoded_height(),
                   movie.path().c_str(), render_s, encode_s, png_note);
    } else
      std::fprintf(stderr, "grainshock: interrupted before the first frame; no movie written\n");
  }
  return {written, stopped};
}

Plan make_live_plan(const PhysicsConfig& physics, const FrontMovieOptions& o) {
  Plan p = make_plan(o);
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

}  // namespace

void check_front_movie(const PhysicsConfig& physics, const FrontMovieOptions& o) {
  frame_times(physics, o);
  make_live_plan(physics, o);
}

FrontMovieResult write_front_movie(const PhysicsConfig& physics, const FrontMovieOptions& o,
                                   const std::filesystem::path& dir) {
  Prepared p;
  p.plan = make_live_plan(physics, o);
  LiveFrames frames(physics, frame_times(physics, o));
  KeptFrames pngs(dir, o.keep_frames);
  // Opened now so that an unwritable folder is reported before any work.
  render::MovieWriter movie(dir / "movie.mp4", o.movie);
  render::Renderer renderer(p.plan.backend);
  install_stop_handlers();
  // A 3D slab or clip seen by a fixed camera follows the front's centre, found by the first pass.
  const bool cut = physics.dim == 3 && (o.slab > 0 || o.clip);
  if (p.plan.need_range || p.plan.follow || cut) {
    Progress progress(o.quiet);
    p.stopped =
        !frames.each(progress, "pass 1 of 2 (range, camera)", [&](std::size_t, const Snapshot& s) {
          p.scans.push_back(scan(s, p.plan.style, p.plan.need_range));
        });
    progress.done();
    finish_first_pass(p, physics.dim, o.movie.fps);
  }
  return render_pass(frames, p, o, pngs, movie, renderer,
                     p.scans.empty() ? "movie" : "pass 2 of 2 (movie)");
}

struct StoredMovie::Impl {
  StoredFrames frames;
  Prepared prepared;
  FrontMovieOptions options;
};

StoredMovie::StoredMovie(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
StoredMovie::~StoredMovie() = default;
StoredMovie::StoredMovie(StoredMovie&&) noexcept = default;

std::size_t StoredMovie::frames() const {
  return impl_->frames.size();
}

StoredMovie prepare_stored_movie(const std::vector<std::string>& files,
                                 const FrontMovieOptions& o) {
  if (files.empty()) throw UserError("a movie of stored snapshots needs at least one file");
  auto impl = std::make_unique<StoredMovie::Impl>(StoredMovie::Impl{StoredFrames(files), {}, o});
  Prepared& p = impl->prepared;
  p.plan = make_plan(o);
  StoredFrames& frames = impl->frames;
  install_stop_handlers();
  // The first pass reads every file: their times, and what the range and the camera need. A
  // file that cannot be read, or does not fit with the first, is named before anything is made.
  Progress progress(o.quiet);
  std::vector<FrameScan> scans;
  p.stopped = !frames.each(
      progress, "pass 1 of 2 (order, range, camera)", [&](std::size_t k, const Snapshot& s) {
        const std::string name = frames.name(k);
        if (k == 0) {
          p.plan.style.field = render::choose_field(o.colour_by, s, files.front());
          if (p.plan.style.field == render::Field::Column) p.plan.style.column = o.colour_by;
          p.plan.style.scale = render::parse_scale(o.scale, p.plan.style.field);
          render::check_style(p.plan.style);
          check_orbit(s.info.dim, o, name);
          settle_range(p.plan, s.info.dim);
        } else {
          const FrameScan& first = scans.front();
          if (s.info.dim != first.dim)
            throw UserError(name + " is " + std::to_string(s.info.dim) + "D but " + frames.name(0) +
                            " is " + std::to_string(first.dim) +
                            "D: a movie's frames share one dimension");
          if ((s.info.box - first.box).cwiseAbs().maxCoeff() >
              1e-9 * std::max(1.0, first.box.maxCoeff())) {
            auto edges = [&](const Eigen::Vector3d& b) {
              std::string e = format_number(b[0]);
              for (int a = 1; a < s.info.dim; ++a) e += " x " + format_number(b[a]);
              return e;
            };
            throw UserError(name + " has box " + edges(s.info.box) + " but " + frames.name(0) +
                            " has " + edges(first.box) + ": a movie's frames share one box");
          }
        }
        if (s.size() > 0 && render::needs_velocity(p.plan.style.field) && !s.has_velocity())
          throw UserError(name + " has no velocities (no velo property); cannot colour by " +
                          render::field_name(p.plan.style.field));
        if (p.plan.style.field == render::Field::Column && !s.column(p.plan.style.column))
          throw UserError(name + " has no column '" + p.plan.style.column + "' but " +
                          frames.name(0) + " has: a movie's frames share one field");
        scans.push_back(scan(s, p.plan.style, p.plan.need_range));
      });
  progress.done();
  if (p.stopped) return StoredMovie(std::move(impl));
  // Frames in order of their Time, then of their time step (a LAMMPS dump without ITEM: TIME
  // has only steps); frames of equal time and step keep the order they were given in.
  std::vector<std::size_t> order(scans.size());
  for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return std::pair{scans[a].time, scans[a].step} < std::pair{scans[b].time, scans[b].step};
  });
  frames.reorder(order);
  for (std::size_t k : order) p.scans.push_back(scans[k]);
  finish_first_pass(p, p.scans.front().dim, o.movie.fps);
  return StoredMovie(std::move(impl));
}

FrontMovieResult write_stored_movie(StoredMovie& m, const std::filesystem::path& dir) {
  const FrontMovieOptions& o = m.impl_->options;
  Prepared& p = m.impl_->prepared;
  KeptFrames pngs(dir, o.keep_frames);
  render::MovieWriter movie(dir / "movie.mp4", o.movie);
  render::Renderer renderer(p.plan.backend);
  return render_pass(m.impl_->frames, p, o, pngs, movie, renderer, "pass 2 of 2 (movie)");
}

}  // namespace gs::app
