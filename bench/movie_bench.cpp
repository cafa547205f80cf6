// Speed of movies: the writer alone on frames like those of a front-propagation movie, and the
// whole `grainshock movie` frame loop (simulate, render, encode) on a real run.
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <ctime>
#include <filesystem>
#include <random>

#include "bench/bench.h"
#include "render/movie_writer.h"
#include "render/renderer.h"
#include "sim/engine.h"

namespace gs::bench {

namespace {

using render::Image;

// A 2D kick seen from above: a dark background, dim grey particles at rest and a ring-shaped band
// of 2e4 particles coloured by speed, each moving outward at its own speed with some sideways
// drift, so that the band both moves and changes inside. Flat or noise frames would make the
// encoder look much faster or much slower than it is on real movies.
class Scene {
 public:
  Scene(int w, int h) : w_(w), h_(h) {
    std::mt19937_64 rng(12345);
    std::uniform_real_distribution<double> u(0, 1);
    const double scale = h / 720.0;
    radius_ = 2.2 * scale;
    for (int i = 0; i < 40000; ++i) rest_.push_back({u(rng) * w, u(rng) * h, 0, 0});
    for (int i = 0; i < 20000; ++i) {
      const double angle = 2 * M_PI * u(rng);
      band_.push_back({angle, 0.3 * h * (1 - 0.25 * u(rng)), u(rng), 0.004 * (u(rng) - 0.5)});
    }
  }

  Image frame(int k) const {
    Image img(w_, h_);
    for (std::size_t i = 0; i < img.rgba.size(); i += 4) {
      img.rgba[i] = 10, img.rgba[i + 1] = 12, img.rgba[i + 2] = 20, img.rgba[i + 3] = 255;
    }
    const double cx = w_ / 2.0, cy = h_ / 2.0;
    for (const auto& p : rest_) disc(img, p.a, p.b, {70, 70, 80});
    for (const auto& p : band_) {
      const double r = p.b + (0.5 + 2 * p.c) * k;
      const double a = p.a + p.d * k;
      disc(img, cx + r * std::cos(a), cy + r * std::sin(a), speed_colour(p.c));
    }
    return img;
  }

 private:
  struct P {
    double a, b, c, d;  // rest: x, y; band: angle, radius, speed in [0, 1], angular drift
  };
  struct Rgb {
    double r, g, b;
  };

  // Blue (slow) to yellow (fast), roughly viridis.
  static Rgb speed_colour(double s) { return {255 * s * s, 40 + 180 * s, 140 * (1 - s) + 40}; }

  void disc(Image& img, double x0, double y0, Rgb c) const {
    const double r = radius_;
    for (int y = std::max(0, int(y0 - r - 1)); y <= std::min(h_ - 1, int(y0 + r + 1)); ++y)
      for (int x = std::max(0, int(x0 - r - 1)); x <= std::min(w_ - 1, int(x0 + r + 1)); ++x) {
        const double cover = std::clamp(r + 0.5 - std::hypot(x - x0, y - y0), 0.0, 1.0);
        if (cover <= 0) continue;
        std::uint8_t* p = img.pixel(x, y);
        p[0] = static_cast<std::uint8_t>(p[0] + (c.r - p[0]) * cover);
        p[1] = static_cast<std::uint8_t>(p[1] + (c.g - p[1]) * cover);
        p[2] = static_cast<std::uint8_t>(p[2] + (c.b - p[2]) * cover);
      }
  }

