#include "analysis/core_energy.h"

#include <cmath>

#include "analysis/band_measures.h"
#include "sim/error.h"
#include "sim/observables.h"

namespace gs {
namespace {

bool active_at(const Snapshot& s, std::size_t i) {
  return s.active.empty() || s.active[i] != 0;
}

// Positions and velocities of the active particles relative to their centre of mass and its
// velocity (Shape), in the snapshot's dimension.
struct Relative {
  int d = 0;
  std::vector<Eigen::Vector3d> x, v;
};
Relative relative_to_centre(const Snapshot& s) {
  if (!s.has_velocity()) throw UserError("the core's energy needs velocities");
  const Shape shape = measure_shape(s);
  Relative r;
  r.d = shape.dim;
  if (r.d != 2 && r.d != 3) throw UserError("the core's energy: dimension must be 2 or 3");
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (!active_at(s, i)) continue;
    Eigen::Vector3d x = s.position[i] - shape.centre, v = s.velocity[i] - shape.centre_velocity;
    for (int k = r.d; k < 3; ++k) x[k] = v[k] = 0;
    r.x.push_back(x);
    r.v.push_back(v);
  }
  return r;
}

}  // namespace

CoreEnergy core_energy(const Snapshot& s, double ambient, double shell) {
  const Relative r = relative_to_centre(s);
  std::vector<double> distance(r.x.size());
  for (std::size_t i = 0; i < r.x.size(); ++i) distance[i] = r.x[i].norm();
  const ShellFront f = shell_front(distance, r.d, ambient, shell);
  CoreEnergy c;
  c.front = f.radius;
  c.inner = f.inner_radius;
  for (std::size_t i = 0; i < r.x.size(); ++i) {
    const double e = 0.5 * r.v[i].squaredNorm();
    c.total_energy += e;
    if (distance[i] < c.inner) {
      c.core_energy += e;
      ++c.core_count;
    }
  }
  if (std::isfinite(c.inner) && c.total_energy > 0) c.share = c.core_energy / c.total_energy;
  return c;
}

PressureProfile kinetic_pressure(const Snapshot& s, double front, const Binning& binning) {
  if (!(binning.bins >= 1 && binning.hi > binning.lo && binning.lo >= 0))
    throw UserError("the pressure profile needs bins on 0 <= lo < hi");
  const Relative r = relative_to_centre(s);
  PressureProfile p;
  p.edges = histogram_edges({}, binning);
  const std::size_t n = p.edges.size() - 1;
  p.pressure.assign(n, 0.0);
  p.count.assign(n, 0);
  if (!(front > 0 && std::isfinite(front))) return p;
  std::vector<double> squares(n, 0.0), radial(n, 0.0);
  for (std::size_t i = 0; i < r.x.size(); ++i) {
    const double rho = r.x[i].norm(), x = rho / front;
    if (!(x >= p.edges.front() && x <= p.edges.back())) continue;
    const std::size_t b = bin_of(p.edges, x);
    ++p.count[b];
    squares[b] += r.v[i].squaredNorm();
    if (rho > 0) radial[b] += r.v[i].dot(r.x[i]) / rho;
  }
  for (std::size_t b = 0; b < n; ++b) {
    if (p.count[b] == 0) continue;
    const double volume =
        sphere_volume(r.d, p.edges[b + 1] * front) - sphere_volume(r.d, p.edges[b] * front);
    // sum |v - u|^2 with u the shell's mean radial velocity: sum |v|^2 - n u^2.
    const double fluctuation = squares[b] - radial[b] * radial[b] / double(p.count[b]);
    p.pressure[b] = fluctuation / (r.d * volume);
  }
  return p;
}

CoreShareTrend core_share_trend(std::span<const double> t, std::span<const double> mean,
                                std::span<const double> sem, double t_from, double t_to) {
  GS_CHECK(t.size() == mean.size() && t.size() == sem.size());
  CoreShareTrend c;
  std::size_t a = t.size(), b = t.size();
  for (std::size_t k = 0; k < t.size(); ++k) {
    if (t[k] > 0 && (a == t.size() || std::abs(std::log(t[k] / t_from)) <
                                          std::abs(std::log(t[a] / t_from))))
      a = k;
    if (t[k] <= t_to) b = k;
  }
  if (a >= t.size() || b >= t.size() || !(t[b] > t[a])) {
    c.reading = "no interval";
    return c;
  }
  c.t_from = t[a];
  c.t_to = t[b];
  c.from = mean[a];
  c.from_sem = sem[a];
  c.to = mean[b];
  c.to_sem = sem[b];
  if (!(std::isfinite(c.from) && std::isfinite(c.to))) {
    c.reading = "not measured";  // no band yet, or realisations from before the measure
    return c;
  }
  if (!(c.from > 0 && c.to > 0)) {
    c.reading = "no core";
    return c;
  }
  const double span = std::log(c.t_to / c.t_from);
  c.slope = std::log(c.to / c.from) / span;
  const double ra = std::isfinite(c.from_sem) ? c.from_sem / c.from : 0;
  const double rb = std::isfinite(c.to_sem) ? c.to_sem / c.to : 0;
  c.sigma = std::sqrt(ra * ra + rb * rb) / span;
  c.reading = c.slope < -2 * c.sigma ? "falls" : c.slope > 2 * c.sigma ? "rises" : "flat";
  return c;
}

}  // namespace gs
