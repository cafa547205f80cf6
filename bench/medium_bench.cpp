// The unbounded medium (sim/unbounded_medium.h): how fast cells are made as a front would ask
// for them, and what the generator's memo costs per particle made.
#include <algorithm>
#include <cmath>
#include <vector>

#include "bench/bench.h"
#include "sim/unbounded_medium.h"

namespace gs::bench {
namespace {

// The cells of a ball of `radius` cells around the origin, made nearest first, as a growing
// front makes them; the memo then holds the ball and the halo its chains reached.
template <int D>
std::vector<Figure> front(double density, int radius) {
  using Cell = typename UnboundedMedium<D>::Cell;
  std::vector<Cell> cells;
  Cell c;
  c.fill(-radius);
  for (;;) {
    double r2 = 0;
    for (int k = 0; k < D; ++k) r2 += (c[k] + 0.5) * (c[k] + 0.5);
    if (r2 <= static_cast<double>(radius) * radius) cells.push_back(c);
    int k = 0;
    while (k < D && c[k] == radius) c[k] = -radius, ++k;
    if (k == D) break;
    ++c[k];
  }
  auto r2 = [](const Cell& a) {
    double s = 0;
    for (const auto x : a) s += static_cast<double>(x) * static_cast<double>(x);
    return s;
  };
  std::stable_sort(cells.begin(), cells.end(),
                   [&](const Cell& a, const Cell& b) { return r2(a) < r2(b); });
  MediumOptions o;
  o.dim = D;
  o.density = density;
  UnboundedMedium<D> medium(o);
  VecArray<D> x;
  x.reserve(static_cast<std::size_t>(1.2 * density * static_cast<double>(cells.size())));
  const double cpu0 = cpu_seconds();
  for (const auto& cell : cells) medium.particles(cell, x);
  const double cpu = cpu_seconds() - cpu0;
  const auto made = static_cast<double>(x.size());
  return {{"cells_per_cpu_second", static_cast<double>(cells.size()) / cpu, "1/s", ""},
          {"particles_per_cpu_second", made / cpu, "1/s", ""},
          {"memo_bytes_per_particle", static_cast<double>(medium.memory_bytes()) / made, "B", ""},
          {"candidates_per_particle", static_cast<double>(medium.cached_candidates()) / made, "",
           ""},
          {"particles", made, "", ""}};
}

}  // namespace

void add_medium_cases(std::vector<Case>& cases) {
  cases.push_back({"medium/front2d_0.25", "unbounded medium, 2D, n = 0.25: a ball of radius 600",
                   false, [] { return front<2>(0.25, 600); }});
  cases.push_back({"medium/front3d_0.25", "unbounded medium, 3D, n = 0.25: a ball of radius 60",
                   false, [] { return front<3>(0.25, 60); }});
  cases.push_back({"medium/front2d_0.5", "unbounded medium, 2D, n = 0.5 (packing 0.39)", false,
                   [] { return front<2>(0.5, 300); }});
}

}  // namespace gs::bench
