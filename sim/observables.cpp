#include "sim/observables.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <unordered_map>

#include "sim/error.h"

namespace gs {
namespace {

int checked_dim(const Snapshot& s) {
  const int d = s.info.dim;
  if (d < 1 || d > 3)
    throw UserError("snapshot dimension must be 1, 2 or 3 (got " + std::to_string(d) + ")");
  GS_CHECK(s.active.empty() || s.active.size() == s.size());
  GS_CHECK(s.velocity.empty() || s.velocity.size() == s.size());
  GS_CHECK(s.radius.empty() || s.radius.size() == s.size());
  return d;
}

void require_velocities(const Snapshot& s) {
  if (!s.has_velocity()) throw UserError("snapshot has no velocities (speeds asked for)");
}

// Only the first d components carry physics; the rest are zero by the snapshot's convention but
// a hand-written file might not honour it.
Eigen::Vector3d project(const Eigen::Vector3d& x, int d) {
  return {x[0], d > 1 ? x[1] : 0.0, d > 2 ? x[2] : 0.0};  // not head(d): a loop per call
}

Eigen::Vector3d centre_of_active(const Snapshot& s, int d, std::size_t* n_out) {
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  std::size_t n = 0;
  for (std::size_t i = 0; i < s.size(); ++i)
    if (s.is_active(i)) {
      c += project(s.position[i], d);
      ++n;
    }
  if (n_out) *n_out = n;
  return n ? Eigen::Vector3d(c / double(n)) : c;
}

}  // namespace

double ball_volume(int d, double a) {
  switch (d) {
    case 1:
      return 2 * a;
    case 2:
      return std::numbers::pi * a * a;
    default:
      return 4.0 / 3.0 * std::numbers::pi * a * a * a;
  }
}

double anisotropy_index(int dim, const Eigen::Vector3d& l) {
  if (dim == 1) return 0;
  if (dim == 2) {
    const double sum = l[0] + l[1];
    if (!(sum > 0)) return 0;
    const double q = (l[0] - l[1]) / sum;
    return q * q;
  }
  const double sum = l[0] + l[1] + l[2];
  if (!(sum > 0)) return 0;
  // Written as a sum of squared differences so a sphere gives 0 without cancellation:
  // 1 - 3 I2 / I1^2 = ((l1-l2)^2 + (l2-l3)^2 + (l3-l1)^2) / (2 I1^2).
  const double a = l[0] - l[1], b = l[1] - l[2], c = l[2] - l[0];
  return (a * a + b * b + c * c) / (2 * sum * sum);
}

Shape measure_shape(const Snapshot& s) {
  Shape sh;
  const int d = checked_dim(s);
  sh.dim = d;
  sh.centre = centre_of_active(s, d, &sh.active);
  if (sh.active == 0) return sh;
  const double n = double(sh.active);
  Eigen::Matrix3d g = Eigen::Matrix3d::Zero();
  Eigen::Vector3d vc = Eigen::Vector3d::Zero();
  double v2 = 0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (!s.is_active(i)) continue;
    const Eigen::Vector3d x = project(s.position[i], d) - sh.centre;
    g += x * x.transpose();
    if (s.has_velocity()) {
      const Eigen::Vector3d v = project(s.velocity[i], d);
      vc += v;
      v2 += v.squaredNorm();
    }
  }
  sh.gyration = g / n;
  sh.radius_rms = std::sqrt(sh.gyration.trace());
  sh.centre_velocity = vc / n;
  sh.speed_rms = std::sqrt(v2 / n);
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver(sh.gyration.topLeftCorner(d, d),
                                                        Eigen::EigenvaluesOnly);
  GS_CHECK(solver.info() == Eigen::Success);
  // Eigen returns them ascending; round-off can leave a tiny negative one for a flat set.
  for (int k = 0; k < d; ++k) sh.eigenvalues[k] = std::max(0.0, solver.eigenvalues()[d - 1 - k]);
  sh.anisotropy = anisotropy_index(d, sh.eigenvalues);
  return sh;
}

double radial_momentum(const Snapshot& s) {
  const int d = checked_dim(s);
  if (!s.has_velocity()) return 0;
  std::size_t n = 0;
  const Eigen::Vector3d c = centre_of_active(s, d, &n);
  if (n == 0) return 0;
  Eigen::Vector3d vc = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < s.size(); ++i)
    if (s.is_active(i)) vc += project(s.velocity[i], d);
  vc /= double(n);
  double p = 0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (!s.is_active(i)) continue;
    const Eigen::Vector3d x = project(s.position[i], d) - c;
    const double r = x.norm();
    if (r > 0) p += (project(s.velocity[i], d) - vc).dot(x) / r;
  }
  return p;
}

