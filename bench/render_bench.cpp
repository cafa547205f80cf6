// Renderer speed at 1920x1080 on synthetic scenes of the paper's sizes, readback included (the
// PNG or movie encoder is not). A frame is everything render() does: choose colours, cull,
// upload, draw, read back, draw the overlays.
#include <unistd.h>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <filesystem>
#include <memory>
#include <numbers>
#include <random>

#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>

#include "bench/bench.h"
#include "io/xyz.h"
#include "render/movie_writer.h"
#include "render/png.h"
#include "render/renderer.h"

namespace gs::bench {
namespace {

// Uniform particles in a periodic box of side L; those within [r_in, r_out] of the centre are
// active and move outward faster towards the inner edge, like the band of a kicked gas.
Snapshot synthetic(int dim, std::size_t n, double box, double r_in, double r_out) {
  Snapshot s;
  s.info.dim = dim;
  s.info.set_cubic_box(box);
  s.info.time = 1000;
  s.info.density = 0.25;
  std::mt19937_64 rng(2024);
  std::uniform_real_distribution<double> u(0, box);
  const Eigen::Vector3d c = Eigen::Vector3d::Constant(box / 2);
  s.position.resize(n);
  s.velocity.resize(n);
  s.radius.assign(n, 0.5);
  s.active.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    Eigen::Vector3d p(u(rng), u(rng), dim == 3 ? u(rng) : 0.0);
    s.position[i] = p;
    const Eigen::Vector3d d = p - Eigen::Vector3d(c.x(), c.y(), dim == 3 ? c.z() : 0.0);
    const double r = d.norm();
    s.active[i] = r >= r_in && r <= r_out;
    s.velocity[i] = s.active[i] ? Eigen::Vector3d(d / r * (0.1 + (r_out - r) / (r_out - r_in)))
                                : Eigen::Vector3d::Zero();
  }
  return s;
}

// Uniform particles where every one is active but only a band is present: the 2e4 active
// discs of a paper-size 2D run with nothing else drawn.
Snapshot band_only(std::size_t n, double box, double r_in, double r_out) {
  Snapshot s;
  s.info.dim = 2;
  s.info.set_cubic_box(box);
  s.info.time = 1000;
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0, 1);
  for (std::size_t i = 0; i < n; ++i) {
    const double a = 2 * std::numbers::pi * u(rng);
    const double r = std::sqrt(r_in * r_in + (r_out * r_out - r_in * r_in) * u(rng));
    const Eigen::Vector3d d(std::cos(a), std::sin(a), 0);
    s.position.push_back(Eigen::Vector3d(box / 2, box / 2, 0) + r * d);
    s.velocity.push_back(d * (0.1 + (r_out - r) / (r_out - r_in)));
    s.radius.push_back(0.5);
    s.active.push_back(1);
  }
  return s;
}

std::vector<Figure> measure(const Snapshot& s, const render::Style& style, const render::View& view,
                            const std::string& target) {
  using clock = std::chrono::steady_clock;
  auto t0 = clock::now();
  render::Renderer r;
  r.render(s, style, view);  // warm-up: shader compilation, buffer and framebuffer allocation
  const double setup = std::chrono::duration<double, std::milli>(clock::now() - t0).count();
  std::vector<double> ms;
  const int frames = 7;
  const std::clock_t c0 = std::clock();
  for (int k = 0; k < frames; ++k) {
    t0 = clock::now();
    r.render(s, style, view);
    ms.push_back(std::chrono::duration<double, std::milli>(clock::now() - t0).count());
  }
  // CPU time of all threads (llvmpipe's rasterizer included): on a shared machine it says what
  // a frame costs when wall time is inflated by other processes.
  const double cpu_ms = 1000.0 * double(std::clock() - c0) / CLOCKS_PER_SEC / frames;
  std::sort(ms.begin(), ms.end());
  return {{"ms_per_frame_median", ms[ms.size() / 2], "ms", target},
          {"ms_per_frame_max", ms.back(), "ms", ""},
          {"cpu_ms_per_frame", cpu_ms, "ms", ""},
          {"first_frame_with_setup", setup, "ms", ""},
          {"particles_drawn", static_cast<double>(r.last().drawn), "", ""}};
}

