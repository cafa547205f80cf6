// Renderer speed at 1920x1080 on synthetic scenes of the paper's sizes, readback included (the
// PNG or movie encoder is not). A frame is everything render() does: choose colours, cull,
// upload, draw, read back, draw the overlays.
#include <unistd.h>
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <memory>
#include <numbers>
#include <random>

#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>

#include "bench/bench.h"
#include "io/gsd.h"
#include "io/xyz.h"
#include "render/colormap.h"
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
  r.recycle(r.render(s, style, view));  // warm-up: shaders, buffers, framebuffer, the picture
  const double setup = std::chrono::duration<double, std::milli>(clock::now() - t0).count();
  std::vector<double> ms;
  const int frames = 7;
  const std::clock_t c0 = std::clock();
  for (int k = 0; k < frames; ++k) {
    t0 = clock::now();
    // Handed back as a movie's frame loop does once the frame is encoded.
    r.recycle(r.render(s, style, view));
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
// gsd: the snapshots as GSD files (HOOMD's binary format, parsed without text), else extended
// XYZ. Each of the 12 files is given 20 times: every frame is read and parsed again.
std::vector<Figure> stored_movie(bool gsd, const std::string& target) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / ("grainshock-bench-" + std::to_string(getpid()));
  fs::create_directories(dir);
  std::vector<std::string> args = {"/proc/self/exe", "movie"};
  for (int f = 0; f < 12; ++f) {
    Snapshot s = synthetic(2, 250000, 1000, 290 + 2.0 * f, 330 + 2.0 * f);
    s.info.time = 1000 + 100 * f;
    const std::string path = (dir / ("t_" + std::to_string(f) + (gsd ? ".gsd" : ".xyz"))).string();
    if (gsd)
      write_gsd(path, s);
    else
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
  return {{"frames_per_second", ok ? 240 / wall : 0, "1/s", target},
          {"frames_per_cpu_second", ok ? 240 / cpu : 0, "1/s", ""},
          {"cpu_ms_per_frame", ok ? 1e3 * cpu / 240 : 0, "ms", ""},
          {"load_average_1min", load_average(), "", ""},
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

// The limit a frame is measured against: the plainest banded splatter of the same
// discs, written for this bench only. Per frame it maps each particle to pixels (the box
// framed as render/discs_2.5e5 frames it), colours an active one by its speed through a
// 256-entry table on a fixed range, sorts the discs into bands of 32 rows (a counting sort),
// and on one thread fills each band with the background and stamps its discs: opaque (every
// pixel whose centre lies within the radius takes the colour) or antialiased (coverage from the
// distance to the rim, as the renderer's rule, blended in float). Buffers are kept across
// frames. What it leaves out of a real frame: percentiles, the colour bar and the time label.
class PlainSplat {
 public:
  explicit PlainSplat(bool antialiased) : aa_(antialiased) {}

  void frame(const Snapshot& s, int w, int h) {
    const double side = s.info.box[0];
    const double ppu = std::min(w, h) / side;
    const double x0 = s.info.origin[0] + side / 2 - w / (2 * ppu);
    const double y0 = s.info.origin[1] + side / 2 + h / (2 * ppu);  // world y of the top row
    const std::size_t n = s.size();
    discs_.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      const Eigen::Vector3d& p = s.position[i];
      std::uint32_t c = 0xffcececeu;  // inactive grey
      if (s.active[i]) {
        const double v = s.velocity[i].norm();
        c = lut_[static_cast<std::size_t>(std::clamp(v * (255 / 1.2), 0.0, 255.0))];
      }
      discs_[i] = {static_cast<float>((p.x() - x0) * ppu), static_cast<float>((y0 - p.y()) * ppu),
                   static_cast<float>(s.radius[i] * ppu), c};
    }
    const int bands = (h + kBand - 1) / kBand;
    start_.assign(bands + 2, 0);
    for (const Disc& d : discs_)
      for (int b = band(d.y - d.r - 0.5f, bands); b <= band(d.y + d.r + 0.5f, bands); ++b)
        ++start_[b + 1];
    for (int b = 0; b < bands; ++b) start_[b + 1] += start_[b];
    binned_.resize(start_[bands]);
    fill_.assign(start_.begin(), start_.end() - 1);
    for (const Disc& d : discs_)
      for (int b = band(d.y - d.r - 0.5f, bands); b <= band(d.y + d.r + 0.5f, bands); ++b)
        binned_[fill_[b]++] = d;
    pixels_.resize(static_cast<std::size_t>(w) * h);
    for (int b = 0; b < bands; ++b) {
      const int r0 = b * kBand, r1 = std::min(h, r0 + kBand);
      std::fill(pixels_.begin() + static_cast<std::ptrdiff_t>(r0) * w,
                pixels_.begin() + static_cast<std::ptrdiff_t>(r1) * w, 0xffffffffu);
      for (std::uint32_t k = start_[b]; k < start_[b + 1]; ++k)
        aa_ ? smooth(binned_[k], w, r0, r1) : stamp(binned_[k], w, r0, r1);
    }
  }
  std::size_t checksum() const {
    std::size_t sum = 0;
    for (std::uint32_t p : pixels_) sum += p & 0xffffff;
    return sum;
  }

 private:
  static constexpr int kBand = 32;
  struct Disc {
    float x, y, r;
    std::uint32_t rgba;
  };
  static int band(float y, int bands) {
    return std::clamp(static_cast<int>(std::floor(y)) / kBand, 0, bands - 1);
  }
  void stamp(const Disc& d, int w, int r0, int r1) {
    const float r2 = d.r * d.r;
    const int ya = std::max(r0, static_cast<int>(std::ceil(d.y - d.r - 0.5f)));
    const int yb = std::min(r1 - 1, static_cast<int>(std::floor(d.y + d.r - 0.5f)));
    for (int y = ya; y <= yb; ++y) {
      const float dy = y + 0.5f - d.y, half = std::sqrt(std::max(r2 - dy * dy, 0.0f));
      const int xa = std::max(0, static_cast<int>(std::ceil(d.x - half - 0.5f)));
      const int xb = std::min(w - 1, static_cast<int>(std::floor(d.x + half - 0.5f)));
      std::uint32_t* row = &pixels_[static_cast<std::size_t>(y) * w];
      for (int x = xa; x <= xb; ++x) row[x] = d.rgba;
    }
  }
  void smooth(const Disc& d, int w, int r0, int r1) {
    const int ya = std::max(r0, static_cast<int>(std::floor(d.y - d.r)));
    const int yb = std::min(r1 - 1, static_cast<int>(std::ceil(d.y + d.r)) - 1);
    const int xa = std::max(0, static_cast<int>(std::floor(d.x - d.r)));
    const int xb = std::min(w - 1, static_cast<int>(std::ceil(d.x + d.r)) - 1);
    const float cr = float(d.rgba & 0xff), cg = float(d.rgba >> 8 & 0xff),
                cb = float(d.rgba >> 16 & 0xff);
    for (int y = ya; y <= yb; ++y) {
      const float dy = y + 0.5f - d.y;
      std::uint32_t* row = &pixels_[static_cast<std::size_t>(y) * w];
      for (int x = xa; x <= xb; ++x) {
        const float dx = x + 0.5f - d.x;
        const float a = std::min(d.r + 0.5f - std::sqrt(dx * dx + dy * dy), 1.0f);
        if (a <= 0) continue;
        const std::uint32_t p = row[x];
        const float pr = float(p & 0xff), pg = float(p >> 8 & 0xff), pb = float(p >> 16 & 0xff);
        row[x] = 0xff000000u | static_cast<std::uint32_t>(pr + a * (cr - pr) + 0.5f) |
                 static_cast<std::uint32_t>(pg + a * (cg - pg) + 0.5f) << 8 |
                 static_cast<std::uint32_t>(pb + a * (cb - pb) + 0.5f) << 16;
      }
    }
  }

  bool aa_;
  std::vector<Disc> discs_, binned_;
  std::vector<std::uint32_t> start_, fill_, pixels_;
  std::array<std::uint32_t, 256> lut_ = [] {
    std::array<std::uint32_t, 256> t{};
    const render::Colormap m = render::Colormap::by_name("magma");
    for (int i = 0; i < 256; ++i) {
      const render::Rgb8 c = m.at8(i / 255.0);
      t[i] = 0xff000000u | c[0] | c[1] << 8 | std::uint32_t(c[2]) << 16;
    }
    return t;
  }();
};

std::vector<Figure> plain_splat(bool antialiased, const std::string& target) {
  const auto s = synthetic(2, 250000, 1000, 300, 330);
  PlainSplat p(antialiased);
  p.frame(s, 1920, 1080);
  const int frames = 15;
  std::vector<double> cpu;
  for (int k = 0; k < frames; ++k) {
    const double c0 = cpu_seconds();
    p.frame(s, 1920, 1080);
    cpu.push_back(1e3 * (cpu_seconds() - c0));
  }
  std::sort(cpu.begin(), cpu.end());
  return {{"cpu_ms_per_frame", cpu[cpu.size() / 2], "ms", target},
          {"cpu_ms_per_frame_min", cpu.front(), "ms", ""},
          {"checksum", static_cast<double>(p.checksum() % 1000000), "", ""}};
}

// LAMMPS `dump image` of render/discs_2.5e5's scene, the program physicists compare with: the
// same 2.5e5 discs in the same box, 1920x1080, type 1 inactive and type 2 active, written as PPM
// (no PNG encoding). The cost of an image is the CPU time of `run 20` less that of `run 0` (set-up
// and the image every run writes at its start), over 20. Skipped (exit_ok 0) when `lmp` is not on
// the PATH.
double lammps_cpu_seconds(const std::filesystem::path& dir, int images) {
  const std::string in = (dir / ("in." + std::to_string(images))).string();
  {
    std::ofstream f(in);
    f << "units lj\ndimension 2\nboundary p p p\natom_style atomic\nread_data "
      << (dir / "scene.data").string() << "\nmass * 1\npair_style zero 1.0\npair_coeff * *\n"
      << "neighbor 0.3 bin\nneigh_modify delay 0 every 1000000 check no\n"
      << "dump d all image 1 " << (dir / ("img" + std::to_string(images) + ".*.ppm")).string()
      << " type type size 1920 1080 view 0 0 zoom 1.77 box no 0.0\n"
      << "dump_modify d adiam * 1.0 backcolor white acolor 1 gray acolor 2 orange\n"
      << "run " << images << "\n";
  }
  std::vector<std::string> args = {"lmp", "-in", in, "-log", "none", "-screen", "none"};
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  rusage before{}, after{};
  getrusage(RUSAGE_CHILDREN, &before);
  pid_t pid = -1;
  int status = -1;
  if (posix_spawnp(&pid, "lmp", nullptr, nullptr, argv.data(), environ) != 0) return -1;
  waitpid(pid, &status, 0);
  getrusage(RUSAGE_CHILDREN, &after);
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) return -1;
  auto secs = [](const timeval& t) { return t.tv_sec + 1e-6 * t.tv_usec; };
  return secs(after.ru_utime) - secs(before.ru_utime) + secs(after.ru_stime) -
         secs(before.ru_stime);
}

std::vector<Figure> lammps_dump_image() {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / ("grainshock-lmp-" + std::to_string(getpid()));
  fs::create_directories(dir);
  const auto s = synthetic(2, 250000, 1000, 300, 330);
  {
    std::ofstream f(dir / "scene.data");
    f << "render/discs_2.5e5's scene\n\n" << s.size() << " atoms\n2 atom types\n\n"
      << "0 1000 xlo xhi\n0 1000 ylo yhi\n-0.5 0.5 zlo zhi\n\nAtoms # atomic\n\n";
    f.precision(10);
    for (std::size_t i = 0; i < s.size(); ++i)
      f << i + 1 << ' ' << (s.active[i] ? 2 : 1) << ' ' << s.position[i].x() << ' '
        << s.position[i].y() << " 0\n";
  }
  const int images = 20;
  double per_image = -1;
  const double none = lammps_cpu_seconds(dir, 0);
  const double some = none < 0 ? -1 : lammps_cpu_seconds(dir, images);
  if (some >= 0) per_image = 1e3 * (some - none) / images;
  fs::remove_all(dir);
  // Ours on the same scene, in the same process: the ratio of two CPU times measured minutes
  // apart at most.
  render::Style st;
  st.show_inactive = true;
  auto v = full_hd();
  v.framing = render::Framing::Box;
  const auto ours = measure(s, st, v, "");
  const double ours_cpu = ours[2].value;
  return {{"lammps_cpu_ms_per_image", per_image, "ms", ""},
          {"grainshock_cpu_ms_per_frame", ours_cpu, "ms", ""},
          {"lammps_over_grainshock", per_image > 0 ? per_image / ours_cpu : 0, "", ">= 5"},
          {"exit_ok", per_image > 0 ? 1.0 : 0.0, "", "1"}};
}

}  // namespace