double isotropic_anisotropy(const Snapshot& s, Rng& rng, int shuffles) {
  const int d = checked_dim(s);
  std::size_t n = 0;
  const Eigen::Vector3d c = centre_of_active(s, d, &n);
  if (n < 2 || d == 1 || shuffles < 1) return 0;
  std::vector<double> r;
  r.reserve(n);
  for (std::size_t i = 0; i < s.size(); ++i)
    if (s.is_active(i)) r.push_back((project(s.position[i], d) - c).norm());
  double sum = 0;
  std::vector<Eigen::Vector3d> x(n);
  for (int k = 0; k < shuffles; ++k) {
    Eigen::Vector3d m = Eigen::Vector3d::Zero();
    for (std::size_t i = 0; i < n; ++i) {
      Eigen::Vector3d u = Eigen::Vector3d::Zero();
      if (d == 2) {
        const double phi = 2 * std::numbers::pi * rng.uniform();
        u = {std::cos(phi), std::sin(phi), 0};
      } else {
        const double z = 2 * rng.uniform() - 1, phi = 2 * std::numbers::pi * rng.uniform();
        const double rho = std::sqrt(std::max(0.0, 1 - z * z));
        u = {rho * std::cos(phi), rho * std::sin(phi), z};
      }
      x[i] = r[i] * u;
      m += x[i];
    }
    m /= double(n);
    Eigen::Matrix3d g = Eigen::Matrix3d::Zero();
    for (const auto& xi : x) g += (xi - m) * (xi - m).transpose();
    g /= double(n);
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver(g.topLeftCorner(d, d),
                                                          Eigen::EigenvaluesOnly);
    GS_CHECK(solver.info() == Eigen::Success);
    Eigen::Vector3d l = Eigen::Vector3d::Zero();
    for (int j = 0; j < d; ++j) l[j] = std::max(0.0, solver.eigenvalues()[d - 1 - j]);
    sum += anisotropy_index(d, l);
  }
  return sum / shuffles;
}

double kinetic_energy(const Snapshot& s) {
  double e = 0;
  for (const auto& v : s.velocity) e += 0.5 * v.squaredNorm();
  return e;
}

Snapshot active_subset(const Snapshot& s) {
  checked_dim(s);
  Snapshot a;
  a.info = s.info;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (!s.is_active(i)) continue;
    a.position.push_back(s.position[i]);
    if (s.has_velocity()) a.velocity.push_back(s.velocity[i]);
    if (!s.radius.empty()) a.radius.push_back(s.radius[i]);
    if (!s.active.empty()) a.active.push_back(1);
    if (!s.first_collision.empty()) a.first_collision.push_back(s.first_collision[i]);
  }
  return a;
}

std::vector<double> active_distances(const Snapshot& s, const Eigen::Vector3d& centre) {
  const int d = checked_dim(s);
  const Eigen::Vector3d c = project(centre, d);
  std::vector<double> r;
  // Sized first: growing it copied the distances over and over (a movie's inset, every frame).
  r.reserve(s.active.empty() ? s.size()
                             : s.size() - std::count(s.active.begin(), s.active.end(), 0));
  for (std::size_t i = 0; i < s.size(); ++i)
    if (s.is_active(i)) r.push_back((project(s.position[i], d) - c).norm());
  return r;
}

std::vector<double> active_speeds(const Snapshot& s) {
  const int d = checked_dim(s);
  require_velocities(s);
  std::vector<double> v;
  for (std::size_t i = 0; i < s.size(); ++i)
    if (s.is_active(i)) v.push_back(project(s.velocity[i], d).norm());
  return v;
}

Histogram radial_distribution(const Snapshot& s, const Binning& binning) {
  const int d = checked_dim(s);
  const auto r = active_distances(s, centre_of_active(s, d, nullptr));
  return make_histogram(r, binning);
}

Histogram speed_distribution(const Snapshot& s, const Binning& binning) {
  return make_histogram(active_speeds(s), binning);
}

namespace {
Histogram scaled_by(const Histogram& h, double time, double exponent) {
  if (!(time > 0) || !std::isfinite(time))
    throw UserError("scaled distribution needs a time > 0 (got " + std::to_string(time) + ")");
  return rescaled(h, std::pow(time, exponent));
}
}  // namespace

Histogram scaled_radial_distribution(const Histogram& p_r, double time, double alpha) {
  return scaled_by(p_r, time, -alpha);
}

Histogram scaled_speed_distribution(const Histogram& p_v, double time, double alpha) {
  return scaled_by(p_v, time, 1 - alpha);
}