render::View full_hd() {
  render::View v;
  v.width = 1920;
  v.height = 1080;
  return v;
}

// `grainshock movie FILE...` as a user runs it: 240 frames from 12 stored 2D snapshots of 2.5e5
// discs (a band of ~2e4 active discs growing from file to file), each file given 20 times, at
// 1920x1080, reading included. The child's wall and CPU time are the figures.
std::vector<Figure> stored_movie() {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / ("grainshock-bench-" + std::to_string(getpid()));
  fs::create_directories(dir);
  std::vector<std::string> args = {"/proc/self/exe", "movie"};
  for (int f = 0; f < 12; ++f) {
    Snapshot s = synthetic(2, 250000, 1000, 290 + 2.0 * f, 330 + 2.0 * f);
    s.info.time = 1000 + 100 * f;
    const std::string path = (dir / ("t_" + std::to_string(f) + ".xyz")).string();
    write_xyz(path, s);
    for (int k = 0; k < 20; ++k) args.push_back(path);
  }
  for (const char* a : {"--width", "1920", "--height", "1080", "--quiet", "--out"})
    args.push_back(a);
  args.push_back((dir / "out").string());
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  rusage before{}, after{};
  getrusage(RUSAGE_CHILDREN, &before);
  const double t0 = wall_seconds();
  pid_t pid = -1;
  int status = -1;
  if (posix_spawn(&pid, argv[0], nullptr, nullptr, argv.data(), environ) == 0)
    waitpid(pid, &status, 0);
  const double wall = wall_seconds() - t0;
  getrusage(RUSAGE_CHILDREN, &after);
  auto secs = [](const timeval& t) { return t.tv_sec + 1e-6 * t.tv_usec; };
  const double cpu =
      secs(after.ru_utime) - secs(before.ru_utime) + secs(after.ru_stime) - secs(before.ru_stime);
  fs::remove_all(dir);
  const bool ok = WIFEXITED(status) && WEXITSTATUS(status) == 0;
  return {{"frames_per_second", ok ? 240 / wall : 0, "1/s", ">= 10 on 2 cores"},
          {"frames_per_cpu_second", ok ? 240 / cpu : 0, "1/s", ""},
          {"exit_ok", ok ? 1.0 : 0.0, "", "1"}};
}

// The frame loop of a 3D orbit movie: a 2e6-sphere box with a shell of active spheres, cut by
// the movies' default slab of 6, the camera turning 90 degrees over 30 frames, 1280x720, H.264.
std::vector<Figure> orbit_movie() {
  const auto s = synthetic(3, 2000000, 200, 60, 64);
  render::Renderer r;
  render::Style st;
  st.field = render::Field::ScaledSpeed;
  render::View v;
  v.width = 1280;
  v.height = 720;
  v.slab = 6;
  render::MovieOptions o;
  o.width = 1280;
  o.height = 720;
  const auto path = std::filesystem::temp_directory_path() /
                    ("grainshock-bench-" + std::to_string(getpid()) + ".mp4");
  const int frames = 30;
  const double t0 = wall_seconds(), c0 = cpu_seconds();
  {
    render::MovieWriter movie(path, o);
    for (int k = 0; k < frames; ++k) {
      v.azimuth = 30 + 90.0 * k / (frames - 1);
      movie.add(r.render(s, st, v));
    }
    movie.finish();
  }
  const double wall = wall_seconds() - t0, cpu = cpu_seconds() - c0;
  std::filesystem::remove(path);
  return {{"frames_per_second", frames / wall, "1/s", ">= 5"},
          {"frames_per_cpu_second", frames / cpu, "1/s", ""}};
}

// What the inset profile adds to a frame of the Fig. 1 job's kind: 2e4 active discs in a band.
std::vector<Figure> inset_cost() {
  const auto s = synthetic(2, 250000, 1000, 300, 340);
  render::Renderer r;
  render::Style st;
  st.field = render::Field::ScaledSpeed;
  const render::View v = full_hd();
  r.render(s, st, v);
  std::vector<double> plain, inset;
  for (int k = 0; k < 9; ++k)
    for (bool with : {false, true}) {
      st.inset = with;
      const double c0 = cpu_seconds();
      r.render(s, st, v);
      (with ? inset : plain).push_back(1e3 * (cpu_seconds() - c0));
    }
  std::sort(plain.begin(), plain.end());
  std::sort(inset.begin(), inset.end());
  const double a = plain[plain.size() / 2], b = inset[inset.size() / 2];
  return {{"cpu_ms_per_frame", a, "ms", ""},
          {"cpu_ms_per_frame_with_inset", b, "ms", ""},
          {"inset_extra_fraction", b / a - 1, "", "<= 0.05"}};
}

}  // namespace

