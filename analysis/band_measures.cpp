#include "analysis/band_measures.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <vector>

#include "analysis/quantile.h"
#include "sim/error.h"
#include "sim/observables.h"

namespace gs {
namespace {

double ball(int d, double r) {
  return d == 2 ? std::numbers::pi * r * r : 4.0 / 3.0 * std::numbers::pi * r * r * r;
}

bool active_at(const Snapshot& s, std::size_t i) {
  return s.active.empty() || s.active[i] != 0;
}

double particle_volume(const Snapshot& s, std::size_t i, int d) {
  return ball(d, s.radius.empty() ? 0.5 : s.radius[i]);
}

double wrap(double x, double box) {
  return x - box * std::floor(x / box);
}

// Upper quantile q of v (sorted in place).
double quantile_of(std::vector<double>& v, double q) {
  std::sort(v.begin(), v.end());
  return sorted_quantile(v, q);
}

double densest_shifted_cell(const Snapshot& s, int d, const BandMeasureOptions& o) {
  const double box = s.info.cube_side();
  const auto n = std::max<std::int64_t>(1, std::int64_t(std::floor(box / o.cell)));
  const double side = box / double(n);
  const std::size_t cells = std::size_t(std::pow(double(n), d));
  std::vector<double> volume(cells);
  std::vector<std::uint8_t> holds(cells);
  double best = std::numeric_limits<double>::quiet_NaN();
  // Offsets (j0, j1, j2) * side / shifts: every combination along the d axes.
  const int combos = int(std::pow(o.shifts, d));
  for (int c = 0; c < combos; ++c) {
    double offset[3] = {0, 0, 0};
    for (int k = 0, m = c; k < d; ++k, m /= o.shifts) offset[k] = (m % o.shifts) * side / o.shifts;
    std::fill(volume.begin(), volume.end(), 0.0);
    std::fill(holds.begin(), holds.end(), 0);
    for (std::size_t i = 0; i < s.size(); ++i) {
      std::size_t key = 0;
      for (int k = d - 1; k >= 0; --k) {
        auto j = std::int64_t(std::floor(wrap(s.position[i][k] - offset[k], box) / side));
        j = std::min(j, n - 1);
        key = key * std::size_t(n) + std::size_t(j);
      }
      volume[key] += particle_volume(s, i, d);
      if (active_at(s, i)) holds[key] = 1;
    }
    const double cell_volume = std::pow(side, d);
    for (std::size_t k = 0; k < cells; ++k)
      if (holds[k] && !(volume[k] / cell_volume <= best)) best = volume[k] / cell_volume;
  }
  return best;
}

// Local packing within radius a of each active particle, from a periodic cell list of side >= a.
std::vector<double> local_packing(const Snapshot& s, int d, double a) {
  const double box = s.info.cube_side();
  const auto n = std::max<std::int64_t>(1, std::int64_t(std::floor(box / a)));
  const double side = box / double(n);
  const std::size_t cells = std::size_t(std::pow(double(n), d));
  std::vector<std::array<std::int64_t, 3>> cell_of(s.size());
  std::vector<std::uint32_t> start(cells + 1, 0), order(s.size());
  auto key_of = [&](const std::array<std::int64_t, 3>& c) {
    std::size_t key = 0;
    for (int k = d - 1; k >= 0; --k) key = key * std::size_t(n) + std::size_t(c[k]);
    return key;
  };
  for (std::size_t i = 0; i < s.size(); ++i) {
    std::array<std::int64_t, 3> c{0, 0, 0};
    for (int k = 0; k < d; ++k)
      c[k] = std::min(n - 1, std::int64_t(std::floor(wrap(s.position[i][k], box) / side)));
    cell_of[i] = c;
    ++start[key_of(c) + 1];
  }
  for (std::size_t k = 0; k < cells; ++k) start[k + 1] += start[k];
  {
    std::vector<std::uint32_t> fill(start.begin(), start.end() - 1);
    for (std::size_t i = 0; i < s.size(); ++i) order[fill[key_of(cell_of[i])]++] = std::uint32_t(i);
  }
  const int reach = n >= 3 ? 1 : 0;  // a box of fewer than 3 cells: every cell is a neighbour
  const int span = n >= 3 ? 3 : int(n);
  std::vector<double> out;
  const double ball_volume = ball(d, a);
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (!active_at(s, i)) continue;
    double filled = 0;
    const int combos = int(std::pow(span, d));
    for (int c = 0; c < combos; ++c) {
      std::array<std::int64_t, 3> nb{0, 0, 0};
      for (int k = 0, m = c; k < d; ++k, m /= span) {
        const std::int64_t j = n >= 3 ? cell_of[i][k] + (m % span) - reach : (m % span);
        nb[k] = ((j % n) + n) % n;
      }
      const std::size_t key = key_of(nb);
      for (std::uint32_t q = start[key]; q < start[key + 1]; ++q) {
        const std::size_t j = order[q];
        double r2 = 0;
        for (int k = 0; k < d; ++k) {
          double dx = wrap(s.position[j][k], box) - wrap(s.position[i][k], box);
          dx -= box * std::round(dx / box);
          r2 += dx * dx;
        }
        if (r2 <= a * a) filled += particle_volume(s, j, d);
      }
    }
    out.push_back(filled / ball_volume);
  }
  return out;
}

}  // namespace

