#include "analysis/band_measures.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "analysis/quantile.h"
#include "sim/error.h"
#include "sim/observables.h"

namespace gs {
namespace {

double particle_volume(const Snapshot& s, std::size_t i, int d) {
  return ball_volume(d, s.radius.empty() ? 0.5 : s.radius[i]);
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
      if (s.is_active(i)) holds[key] = 1;
    }
    const double cell_volume = std::pow(side, d);
    for (std::size_t k = 0; k < cells; ++k)
      if (holds[k] && !(volume[k] / cell_volume <= best)) best = volume[k] / cell_volume;
  }
  return best;
}

// Particles sorted into a periodic grid of cells of side >= reach, to find every particle within
// `reach` of one (minimum image) from its cell's 3^d stencil.
class PeriodicCells {
 public:
  PeriodicCells(const Snapshot& s, int d, double reach) : s_(s), d_(d), box_(s.info.cube_side()) {
    n_ = std::max<std::int64_t>(1, std::int64_t(std::floor(box_ / reach)));
    const double side = box_ / double(n_);
    const std::size_t cells = std::size_t(std::pow(double(n_), d));
    cell_of_.resize(s.size());
    start_.assign(cells + 1, 0);
    order_.resize(s.size());
    for (std::size_t i = 0; i < s.size(); ++i) {
      std::array<std::int64_t, 3> c{0, 0, 0};
      for (int k = 0; k < d; ++k)
        c[k] = std::min(n_ - 1, std::int64_t(std::floor(wrap(s.position[i][k], box_) / side)));
      cell_of_[i] = c;
      ++start_[key_of(c) + 1];
    }
    for (std::size_t k = 0; k < cells; ++k) start_[k + 1] += start_[k];
    std::vector<std::uint32_t> fill(start_.begin(), start_.end() - 1);
    for (std::size_t i = 0; i < s.size(); ++i)
      order_[fill[key_of(cell_of_[i])]++] = std::uint32_t(i);
  }

  // f(j, dx): every particle j of the stencil of i's cell (i itself included), dx = x_j - x_i
  // by the minimum image.
  template <class F>
  void near(std::size_t i, F&& f) const {
    const int reach = n_ >= 3 ? 1 : 0;  // a box of fewer than 3 cells: every cell is a neighbour
    const int span = n_ >= 3 ? 3 : int(n_);
    const int combos = int(std::pow(span, d_));
    for (int c = 0; c < combos; ++c) {
      std::array<std::int64_t, 3> nb{0, 0, 0};
      for (int k = 0, m = c; k < d_; ++k, m /= span) {
        const std::int64_t j = n_ >= 3 ? cell_of_[i][k] + (m % span) - reach : (m % span);
        nb[k] = ((j % n_) + n_) % n_;
      }
      const std::size_t key = key_of(nb);
      for (std::uint32_t q = start_[key]; q < start_[key + 1]; ++q) {
        const std::size_t j = order_[q];
        Eigen::Vector3d dx = Eigen::Vector3d::Zero();
        for (int k = 0; k < d_; ++k) {
          double x = wrap(s_.position[j][k], box_) - wrap(s_.position[i][k], box_);
          dx[k] = x - box_ * std::round(x / box_);
        }
        f(j, dx);
      }
    }
  }

 private:
  std::size_t key_of(const std::array<std::int64_t, 3>& c) const {
    std::size_t key = 0;
    for (int k = d_ - 1; k >= 0; --k) key = key * std::size_t(n_) + std::size_t(c[k]);
    return key;
  }
  const Snapshot& s_;
  int d_;
  double box_;
  std::int64_t n_ = 1;
  std::vector<std::array<std::int64_t, 3>> cell_of_;
  std::vector<std::uint32_t> start_, order_;
};