  int w_, h_;
  double radius_;
  std::vector<P> rest_, band_;
};

std::vector<Figure> encode(int w, int h, const std::string& codec, const std::string& target) {
  // A short loop of frames played forwards and backwards: the motion stays smooth and drawing
  // them is not part of the measurement.
  const Scene scene(w, h);
  std::vector<Image> pool;
  const int unique = 12;
  for (int k = 0; k < unique; ++k) pool.push_back(scene.frame(k));
  const int frames = 150;

  const auto path = std::filesystem::temp_directory_path() /
                    ("grainshock-bench-" + std::to_string(getpid()) + ".mp4");
  render::MovieOptions o;
  o.codec = codec;
  o.width = w;
  o.height = h;
  const std::clock_t cpu0 = std::clock();
  const auto t0 = std::chrono::steady_clock::now();
  {
    render::MovieWriter movie(path, o);
    for (int i = 0; i < frames; ++i) {
      const int phase = i % (2 * unique - 2);
      movie.add(pool[phase < unique ? phase : 2 * unique - 2 - phase]);
    }
    movie.finish();
  }
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const double cpu = double(std::clock() - cpu0) / CLOCKS_PER_SEC;
  const double bytes = double(std::filesystem::file_size(path));
  std::filesystem::remove(path);
  return {
      {"frames_per_second", frames / wall, "1/s", target},
      // CPU time of the whole process (worker, encoder threads, the copies in add()): this one
      // does not depend on what else the machine is doing.
      {"frames_per_cpu_second", frames / cpu, "1/s", ""},
      {"kilobytes_per_frame", bytes / frames / 1e3, "kB", ""},
  };
}

// The frame loop of `grainshock movie` on a 2D run with about 2e4 active particles: elastic
// (r = 1, the paper's Fig. 1(b)), because the inelastic band needs far longer to gather that
// many. Frames follow the front as in the command; the colour range is fixed.
std::vector<Figure> pipeline(int w, int h, const std::string& target) {
  PhysicsConfig c;
  c.dim = 2;
  c.particles = 250000;
  c.restitution = 1;
  c.t_max = 9000;
  c.kick_site = KickSite::Centre;
  auto sim = make_simulation(c);
  sim->run_until(7000);  // about 2e4 active particles by then

  render::Renderer renderer;
  render::Style style;
  style.background = render::Background::Dark;
  style.scale = render::Scale::Log;
  style.range = std::pair{1e-3, 1.0};
  render::View view;
  view.width = w;
  view.height = h;
  const auto path = std::filesystem::temp_directory_path() /
                    ("grainshock-bench-" + std::to_string(getpid()) + ".mp4");
  render::MovieOptions o;
  o.width = w;
  o.height = h;

  const int frames = 60;
  double simulate = 0, copy = 0, draw = 0, wait = 0, flush = 0;
  std::int64_t active = 0;
  using Clock = std::chrono::steady_clock;
  auto since = [](Clock::time_point t0) {
    return std::chrono::duration<double>(Clock::now() - t0).count();
  };
  const auto start = Clock::now();
  {
    render::MovieWriter movie(path, o);
    Snapshot snap;
    for (int k = 1; k <= frames; ++k) {
      auto t0 = Clock::now();
      sim->run_until(7000 + 2000.0 * k / frames);
      simulate += since(t0);
      t0 = Clock::now();
      sim->snapshot(snap);
      copy += since(t0);
      t0 = Clock::now();
      render::Image img = renderer.render(snap, style, view);
      draw += since(t0);
      t0 = Clock::now();
      movie.add(std::move(img));
      wait += since(t0);
    }
    const auto t0 = Clock::now();
    movie.finish();
    flush = since(t0);
  }
  const double wall = since(start);
  active = sim->sample().active;
  std::filesystem::remove(path);
  return {
      {"frames_per_second", frames / wall, "1/s", target},
      {"simulate_ms_per_frame", 1e3 * simulate / frames, "ms", ""},
      {"snapshot_ms_per_frame", 1e3 * copy / frames, "ms", ""},
      {"render_ms_per_frame", 1e3 * draw / frames, "ms", ""},
      // Time the frame loop waited for the encoder thread because its queue was full.
      {"encode_wait_ms_per_frame", 1e3 * wait / frames, "ms", "~0 (encoding never the bottleneck)"},
      // The frames still in the encoder's look-ahead when the loop ends, once per movie.
      {"final_flush_ms", 1e3 * flush, "ms", ""},
      {"active_particles", double(active), "", "about 2e4"},
  };
}

}  // namespace

void add_movie_cases(std::vector<Case>& cases) {
  cases.push_back({"movie/encode_h264_720p",
                   "movie writer alone, 1280x720, libx264 CRF 18 veryfast, 2e4 coloured discs",
                   false, [] { return encode(1280, 720, "h264", ""); }});
  cases.push_back(
      {"movie/encode_h264_1080p",
       "movie writer alone, 1920x1080, libx264 CRF 18 veryfast, 2e4 coloured discs", false,
       [] { return encode(1920, 1080, "h264", ">= 30 (encoding never the bottleneck)"); }});
  cases.push_back({"movie/encode_mpeg4_1080p",
                   "movie writer alone, 1920x1080, MPEG-4 Part 2 fallback (qscale 3)", false,
                   [] { return encode(1920, 1080, "mpeg4", ">= 30"); }});
  cases.push_back({"movie/pipeline_720p",
                   "grainshock movie frame loop, 2D r = 1 run with ~2e4 active, 1280x720", false,
                   [] { return pipeline(1280, 720, ""); }});
  cases.push_back({"movie/pipeline_1080p",
                   "grainshock movie frame loop, 2D r = 1 run with ~2e4 active, 1920x1080", false,
                   [] { return pipeline(1920, 1080, ""); }});
}

}  // namespace gs::bench
