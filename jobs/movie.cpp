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
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstdio>
#include <functional>
#include <mutex>
#include <numbers>
#include <optional>
#include <thread>
#include <utility>

#include "io/checkpoint.h"
#include "io/snapshot_file.h"
#include "jobs/progress.h"
#include "render/camera.h"
#include "render/field.h"
#include "render/follow_camera.h"
#include "render/movie_parts.h"
#include "render/png.h"
#include "render/renderer.h"
#include "sim/engine.h"
#include "sim/error.h"
#include "sim/format.h"
#include "sim/stop.h"

namespace gs::jobs {
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

// Where a live movie keeps checkpoints: `due` says when one is; `write` takes it, `next` being
// the frame to draw next. Without `write`, none.
struct PauseHook {
  std::function<bool()> due;
  std::function<void(std::size_t next, const Simulation& sim)> write;
};

// Advances to each frame time from frame `first` on, in slices that depend only on the
// simulated time (where a slice ends does not change the history), so that both passes and a
// resumed movie see the same trajectory, and a stop request or a checkpoint falling due is
// noticed within a fraction of a second. A stop writes a checkpoint first. Returns false if
// stopped.
template <class Visit>
bool for_each_frame(Simulation& sim, const std::vector<double>& times, std::size_t first,
                    ProgressLine& progress, const char* pass, Visit visit, const PauseHook& hook) {
  const auto t0 = std::chrono::steady_clock::now();
  const auto events0 = sim.stats().events;
  auto halt = [&](std::size_t next) {
    const bool stop = stop_requested();
    if (hook.write && (stop || hook.due())) hook.write(next, sim);
    return stop;
  };
  for (std::size_t k = first; k < times.size(); ++k) {
    while (sim.time() < times[k]) {
      sim.run_until(std::min(times[k], sim.time() + std::max(1.0, 0.01 * sim.time())));
      if (halt(k)) return false;
    }
    visit(k);
    char what[160];
    std::snprintf(what, sizeof what, "%s: frame %zu of %zu, t = %.4g, %.3g events/s", pass, k + 1,
                  times.size(), times[k],
                  double(sim.stats().events - events0) / std::max(1e-9, seconds_since(t0)));
    progress.update(double(k + 1) / times.size(), what);
    if (halt(k + 1)) return false;
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

// Points the renderer's view at a shot. 2D: the zoom that turns the renderer's fitted framing of
// this frame into the shot's width; 3D: an explicit camera distance.
void aim(render::View& view, const render::Shot& shot, const Snapshot& s, const FrameScan& f) {
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
  virtual bool each(ProgressLine& progress, const char* pass,
                    const std::function<void(std::size_t, const Snapshot&)>& visit) = 0;
};

// A running simulation, replayed from the start on each pass, or from a checkpoint's state.
class LiveFrames final : public Frames {
 public:
  LiveFrames(const PhysicsConfig& physics, std::vector<double> times)
      : physics_(physics), times_(std::move(times)) {}
  std::size_t size() const override { return times_.size(); }
  // The next pass goes on from `sim`, whose next frame is `next`.
  void start_at(std::unique_ptr<Simulation> sim, std::size_t next) {
    start_ = std::move(sim);
    first_ = next;
  }
  bool each(ProgressLine& progress, const char* pass,
            const std::function<void(std::size_t, const Snapshot&)>& visit) override {
    auto sim = start_ ? std::move(start_) : make_simulation(physics_);
    const std::size_t first = std::exchange(first_, 0);
    return for_each_frame(
        *sim, times_, first, progress, pass,
        [&](std::size_t k) {
          sim->snapshot(snap_);
          visit(k, snap_);
        },
        hook);
  }
  PauseHook hook;  // the checkpoints of the next pass

 private:
  PhysicsConfig physics_;
  std::vector<double> times_;
  std::unique_ptr<Simulation> start_;
  std::size_t first_ = 0;
  Snapshot snap_;  // reused frame after frame
};

// Every frame of stored snapshot files in a chosen order. list() opens the files (which indexes
// their frames without parsing them) and takes the frames in the order given; reorder() changes
// it. A second thread reads frame k + 1 while frame k is drawn; it waits for the slot to empty
// first, so at most two frames are in memory at once. The last file opened stays open for the
// frames after it.
class StoredFrames final : public Frames {
 public:
  StoredFrames(std::vector<std::string> paths, const ReadOptions& read)
      : paths_(std::move(paths)), read_(read) {}
  std::size_t size() const override { return entries_.size(); }
  // UserError naming a file that cannot be opened or holds no frame.
  void list() {
    for (std::size_t file = 0; file < paths_.size(); ++file) {
      const std::size_t n = open_snapshots(paths_[file], read_).frame_count();
      if (n == 0) throw UserError("snapshot '" + paths_[file] + "' holds no frame");
      counts_.push_back(n);
      for (std::size_t j = 0; j < n; ++j) entries_.push_back({file, j});
    }
  }
  // "'file'", or "frame 3 of 'file'" for a file of several frames (frames count from 0).
  std::string name(std::size_t k) const {
    const Entry& e = entries_[k];
    const std::string file = "'" + paths_[e.file] + "'";
    return counts_[e.file] == 1 ? file : "frame " + std::to_string(e.frame) + " of " + file;
  }
  Snapshot read_frame(std::size_t k) const {
    return read(open_snapshots(paths_[entries_[k].file], read_), entries_[k].frame);
  }
  // Reorders the frames: frame k becomes the one that was frame `order[k]`.
  void reorder(const std::vector<std::size_t>& order) {
    std::vector<Entry> e;
    for (std::size_t k : order) e.push_back(entries_[k]);
    entries_ = std::move(e);
  }
  bool each(ProgressLine& progress, const char* pass,
            const std::function<void(std::size_t, const Snapshot&)>& visit) override {
    struct Item {
      bool end = false;  // the item ending the pass
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
    // A file's frames as list() counted them: a file that changed since reads as an error.
    auto open = [&](std::size_t file) {
      SnapshotFile f = open_snapshots(paths_[file], read_);
      if (f.frame_count() != counts_[file])
        throw UserError(
            "snapshot '" + paths_[file] + "' changed while the movie was made: it had " +
            std::to_string(counts_[file]) + " frames, it has " + std::to_string(f.frame_count()));
      return f;
    };
    std::thread reader([&] {
      try {
        std::optional<SnapshotFile> f;
        std::size_t open_file = 0;
        for (const Entry& e : entries_) {
          if (!f || open_file != e.file) f.reset(), f.emplace(open(e.file)), open_file = e.file;
          if (!put({false, read(*f, e.frame)})) return;
        }
        put({true, {}});
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
      if (item.end) return true;
      visit(k, item.snap);
      char what[160];
      std::snprintf(what, sizeof what, "%s: frame %zu of %zu, t = %.4g", pass, k + 1,
                    entries_.size(), item.snap.info.time);
      progress.update((k + 1.0) / entries_.size(), what);
      if (stop_requested()) return false;
    }
  }

 private:
  struct Entry {
    std::size_t file, frame;
  };
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
  ReadOptions read_;
  std::vector<Entry> entries_;       // frame k of the movie is frame entries_[k].frame of a file
  std::vector<std::size_t> counts_;  // frames in each file
};

// The first pass, when one is needed: the colour range that spans every frame. `check` (stored
// snapshots) is called on every frame the movie draws, before it is drawn.
struct Prepared {
  Plan plan;
  std::vector<FrameScan> scans;
  std::function<void(std::size_t, const Snapshot&)> check;
  bool stopped = false;
};

void finish_first_pass(Prepared& p) {
  if (!p.stopped && p.plan.need_range)
    p.plan.style.range = fixed_range(p.scans, p.plan.style.scale);
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

render::FollowCamera make_follow(int dim, const render::View& view, const FrontMovieOptions& o) {
  return render::FollowCamera(dim, double(view.width) / view.height, view.margin,
                              static_cast<int>(o.movie.fps / 2));
}

// The second pass, the one frame loop of every movie: aims the camera (`follow`, made at the
// first frame unless a resumed movie brings its own), renders, encodes. A stopped movie that
// will be resumed (`resumable`) keeps its parts beside the movie of its frames so far.
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
        aim(view, follow->next(f.front, f.radius), snap, f);
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
    movie.finish(stopped && resumable);
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

std::filesystem::path movie_checkpoint_path(const std::filesystem::path& dir) {
  return dir / "movie.checkpoint.bin";
}

std::filesystem::path previous_movie_checkpoint_path(const std::filesystem::path& dir) {
  return dir / "movie.checkpoint.prev.bin";
}

namespace {

enum Pass : std::uint32_t { kRangePass = 1, kMoviePass = 2 };

void remove_movie_checkpoints(const std::filesystem::path& dir) {
  std::error_code ec;
  std::filesystem::remove(movie_checkpoint_path(dir), ec);
  std::filesystem::remove(previous_movie_checkpoint_path(dir), ec);
}

// A live movie's checkpoints (io/checkpoint.h): the pass and the frame reached, the colour
// ranges pass 1 has found, the following camera, the parts of the movie on disk and the engine.
// Each is written whole, the previous one kept until it is in place.
class LiveCheckpoints {
 public:
  LiveCheckpoints(const std::filesystem::path& dir, const MovieCheckpoints& c,
                  const PhysicsConfig& physics)
      : dir_(dir),
        spec_(c.spec),
        every_(c.every),
        id_{physics.dim, static_cast<std::uint64_t>(physics.particles)} {}
  // The first is due at once, so that a kill at any moment leaves one; then every `every` s.
  bool due() const { return !any_ || (every_ > 0 && seconds_since(last_) >= every_); }
  void resumed() {
    any_ = true;
    last_ = std::chrono::steady_clock::now();
  }
  void write(Pass pass, std::size_t next, std::size_t frames, const std::vector<FrameScan>& scans,
             const std::optional<render::FollowCamera>& follow, const render::MovieParts& movie,
             const Simulation& sim) {
    CheckpointWriter out(movie_checkpoint_path(dir_), previous_movie_checkpoint_path(dir_), id_);
    out.string(spec_);
    out.value(static_cast<std::uint32_t>(pass));
    out.value(static_cast<std::uint64_t>(next));
    out.value(static_cast<std::uint64_t>(frames));
    out.value(static_cast<std::uint64_t>(scans.size()));
    for (const FrameScan& f : scans) {  // all that fixed_range() reads of them
      out.value(static_cast<std::uint8_t>(f.any_active));
      out.value(f.range.first);
      out.value(f.range.second);
    }
    out.value(static_cast<std::uint8_t>(follow.has_value()));
    if (follow) follow->save(out);
    out.value(static_cast<std::int32_t>(movie.parts()));
    out.value(static_cast<std::int64_t>(movie.frames_added()));
    sim.save(out);
    out.commit();
    resumed();
  }

 private:
  std::filesystem::path dir_;
  std::string spec_;
  double every_;
  StateIdentity id_;
  bool any_ = false;
  std::chrono::steady_clock::time_point last_;
};

// What a live movie goes on from.
struct Resumed {
  Pass pass = kRangePass;
  std::size_t next = 0;
  std::vector<FrameScan> scans;
  std::optional<render::FollowCamera> follow;
  int parts = 0;
  std::int64_t part_frames = 0;
  std::unique_ptr<Simulation> sim;
};

// Reads dir's checkpoint, refusing (UserError, one line; nothing touched) a folder without one,
// one that CheckpointReader refuses, and one of another movie.toml. `camera` is the following
// camera as this movie makes it, to be loaded with the state.
Resumed read_live_checkpoint(const std::filesystem::path& dir, const MovieCheckpoints& c,
                             const PhysicsConfig& physics, const Plan& plan, std::size_t frames,
                             const render::FollowCamera& camera) {
  const std::filesystem::path file = checkpoint_to_resume(
      movie_checkpoint_path(dir), previous_movie_checkpoint_path(dir), "movie checkpoint");
  CheckpointReader in(file);
  if (in.string() != c.spec)
    throw UserError("the checkpoint '" + file.string() + "' is of another movie than '" +
                    (dir / "movie.toml").string() + "' describes");
  Resumed r;
  const auto pass = in.value<std::uint32_t>();
  in.expect(pass == kRangePass || pass == kMoviePass);
  r.pass = static_cast<Pass>(pass);
  r.next = in.value<std::uint64_t>();
  in.expect(in.value<std::uint64_t>() == frames && r.next <= frames);
  const auto scans = in.value<std::uint64_t>();
  in.expect(scans == (r.pass == kRangePass ? r.next : plan.need_range ? frames : 0));
  r.scans.resize(scans);
  for (FrameScan& f : r.scans) {
    f.any_active = in.value<std::uint8_t>() != 0;
    in.value(f.range.first);
    in.value(f.range.second);
  }
  if (in.value<std::uint8_t>()) {
    r.follow.emplace(camera);
    r.follow->load(in);
  }
  r.parts = in.value<std::int32_t>();
  r.part_frames = in.value<std::int64_t>();
  // Every frame before the next one is in a whole part.
  in.expect(r.parts >= 0 && r.part_frames >= r.parts &&
            r.part_frames == (r.pass == kMoviePass ? std::int64_t(r.next) : 0));
  r.sim = load_simulation(physics, in);
  in.finish();
  return r;
}

// A finished movie joins its parts into movie.mp4, then removes its checkpoints, then its parts:
// a kill after the join leaves a finished movie whose leftovers only need removing.
FrontMovieResult remove_leftovers_of_finished(const std::filesystem::path& dir, bool quiet) {
  remove_movie_checkpoints(dir);
  std::error_code ec;
  std::filesystem::remove_all(render::MovieParts::folder(dir / "movie.mp4"), ec);
  if (!quiet)
    std::fprintf(stderr,
                 "grainshock: %s had finished; its leftover checkpoints and parts are "
                 "removed\n",
                 dir.c_str());
  return {0, false};
}

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
      return remove_leftovers_of_finished(dir, o.quiet);  // killed before its parts went
    }
    r = read_live_checkpoint(dir, *checkpoints, physics, p.plan, frames.size(),
                             make_follow(physics.dim, p.plan.view, o));
    // The parts are removed only once the movie is joined: the kill came after that.
    if (!render::MovieParts::on_disk(movie, r.parts) && std::filesystem::exists(movie))
      return remove_leftovers_of_finished(dir, o.quiet);
    pass = r.pass;
    p.scans = std::move(r.scans);
    frames.start_at(std::move(r.sim), r.next);
    ck->resumed();
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

struct StoredMovie::Impl {
  Impl(const std::vector<std::string>& files, const FrontMovieOptions& o)
      : frames(files, o.read), options(o) {}
  StoredFrames frames;
  Prepared prepared;
  FrontMovieOptions options;
  std::string first_name;  // the first frame given, which the others must fit
  int first_dim = 2;
  Eigen::Vector3d first_box = Eigen::Vector3d::Zero();
  bool ordered = false;  // the frames are known to be in order of time
};

namespace {

// Thrown by the drawing pass when frames given in the order of their files turn out not to be
// in order of time: the movie then starts again after a pass that orders them.
struct OutOfOrder {};

// UserError naming the frame unless it fits the first: dimension, box, the field's data.
void check_stored_frame(const StoredMovie::Impl& m, std::size_t k, const Snapshot& s) {
  const std::string name = m.frames.name(k);
  const render::Style& style = m.prepared.plan.style;
  if (s.info.dim != m.first_dim)
    throw UserError(name + " is " + std::to_string(s.info.dim) + "D but " + m.first_name + " is " +
                    std::to_string(m.first_dim) + "D: a movie's frames share one dimension");
  if ((s.info.box - m.first_box).cwiseAbs().maxCoeff() >
      1e-9 * std::max(1.0, m.first_box.maxCoeff())) {
    auto edges = [&](const Eigen::Vector3d& b) {
      std::string e = format_number(b[0]);
      for (int a = 1; a < s.info.dim; ++a) e += " x " + format_number(b[a]);
      return e;
    };
    throw UserError(name + " has box " + edges(s.info.box) + " but " + m.first_name + " has " +
                    edges(m.first_box) + ": a movie's frames share one box");
  }
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
  p.plan.style.field = render::choose_field(o.colour_by, s, files.front());
  if (p.plan.style.field == render::Field::Column) p.plan.style.column = o.colour_by;
  p.plan.style.scale = render::parse_scale(o.scale, p.plan.style.field);
  render::check_style(p.plan.style);
  check_orbit(s.info.dim, o, m.first_name);
  settle_range(p.plan, s.info.dim);
  check_stored_frame(m, 0, s);
  // What the reader assumed (masses, time from steps, wrapping), said once for the movie.
  if (!o.quiet)
    for (const auto& note : s.notes)
      std::fprintf(stderr, "grainshock: %s: %s\n", m.first_name.c_str(), note.c_str());
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
