#include "analysis/core_energy.h"

#include <cmath>

#include "analysis/band_measures.h"
#include "sim/error.h"
#include "sim/observables.h"

namespace gs {
namespace {

// The centre of mass of the active particles and its velocity (Shape), and a visit of each
// active particle's position and velocity relative to them in the first d axes, without a copy
// of the arrays (millions of spheres in 3D).
struct Frame {
  int d = 0;
  Eigen::Vector3d centre, velocity;
};
Frame frame_of(const Snapshot& s) {
  if (!s.has_velocity()) throw UserError("the core's energy needs velocities");
  const Shape shape = measure_shape(s);
  if (shape.dim != 2 && shape.dim != 3)
    throw UserError("the core's energy: dimension must be 2 or 3");
  return {shape.dim, shape.centre, shape.centre_velocity};
}
template <class F>
void for_each_active(const Snapshot& s, const Frame& f, F&& visit) {
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (!s.is_active(i)) continue;
    Eigen::Vector3d x = s.position[i] - f.centre, v = s.velocity[i] - f.velocity;
    for (int k = f.d; k < 3; ++k) x[k] = v[k] = 0;
    visit(x, v);
  }
}

}  // namespace

CoreEnergy core_energy(const Snapshot& s, double ambient, double shell) {
  const Frame f = frame_of(s);
  std::vector<double> distance;
  for_each_active(s, f, [&](const Eigen::Vector3d& x, const Eigen::Vector3d&) {
    distance.push_back(x.norm());
  });
  const ShellFront front = shell_front(distance, f.d, ambient, shell);
  CoreEnergy c;
  c.front = front.radius;
  c.inner = front.inner_radius;
  std::size_t i = 0;
  for_each_active(s, f, [&](const Eigen::Vector3d&, const Eigen::Vector3d& v) {
    const double e = 0.5 * v.squaredNorm();
    c.total_energy += e;
    if (distance[i++] < c.inner) {
      c.core_energy += e;
      ++c.core_count;
    }
  });
  if (std::isfinite(c.inner) && c.total_energy > 0) c.share = c.core_energy / c.total_energy;
  return c;
}

PressureProfile kinetic_pressure(const Snapshot& s, double front, const Binning& binning) {
  if (!(binning.bins >= 1 && binning.hi > binning.lo && binning.lo >= 0))
    throw UserError("the pressure profile needs bins on 0 <= lo < hi");
  const Frame f = frame_of(s);
  PressureProfile p;
  p.edges = histogram_edges({}, binning);
  const std::size_t n = p.edges.size() - 1;
  p.pressure.assign(n, 0.0);
  p.count.assign(n, 0);
  if (!(front > 0 && std::isfinite(front))) return p;
  std::vector<double> squares(n, 0.0), radial(n, 0.0);
  for_each_active(s, f, [&](const Eigen::Vector3d& x, const Eigen::Vector3d& v) {
    const double rho = x.norm(), u = rho / front;
    if (!(u >= p.edges.front() && u <= p.edges.back())) return;
    const std::size_t b = bin_of(p.edges, u);
    ++p.count[b];
    squares[b] += v.squaredNorm();
    if (rho > 0) radial[b] += v.dot(x) / rho;
  });
  for (std::size_t b = 0; b < n; ++b) {
    if (p.count[b] == 0) continue;
    const double volume =
        ball_volume(f.d, p.edges[b + 1] * front) - ball_volume(f.d, p.edges[b] * front);
    // sum |v - u|^2 with u the shell's mean radial velocity: sum |v|^2 - n u^2.
    const double fluctuation = squares[b] - radial[b] * radial[b] / double(p.count[b]);
    p.pressure[b] = fluctuation / (f.d * volume);
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
    c.reading = "not measured";  // no band yet at either time
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