void add_render_cases(std::vector<Case>& cases) {
  cases.push_back({"movie/stored_2d_240",
                   "grainshock movie of 240 stored 2D snapshots of 2.5e5 discs, 1920x1080", true,
                   stored_movie});
  cases.push_back({"movie/orbit_3d_2e6", "3D orbit movie frame loop, 2e6 spheres, slab 6, 1280x720",
                   true, orbit_movie});
  cases.push_back({"render/inset_cost",
                   "the inset profile's share of a 2D frame (2e4 active of 2.5e5), 1920x1080",
                   false, inset_cost});
  cases.push_back(
      {"render/discs_2.5e5", "2D, 2.5e5 discs (whole box, inactive shown), 1920x1080", false, [] {
         const auto s = synthetic(2, 250000, 1000, 300, 330);
         render::Style st;
         st.show_inactive = true;
         auto v = full_hd();
         v.framing = render::Framing::Box;
         // 167 ms of CPU before the discs were splatted by bands of rows on two threads.
         return measure(s, st, v, "cpu <= 56 ms");
       }});
  cases.push_back(
      {"render/discs_2e4_active", "2D, 2e4 active discs in a band, fitted, 1920x1080", false, [] {
         const auto s = band_only(20000, 1000, 300, 330);
         return measure(s, render::Style{}, full_hd(), "<= 40 ms");
       }});
  cases.push_back({"render/spheres_2e6",
                   "3D, 2e6 spheres in a 200^3 box, active shell drawn, 1920x1080", false, [] {
                     const auto s = synthetic(3, 2000000, 200, 60, 64);
                     return measure(s, render::Style{}, full_hd(), "<= 1 s");
                   }});
  cases.push_back({"render/spheres_2e6_slab",
                   "3D, 2e6 spheres, slab of 6 with inactive shown, 1920x1080", true, [] {
                     const auto s = synthetic(3, 2000000, 200, 60, 64);
                     render::Style st;
                     st.show_inactive = true;
                     auto v = full_hd();
                     v.slab = 6;
                     return measure(s, st, v, "<= 1 s");
                   }});
  cases.push_back(
      {"render/png_1080p", "PNG writing of a 1920x1080 frame, levels 1 and 6", false, [] {
         const auto s = synthetic(2, 250000, 1000, 300, 330);
         render::Style st;
         st.show_inactive = true;
         render::Renderer r;
         const render::Image img = r.render(s, st, full_hd());
         const auto path = std::filesystem::temp_directory_path() /
                           ("grainshock_bench_" + std::to_string(::getpid()) + ".png");
         std::vector<Figure> out;
         for (int level : {1, 6}) {
           double best = 1e300;
           for (int k = 0; k < 3; ++k) {
             const auto t0 = std::chrono::steady_clock::now();
             render::write_png(path.string(), img, {}, level);
             best = std::min(best, std::chrono::duration<double, std::milli>(
                                       std::chrono::steady_clock::now() - t0)
                                       .count());
           }
           out.push_back({"write_ms_level" + std::to_string(level), best, "ms",
                          level == 1 ? "well under level 6" : ""});
           out.push_back({"bytes_level" + std::to_string(level),
                          static_cast<double>(std::filesystem::file_size(path)), "B", ""});
         }
         std::filesystem::remove(path);
         return out;
       }});
  cases.push_back({"render/spheres_2e6_whole",
                   "3D, 2e6 spheres, all shown (occlusion culling), 1920x1080", true, [] {
                     const auto s = synthetic(3, 2000000, 200, 60, 64);
                     render::Style st;
                     st.show_inactive = true;
                     render::View v = full_hd();
                     v.framing = render::Framing::Box;
                     return measure(s, st, v, "<= 1 s");
                   }});
}

}  // namespace gs::bench
