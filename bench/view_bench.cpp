// The page of `grainshock view`: its size and the time to write it for frames of the Fig. 1 job's
// size (2D, the box of 2.5e5 discs), and for one frame of a 2e6-sphere 3D run. The browser's side
// (load time, frame switch) is measured by bench/view_browser_bench.py in headless Chromium.
#include <chrono>
#include <cmath>
#include <numbers>
#include <random>

#include "bench/bench.h"
#include "jobs/view_job.h"

namespace gs::bench {
namespace {

// A kick's band: `active` particles between r_in and r_out about the box's centre, moving out.
Snapshot band(int dim, std::size_t active, double r_in, double r_out, double t) {
  Snapshot s;
  s.info.dim = dim;
  s.info.time = t;
  s.info.density = 0.25;
  std::mt19937_64 rng(11);
  std::normal_distribution<double> g;
  std::uniform_real_distribution<double> u(0, 1);
  for (std::size_t i = 0; i < active; ++i) {
    Eigen::Vector3d d(g(rng), g(rng), dim == 3 ? g(rng) : 0.0);
    d.normalize();
    const double r = r_in + (r_out - r_in) * std::pow(u(rng), 1.0 / dim);
    s.position.push_back(r * d);
    s.velocity.push_back(d * (0.1 + (r_out - r) / (r_out - r_in)) * 0.01);
    s.radius.push_back(0.5);
    s.active.push_back(1);
    s.first_collision.push_back(t * u(rng));
  }
  return s;
}

std::vector<Figure> page_of(const std::vector<Snapshot>& snaps, const std::string& target) {
  std::vector<const Snapshot*> ptrs;
  for (const auto& s : snaps) ptrs.push_back(&s);
  jobs::ViewOptions o;
  o.max_mb = 1e4;  // nothing left out: the size is what is measured
  const auto t0 = std::chrono::steady_clock::now();
  const std::string html = jobs::view_page(ptrs, o);
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::size_t particles = 0;
  for (const auto& x : snaps) particles += x.size();
  return {{"page_mb", html.size() / 1e6, "MB", target},
          {"bytes_per_particle_frame", double(html.size()) / particles, "B", ""},
          {"write_seconds", s, "s", ""}};
}

}  // namespace

void add_view_cases(std::vector<Case>& cases) {
  // The Fig. 1 job's four frames drawn by `render` hold its active discs; at most the box's 2.5e5
  // each (a band of 2.5e5 is more than the paper's Fig. 1 shows at t_paper = 50000): an upper
  // bound of the default job's page, stills and plots aside (a few hundred kB).
  cases.push_back(
      {"view/page_fig1_bound", "grainshock view: 4 frames of 2.5e5 active discs", false, [] {
         std::vector<Snapshot> s;
         for (int k = 0; k < 4; ++k)
           s.push_back(band(2, 250000, 100 + 100 * k, 330 + 100 * k, 1e3 * (k + 1)));
         return page_of(s, "< 20 MB (the default job's page)");
       }});
  cases.push_back({"view/page_3d_2e6", "grainshock view: one frame of 2e6 active spheres", true,
                   [] { return page_of({band(3, 2000000, 60, 90, 1e4)}, ""); }});
}

}  // namespace gs::bench