// Local packing within radius a of each active particle.
std::vector<double> local_packing(const Snapshot& s, int d, double a) {
  const PeriodicCells cells(s, d, a);
  std::vector<double> out;
  const double around = ball_volume(d, a);
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (!s.is_active(i)) continue;
    double filled = 0;
    cells.near(i, [&](std::size_t j, const Eigen::Vector3d& dx) {
      if (dx.squaredNorm() <= a * a) filled += particle_volume(s, j, d);
    });
    out.push_back(filled / around);
  }
  return out;
}

using Polygon = std::vector<Eigen::Vector2d>;

// Keeps the part of `poly` (convex, counter-clockwise) on the side of the bisector of 0 and q
// that holds 0: x . q <= |q|^2 / 2 (Sutherland-Hodgman against one line).
void clip_by_bisector(const Polygon& poly, const Eigen::Vector2d& q, Polygon& out) {
  out.clear();
  const double h = 0.5 * q.squaredNorm();
  for (std::size_t k = 0; k < poly.size(); ++k) {
    const Eigen::Vector2d& a = poly[k];
    const Eigen::Vector2d& b = poly[(k + 1) % poly.size()];
    const double fa = a.dot(q) - h, fb = b.dot(q) - h;
    if (fa <= 0) out.push_back(a);
    if ((fa < 0 && fb > 0) || (fa > 0 && fb < 0)) out.push_back(a + (b - a) * (fa / (fa - fb)));
  }
}

double polygon_area(const Polygon& p) {
  double twice = 0;
  for (std::size_t k = 0; k < p.size(); ++k) {
    const auto& a = p[k];
    const auto& b = p[(k + 1) % p.size()];
    twice += a.x() * b.y() - b.x() * a.y();
  }
  return 0.5 * twice;
}

double farthest_vertex(const Polygon& p) {
  double r2 = 0;
  for (const auto& v : p) r2 = std::max(r2, v.squaredNorm());
  return std::sqrt(r2);
}

}  // namespace

std::vector<double> voronoi_packing(const Snapshot& s, double cap) {
  if (s.info.dim != 2) throw UserError("Voronoi packing: dimension must be 2");
  if (!(s.info.cube_side() > 0)) throw UserError("Voronoi packing needs a cubic periodic box");
  GS_CHECK(cap > 0);
  // A neighbour farther than twice the cap square's corner cannot cut it.
  const double reach = 2 * std::sqrt(2.0) * cap;
  const PeriodicCells cells(s, 2, reach);
  std::vector<std::pair<double, Eigen::Vector2d>> nb;
  Polygon cell, next;
  std::vector<double> out;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (!s.is_active(i)) continue;
    nb.clear();
    cells.near(i, [&](std::size_t j, const Eigen::Vector3d& dx) {
      const double r2 = dx.head<2>().squaredNorm();
      if (j != i && r2 > 0 && r2 <= reach * reach) nb.emplace_back(r2, dx.head<2>());
    });
    std::sort(nb.begin(), nb.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    cell = {{-cap, -cap}, {cap, -cap}, {cap, cap}, {-cap, cap}};
    double bound = 2 * farthest_vertex(cell);
    for (const auto& [r2, q] : nb) {
      if (r2 > bound * bound) break;  // sorted: no farther one cuts the cell either
      clip_by_bisector(cell, q, next);
      cell.swap(next);
      bound = 2 * farthest_vertex(cell);
    }
    out.push_back(particle_volume(s, i, 2) / polygon_area(cell));
  }
  return out;
}

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
    density[b] /= ball_volume(dim, (b + 1) * shell) - ball_volume(dim, b * shell);
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
    if (s.is_active(i)) active.push_back(s.position[i]);
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
  if (d == 2) {
    auto vor = voronoi_packing(s, o.voronoi_cap);
    m.voronoi_median = quantile_of(vor, 0.5);
  }
  m.cell_small = band_packing(s, {.cell = o.small_cell}).typical;
  m.cell_large = band_packing(s, {.cell = o.large_cell}).typical;
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
