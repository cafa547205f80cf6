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

#include "bench/bench.h"
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

}  // namespace

void add_render_cases(std::vector<Case>& cases) {
  cases.push_back(
      {"render/discs_2.5e5", "2D, 2.5e5 discs (whole box, inactive shown), 1920x1080", false, [] {
         const auto s = synthetic(2, 250000, 1000, 300, 330);
         render::Style st;
         st.show_inactive = true;
         auto v = full_hd();
         v.framing = render::Framing::Box;
         return measure(s, st, v, "<= 100 ms");
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