BandPacking band_packing(const Snapshot& s, const PackingOptions& options) {
  const int d = checked_dim(s);
  if (!(options.cell > 0)) throw UserError("packing cell side must be positive");
  BandPacking out;
  // A rectangular box (not ours) is not wrapped: cells of side `cell` tile unbounded space.
  const double box = s.info.cube_side();
  std::int64_t per_side = 0;  // 0: unbounded cells
  double side = options.cell;
  if (box > 0) {
    per_side = std::max<std::int64_t>(1, static_cast<std::int64_t>(std::floor(box / options.cell)));
    side = box / double(per_side);
  }
  out.cell_side = side;

  // 21 bits per axis: 2^20 cells of side 10 on each side of the origin, far beyond any box.
  constexpr std::int64_t half = std::int64_t{1} << 20;
  auto key_of = [&](const Eigen::Vector3d& x) {
    std::uint64_t key = 0;
    for (int k = 0; k < d; ++k) {
      auto c = static_cast<std::int64_t>(std::floor(x[k] / side));
      if (per_side > 0) c = ((c % per_side) + per_side) % per_side;
      GS_CHECK_MSG(c > -half && c < half, "packing cell index out of range");
      key |= static_cast<std::uint64_t>(c + half) << (21 * k);
    }
    return key;
  };

  struct Cell {
    double volume = 0;  // sum of particle volumes
    std::uint32_t active = 0;
  };
  std::unordered_map<std::uint64_t, Cell> cells;
  for (std::size_t i = 0; i < s.size(); ++i)
    if (s.is_active(i)) ++cells[key_of(s.position[i])].active;
  for (std::size_t i = 0; i < s.size(); ++i) {
    auto it = cells.find(key_of(s.position[i]));
    if (it == cells.end()) continue;
    it->second.volume += ball_volume(d, s.radius.empty() ? 0.5 : s.radius[i]);
  }

  std::vector<std::pair<std::uint64_t, Cell>> sorted(cells.begin(), cells.end());
  std::sort(sorted.begin(), sorted.end(),
            [](const auto& a, const auto& b) { return a.first < b.first; });
  const double cell_volume = std::pow(side, d);
  double weighted = 0, sum = 0;
  std::uint64_t weights = 0;
  for (const auto& [key, c] : sorted) {
    const double f = c.volume / cell_volume;
    out.fraction.push_back(f);
    out.active.push_back(c.active);
    weighted += f * c.active;
    weights += c.active;
    sum += f;
  }
  out.distribution = make_histogram(out.fraction, options.binning);
  if (sorted.empty()) return out;
  out.typical = weighted / double(weights);
  out.mean = sum / double(sorted.size());
  if (!(options.upper_quantile > 0 && options.upper_quantile <= 1))
    throw UserError("packing quantile must be in (0, 1]");
  std::vector<std::size_t> order(out.fraction.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return out.fraction[a] < out.fraction[b] || (out.fraction[a] == out.fraction[b] && a < b);
  });
  std::uint64_t cumulative = 0;
  for (std::size_t i : order) {
    cumulative += out.active[i];
    if (double(cumulative) >= options.upper_quantile * double(weights)) {
      out.upper = out.fraction[i];
      break;
    }
  }
  const auto& v = out.distribution.values;
  out.mode = out.distribution.centre(std::size_t(std::max_element(v.begin(), v.end()) - v.begin()));
  return out;
}

namespace {

// Density and mean speed per shell from the shells, counts and speed sums of `p`.
void shell_means(RadialProfile& p, int d) {
  const std::size_t n = p.count.size();
  p.density.resize(n);
  p.mean_speed.resize(n);
  for (std::size_t b = 0; b < n; ++b) {
    const double shell = ball_volume(d, p.edges[b + 1]) - ball_volume(d, p.edges[b]);
    p.density[b] = double(p.count[b]) / shell;
    p.mean_speed[b] =
        p.count[b] ? p.speed_sum[b] / double(p.count[b]) : std::numeric_limits<double>::quiet_NaN();
  }
}

}  // namespace

