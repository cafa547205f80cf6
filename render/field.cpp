#include "render/field.h"

#include <algorithm>
#include <cmath>

#include "sim/error.h"

namespace gs::render {

std::vector<double> field_values(const Snapshot& s, Field f, double* v_rms,
                                 const std::string& column) {
  std::vector<double> v;
  field_values(s, f, v_rms, column, v);
  return v;
}

void field_values(const Snapshot& s, Field f, double* v_rms, const std::string& column,
                  std::vector<double>& v) {
  const std::size_t n = s.size();
  v.resize(n);  // every value is written below
  if (v_rms) *v_rms = 0;
  if (f == Field::None) {
    v.assign(n, 0.5);
    return;
  }
  if (f == Field::Type) {
    if (n > 0 && s.type.size() != n)
      throw UserError("snapshot has no particle types; cannot colour by type");
    for (std::size_t i = 0; i < n; ++i) v[i] = s.type[i];
    return;
  }
  if (f == Field::Column) {
    const Column* c = s.column(column);
    if (!c) throw UserError("snapshot has no column '" + column + "'; cannot colour by it");
    GS_CHECK(c->values.size() == n);
    v = c->values;
    return;
  }
  if (f == Field::FirstCollision) {
    if (n > 0 && s.first_collision.size() != n)
      throw UserError("snapshot has no first_collision column; cannot colour by first collision");
    for (std::size_t i = 0; i < n; ++i)
      v[i] = s.first_collision[i] < 0 ? std::nan("") : s.first_collision[i];
    return;
  }
  if (n > 0 && !s.has_velocity())
    throw UserError(std::string("snapshot has no velocities (velo); cannot colour by ") +
                    field_name(f));
  if (f == Field::Speed || f == Field::ScaledSpeed) {
    for (std::size_t i = 0; i < n; ++i) v[i] = s.velocity[i].norm();
  } else {
    Eigen::Vector3d com = Eigen::Vector3d::Zero(), drift = Eigen::Vector3d::Zero();
    std::size_t m = 0;
    for (std::size_t i = 0; i < n; ++i)
      if (s.active[i]) com += s.position[i], drift += s.velocity[i], ++m;
    if (m) com /= static_cast<double>(m), drift /= static_cast<double>(m);
    // The scaled field is taken relative to the band's drift, as the radial profiles are
    // (sim/observables.h): the kick leaves a net momentum of the order of v_rms itself.
    if (f == Field::RadialVelocity) drift.setZero();
    for (std::size_t i = 0; i < n; ++i) {
      const Eigen::Vector3d r = s.position[i] - com;
      const double len = r.norm();
      v[i] = len > 0 ? (s.velocity[i] - drift).dot(r) / len : 0;
    }
  }
  if (!is_scaled(f)) return;
  double sum = 0;
  std::size_t m = 0;
  for (std::size_t i = 0; i < n; ++i)
    if (s.active[i]) sum += s.velocity[i].squaredNorm(), ++m;
  if (m == 0)  // before the first collision: the kicked particle alone moves
    for (std::size_t i = 0; i < n; ++i)
      if (s.velocity[i].squaredNorm() > 0) sum += s.velocity[i].squaredNorm(), ++m;
  const double rms = m ? std::sqrt(sum / static_cast<double>(m)) : 0;
  if (v_rms) *v_rms = rms;
  if (rms > 0)
    for (double& x : v) x /= rms;
}

Field default_field(const Snapshot& s) {
  if (!s.has_velocity()) return s.type.size() == s.size() && s.size() > 0 ? Field::Type : Field::None;
  if (s.info.kick) return Field::ScaledSpeed;  // ours, with or without its resting particles
  for (std::size_t i = 0; i < s.size(); ++i)
    if (!s.active[i] && s.velocity[i].squaredNorm() == 0) return Field::ScaledSpeed;
  return Field::Speed;
}

std::vector<Field> available_fields(const Snapshot& s) {
  std::vector<Field> out;
  for (Field f : all_fields())
    if (f == Field::None || s.size() == 0 ||
        (needs_velocity(f)      ? s.has_velocity()
         : f == Field::Type     ? s.type.size() == s.size()
                                : s.first_collision.size() == s.size()))
      out.push_back(f);
  return out;
}

Field choose_field(const std::string& name, const Snapshot& s, const std::string& file,
                   std::string* note) {
  std::string list;
  for (Field f : available_fields(s)) {
    if (name == field_name(f)) return f;
    list += (list.empty() ? "" : ", ") + std::string(field_name(f));
  }
  for (const Column& c : s.columns) list += ", " + c.name;
  if (name == "auto") {
    const Field f = default_field(s);
    if (note && s.size() > 0 && !s.has_velocity())
      *note = std::string("no velocities: coloured by ") +
              (f == Field::Type ? "particle type" : "nothing (one colour)") +
              "; --color-by chooses (it can be coloured by " + list + ")";
    return f;
  }
  if (s.column(name)) return Field::Column;
  for (Field f : all_fields())
    if (name == field_name(f))
      throw UserError(
          "snapshot '" + file + "' has no " +
          (needs_velocity(f)    ? "velocities (no velo property)"
           : f == Field::Type   ? "particle types (type, typeid or species)"
                                : "first_collision property") +
          "; cannot colour by " + name + " (it has: " + list + ")");
  throw UsageError("unknown --color-by '" + name + "'; snapshot '" + file + "' can be coloured by " +
                  list);
}

constexpr double kDegenerateSpread = 1e-3;

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
  const double lo = pick(std::clamp(plo, 0.0, 100.0)), hi = pick(std::clamp(phi, 0.0, 100.0));
  // A spread below 1e-3 of the values is below what the colour bar's three-digit labels can
  // show, and in a file written to six decimals (a ring of one speed) it is round-off: stretched
  // over the colour map it would paint noise. Such a range is one value, shown in one colour.
  if (scale == Scale::Log) {
    if (hi > lo * (1 + kDegenerateSpread)) return {lo, hi};
    const double c = std::sqrt(lo * hi);
    return {c / 2, c * 2};
  }
  if (hi - lo > kDegenerateSpread * std::max(std::abs(lo), std::abs(hi))) return {lo, hi};
  const double c = lo / 2 + hi / 2, w = std::max(std::abs(c) * 0.05, 1e-9);
  return {c - w, c + w};
}

double normalise(double v, std::pair<double, double> range, Scale scale) {
  double t = scale == Scale::Log
                 ? (v > 0 ? std::log(v / range.first) / std::log(range.second / range.first) : 0)
                 : (v - range.first) / (range.second - range.first);
  if (!(t > 0)) return 0;  // also NaN
  return std::min(t, 1.0);
}

}  // namespace gs::render
