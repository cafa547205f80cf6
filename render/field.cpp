#include "render/field.h"

#include <algorithm>
#include <cmath>

#include "sim/error.h"

namespace gs::render {

std::vector<double> field_values(const Snapshot& s, Field f) {
  const std::size_t n = s.size();
  std::vector<double> v(n);
  if (f == Field::FirstCollision) {
    if (n > 0 && s.first_collision.size() != n)
      throw UserError("snapshot has no first_collision column; cannot colour by first collision");
    for (std::size_t i = 0; i < n; ++i)
      v[i] = s.first_collision[i] < 0 ? std::nan("") : s.first_collision[i];
    return v;
  }
  if (n > 0 && !s.has_velocity())
    throw UserError(std::string("snapshot has no velocities (velo); cannot colour by ") +
                    (f == Field::Speed ? "speed" : "radial velocity"));
  if (f == Field::Speed) {
    for (std::size_t i = 0; i < n; ++i) v[i] = s.velocity[i].norm();
    return v;
  }
  Eigen::Vector3d com = Eigen::Vector3d::Zero();
  std::size_t m = 0;
  for (std::size_t i = 0; i < n; ++i)
    if (s.active[i]) com += s.position[i], ++m;
  if (m) com /= static_cast<double>(m);
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector3d r = s.position[i] - com;
    const double len = r.norm();
    v[i] = len > 0 ? s.velocity[i].dot(r) / len : 0;
  }
  return v;
}

std::pair<double, double> auto_range(const std::vector<double>& values,
                                     const std::vector<std::uint8_t>& mask, Scale scale, double plo,
                                     double phi) {
  std::vector<double> x;
  x.reserve(values.size());
  for (std::size_t i = 0; i < values.size(); ++i)
    if (mask[i] && std::isfinite(values[i]) && (scale == Scale::Linear || values[i] > 0))
      x.push_back(values[i]);
  if (x.empty()) return scale == Scale::Log ? std::pair{0.1, 1.0} : std::pair{0.0, 1.0};
  auto pick = [&](double p) {
    const auto k = static_cast<std::size_t>(std::llround(p / 100 * (x.size() - 1)));
    std::nth_element(x.begin(), x.begin() + k, x.end());
    return x[k];
  };
  double lo = pick(std::clamp(plo, 0.0, 100.0)), hi = pick(std::clamp(phi, 0.0, 100.0));
  if (!(hi > lo)) {
    if (scale == Scale::Log) {
      lo /= 2, hi *= 2;
    } else {
      const double w = std::max(std::abs(lo) * 0.05, 1e-9);
      lo -= w, hi += w;
    }
  }
  return {lo, hi};
}

double normalise(double v, std::pair<double, double> range, Scale scale) {
  double t = scale == Scale::Log
                 ? (v > 0 ? std::log(v / range.first) / std::log(range.second / range.first) : 0)
                 : (v - range.first) / (range.second - range.first);
  if (!(t > 0)) return 0;  // also NaN
  return std::min(t, 1.0);
}

}  // namespace gs::render