double sphere_volume(int dim, double radius) { return ball(dim, radius); }

ShellFront shell_front(std::span<const double> distances, int dim, double ambient, double shell) {
  GS_CHECK(dim == 2 || dim == 3);
  GS_CHECK(shell > 0 && ambient > 0);
  ShellFront f;
  if (distances.empty()) return f;
  const double rmax = *std::max_element(distances.begin(), distances.end());
  const std::size_t bins = std::size_t(std::floor(rmax / shell)) + 2;  // the last ones are empty
  std::vector<double> density(bins, 0.0);
  for (double r : distances) density[std::min(bins - 1, std::size_t(r / shell))] += 1;
  for (std::size_t b = 0; b < bins; ++b)
    density[b] /= ball(dim, (b + 1) * shell) - ball(dim, b * shell);
  const std::size_t peak =
      std::size_t(std::max_element(density.begin(), density.end()) - density.begin());
  const double half = ambient / 2;
  if (!(density[peak] >= half)) return f;
  f.peak_density = density[peak];
  std::size_t j = peak + 1;
  while (density[j] >= half) ++j;  // the last shell is empty, so this stops
  // Linear between the centres of shells j - 1 and j.
  const double c0 = (j - 0.5) * shell;
  f.radius = c0 + (density[j - 1] - half) / (density[j - 1] - density[j]) * shell;
  std::size_t i = peak;
  while (i > 0 && density[i - 1] >= half) --i;
  // Linear between the centres of shells i - 1 (below half) and i.
  f.inner_radius = i == 0 ? 0.0
                          : (i - 0.5) * shell +
                                (half - density[i - 1]) / (density[i] - density[i - 1]) * shell;
  return f;
}

ShellFront front_of(std::span<const Eigen::Vector3d> active, int dim, double ambient,
                    double shell) {
  if (active.empty()) return {};
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (const auto& x : active) centre += x;
  centre /= double(active.size());
  std::vector<double> d;
  d.reserve(active.size());
  for (const auto& x : active) d.push_back((x - centre).norm());
  return shell_front(d, dim, ambient, shell);
}

ShellFront measure_front(const Snapshot& s, double ambient, double shell) {
  std::vector<Eigen::Vector3d> active;
  for (std::size_t i = 0; i < s.size(); ++i)
    if (active_at(s, i)) active.push_back(s.position[i]);
  return front_of(active, s.info.dim, ambient, shell);
}

BandMeasures measure_band(const Snapshot& s, double ambient, const BandMeasureOptions& o) {
  const int d = s.info.dim;
  if (d != 2 && d != 3) throw UserError("band measures: dimension must be 2 or 3");
  if (!(s.info.cube_side() > 0)) throw UserError("band measures need a cubic periodic box");
  BandMeasures m;
  m.front = measure_front(s, ambient, o.shell);
  if (!(m.front.peak_density > 0)) return m;  // no band yet
  m.densest_cell = densest_shifted_cell(s, d, o);
  auto local = local_packing(s, d, o.local_radius);
  m.local_upper = quantile_of(local, o.local_quantile);
  m.local_median = quantile_of(local, 0.5);
  return m;
}

Histogram weighted_cell_histogram(std::span<const double> fraction,
                                  std::span<const std::uint32_t> active, const Binning& b) {
  GS_CHECK(fraction.size() == active.size());
  if (b.bins < 1 || !(b.hi > b.lo)) throw UserError("weighted histogram needs bins on lo < hi");
  Histogram h;
  const double w = (b.hi - b.lo) / b.bins;
  for (int k = 0; k <= b.bins; ++k) h.edges.push_back(b.lo + k * w);
  h.values.assign(std::size_t(b.bins), 0.0);
  double total = 0;
  for (std::size_t i = 0; i < fraction.size(); ++i) {
    total += active[i];
    ++h.samples;
    const double x = fraction[i];
    if (x < b.lo || x > b.hi) {
      ++h.outside;
      continue;
    }
    h.values[std::min(std::size_t(b.bins) - 1, std::size_t((x - b.lo) / w))] += active[i];
  }
  if (total > 0)
    for (auto& v : h.values) v /= total * w;
  return h;
}

}  // namespace gs