RadialProfile radial_profile(const Snapshot& s, const Binning& binning) {
  const int d = checked_dim(s);
  require_velocities(s);
  // The centre and its velocity alone (measure_shape adds the gyration tensor and its
  // eigenvalues): a movie's inset takes this profile in every frame.
  std::size_t active = 0;
  const Eigen::Vector3d centre = centre_of_active(s, d, &active);
  Eigen::Vector3d centre_velocity = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < s.size(); ++i)
    if (s.is_active(i)) centre_velocity += project(s.velocity[i], d);
  if (active > 0) centre_velocity /= double(active);
  const auto r = active_distances(s, centre);
  // The shells are P(R,t)'s histogram bins exactly.
  RadialProfile p;
  p.edges = histogram_edges(r, binning);
  const std::size_t n = p.edges.size() - 1;
  std::vector<std::uint64_t> count(n, 0);
  std::vector<double> speed(n, 0.0), radial(n, 0.0);
  const double lo = p.edges.front(), hi = p.edges.back();
  // Locals, not the snapshot's members, in the loop: the sums' stores would otherwise make the
  // compiler load them again for every particle.
  const Eigen::Vector3d* x_of = s.position.data();
  const Eigen::Vector3d* v_of = s.velocity.data();
  const std::uint8_t* active_of = s.active.empty() ? nullptr : s.active.data();
  const std::size_t size = s.size();
  std::size_t j = 0;
  for (std::size_t i = 0; i < size; ++i) {
    if (active_of && !active_of[i]) continue;
    const double ri = r[j++];
    if (!(ri >= lo && ri <= hi)) continue;
    const std::size_t b = bin_of(p.edges, ri);
    const Eigen::Vector3d v = project(v_of[i], d);
    const Eigen::Vector3d x = project(x_of[i], d) - centre;
    ++count[b];
    speed[b] += v.norm();
    if (ri > 0) radial[b] += (v - centre_velocity).dot(x) / ri;
  }
  p.count = std::move(count);
  p.speed_sum = std::move(speed);
  shell_means(p, d);
  p.mean_radial_velocity.resize(n);
  for (std::size_t b = 0; b < n; ++b)
    p.mean_radial_velocity[b] =
        p.count[b] ? radial[b] / double(p.count[b]) : std::numeric_limits<double>::quiet_NaN();
  p.radial_velocity_sum = std::move(radial);
  return p;
}

RadialProfile speed_profile(int d, std::span<const Eigen::Vector3d> positions,
                            std::span<const double> speeds, const Binning& binning) {
  GS_CHECK(positions.size() == speeds.size() && d >= 1 && d <= 3);
  // In the order radial_profile takes them, so that the sums are the same bits.
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (const auto& x : positions) centre += project(x, d);
  if (!positions.empty()) centre /= double(positions.size());
  std::vector<double> r(positions.size());
  for (std::size_t i = 0; i < r.size(); ++i) r[i] = (project(positions[i], d) - centre).norm();
  RadialProfile p;
  p.edges = histogram_edges(r, binning);
  const std::size_t n = p.edges.size() - 1;
  p.count.assign(n, 0);
  p.speed_sum.assign(n, 0.0);
  const double lo = p.edges.front(), hi = p.edges.back();
  for (std::size_t i = 0; i < r.size(); ++i) {
    if (!(r[i] >= lo && r[i] <= hi)) continue;
    const std::size_t b = bin_of(p.edges, r[i]);
    ++p.count[b];
    p.speed_sum[b] += speeds[i];
  }
  shell_means(p, d);
  return p;
}

InnerEdge inner_edge_speed(const Snapshot& s) {
  const int d = checked_dim(s);
  const auto v = active_speeds(s);
  const auto r = active_distances(s, centre_of_active(s, d, nullptr));
  InnerEdge e;
  const std::size_t n = r.size();
  if (n < 2) return e;
  double mr = 0, mv = 0;
  for (std::size_t i = 0; i < n; ++i) {
    mr += r[i];
    mv += v[i];
  }
  mr /= double(n);
  mv /= double(n);
  double srr = 0, svv = 0, srv = 0;
  for (std::size_t i = 0; i < n; ++i) {
    srr += (r[i] - mr) * (r[i] - mr);
    svv += (v[i] - mv) * (v[i] - mv);
    srv += (r[i] - mr) * (v[i] - mv);
  }
  if (srr > 0 && svv > 0) e.correlation = srv / std::sqrt(srr * svv);
  std::vector<double> sorted = r;
  std::nth_element(sorted.begin(), sorted.begin() + std::ptrdiff_t(n / 2), sorted.end());
  e.median_radius = sorted[n / 2];
  double si = 0, so = 0;
  std::size_t ni = 0, no = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (r[i] < e.median_radius) {
      si += v[i];
      ++ni;
    } else {
      so += v[i];
      ++no;
    }
  }
  if (ni) e.inner_speed = si / double(ni);
  if (no) e.outer_speed = so / double(no);
  if (ni && no && e.outer_speed > 0) e.ratio = e.inner_speed / e.outer_speed;
  return e;
}

}  // namespace gs