void add_render_cases(std::vector<Case>& cases) {
  cases.push_back({"movie/stored_2d_240",
                   "grainshock movie of 240 stored 2D snapshots of 2.5e5 discs, 1920x1080", true,
                   [] { return stored_movie(false, ">= 15 on 2 cores"); }});
  cases.push_back({"movie/stored_2d_240_gsd",
                   "the same from GSD snapshots", true,
                   [] { return stored_movie(true, ">= 30 on 2 cores"); }});
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
         // 167 ms of CPU before the discs were splatted by bands of rows on two threads; issue
         // 32 asks for 15 ms, within 1.5x of render/plain_splat_2.5e5.
         return measure(s, st, v, "cpu <= 15 ms");
       }});
  cases.push_back({"render/plain_splat_2.5e5",
                   "the limit: a plain banded splatter of render/discs_2.5e5's discs, opaque",
                   false, [] { return plain_splat(false, ""); }});
  cases.push_back({"render/plain_splat_aa_2.5e5",
                   "the limit: a plain banded splatter of render/discs_2.5e5's discs, antialiased",
                   false, [] { return plain_splat(true, ""); }});
  cases.push_back({"render/lammps_dump_image_2.5e5",
                   "LAMMPS dump image (PPM) of render/discs_2.5e5's scene against ours", true,
                   lammps_dump_image});
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
