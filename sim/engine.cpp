#include "sim/engine.h"

#include <algorithm>
#include <cmath>

#include "sim/collision.h"
#include "sim/error.h"

namespace gs {

template <int D>
Engine<D>::Engine(const PhysicsConfig& c, InitialState<D> init)
    : config_(c), grid_(c.box()), queue_(init.position.size()) {
  const std::size_t n = init.position.size();
  GS_CHECK(n >= 2 && init.velocity.size() == n);
  GS_CHECK(n < static_cast<std::size_t>(INT32_MAX));
  pos_ = std::move(init.position);
  vel_ = std::move(init.velocity);
  tloc_.assign(n, 0.0);
  cell_.resize(n);
  image_.assign(n, IVec<D>::Zero());
  counter_.assign(n, 0);
  head_.assign(grid_.cell_count(), -1);
  next_.assign(n, -1);
  prev_.assign(n, -1);
  coll_time_.assign(n, kNever);
  coll_partner_.assign(n, -1);
  coll_counter_.assign(n, 0);
  cross_time_.assign(n, kNever);
  cross_dir_.assign(n, 0);
  active_.assign(n, 0);
  moving_.assign(n, 0);
  first_collision_.assign(n, -1.0);
  moved_.reserve(n);

  for (std::size_t i = 0; i < n; ++i) {
    const auto id = static_cast<std::int32_t>(i);
    cell_[i] = grid_.coords_of(pos_[i]);
    cell_insert(id, grid_.index(cell_[i]));
  }
  if (config_.sticky()) {
    for (std::size_t i = 1; i < n; ++i) GS_CHECK(pos_[i][0] >= pos_[i - 1][0]);
    cluster_lo_.resize(n);
    cluster_hi_.resize(n);
    for (std::size_t i = 0; i < n; ++i)
      cluster_lo_[i] = cluster_hi_[i] = static_cast<std::int32_t>(i);
  }
  for (std::size_t i = 0; i < n; ++i)
    if (vel_[i].squaredNorm() > 0) mark_moving(static_cast<std::int32_t>(i));
  for (std::int32_t i : moved_) predict(i);
}

template <int D>
void Engine<D>::cell_insert(std::int32_t i, std::int32_t cell) {
  next_[i] = head_[cell];
  prev_[i] = -1;
  if (head_[cell] >= 0) prev_[head_[cell]] = i;
  head_[cell] = i;
}

template <int D>
void Engine<D>::cell_remove(std::int32_t i, std::int32_t cell) {
  if (prev_[i] >= 0)
    next_[prev_[i]] = next_[i];
  else
    head_[cell] = next_[i];
  if (next_[i] >= 0) prev_[next_[i]] = prev_[i];
}

template <int D>
void Engine<D>::mark_moving(std::int32_t i) {
  if (moving_[i]) return;
  moving_[i] = 1;
  moved_.push_back(i);  // capacity reserved for all particles: never reallocates
}

template <int D>
void Engine<D>::mark_active(std::int32_t i) {
  mark_moving(i);
  if (active_[i]) return;
  active_[i] = 1;
  first_collision_[i] = now_;
}

template <int D>
void Engine<D>::advance(std::int32_t i) {
  pos_[i] += vel_[i] * (now_ - tloc_[i]);
  tloc_[i] = now_;
}

template <int D>
Vec<D> Engine<D>::position(std::int32_t i) const {
  Vec<D> x = pos_[i] + vel_[i] * (now_ - tloc_[i]);
  for (int k = 0; k < D; ++k) x[k] += image_[i][k] * grid_.box();
  return x;
}

// Separation from i (at xi, current time) to j, nearest periodic image.
template <int D>
Vec<D> Engine<D>::separation(std::int32_t, const Vec<D>& xi, std::int32_t j) const {
  return grid_.minimum_image(pos_[j] + vel_[j] * (now_ - tloc_[j]) - xi);
}

template <int D>
void Engine<D>::scan_cell(std::int32_t i, const Vec<D>& xi, std::int32_t cell) {
  const Vec<D>& vi = vel_[i];
  for (std::int32_t j = head_[cell]; j >= 0; j = next_[j]) {
    if (j == i) continue;
    const double dt = contact_time<D>(separation(i, xi, j), vel_[j] - vi);
    if (now_ + dt < coll_time_[i]) {
      coll_time_[i] = now_ + dt;
      coll_partner_[i] = j;
      coll_counter_[i] = counter_[j];
    }
  }
}

template <int D>
void Engine<D>::predict_crossing(std::int32_t i, const Vec<D>& xi) {
  double best = kNever;
  std::int8_t dir = 0;
  const double h = grid_.side();
  for (int k = 0; k < D; ++k) {
    const double v = vel_[i][k];
    if (v == 0) continue;
    const double wall = (cell_[i][k] + (v > 0 ? 1 : 0)) * h;
    const double dt = std::max(0.0, (wall - xi[k]) / v);  // round-off can put xi a hair past it
    if (dt < best) {
      best = dt;
      dir = static_cast<std::int8_t>(2 * k + (v > 0 ? 1 : 0));
    }
  }
  cross_time_[i] = now_ + best;
  cross_dir_[i] = dir;
}

template <int D>
void Engine<D>::schedule(std::int32_t i) {
  const double t = std::min(coll_time_[i], cross_time_[i]);
  if (t == kNever)
    queue_.remove(i);
  else
    queue_.set(i, t);
}

// Full prediction: every neighbour cell and the next crossing. Particles at rest do this too
// when they have just stopped, because a moving neighbour may be heading for them.
template <int D>
void Engine<D>::predict(std::int32_t i) {
  const Vec<D> xi = pos_[i] + vel_[i] * (now_ - tloc_[i]);
  coll_time_[i] = kNever;
  coll_partner_[i] = -1;
  grid_.for_each_neighbour(cell_[i], [&](std::int32_t cell) { scan_cell(i, xi, cell); });
  predict_crossing(i, xi);
  schedule(i);
}

template <int D>
EventKind Engine<D>::step() {
  if (queue_.empty()) return EventKind::None;
  now_ = std::max(now_, queue_.top_time());
  return process_next();
}

template <int D>
void Engine<D>::run_until(double t) {
  while (!queue_.empty() && queue_.top_time() <= t) {
    now_ = std::max(now_, queue_.top_time());
    process_next();
  }
  now_ = std::max(now_, t);
}

template <int D>
EventKind Engine<D>::process_next() {
  const std::int32_t i = queue_.top();
  ++stats_.events;
  if (cross_time_[i] <= coll_time_[i]) {
    cross_cell(i);
    return EventKind::Crossing;
  }
  const std::int32_t j = coll_partner_[i];
  if (counter_[j] != coll_counter_[i]) {  // the partner has changed course since
    ++stats_.stale;
    predict(i);
    return EventKind::Stale;
  }
  if (config_.sticky())
    collide_sticky(i, j);
  else
    collide_pair(i, j);
  return EventKind::Collision;
}

template <int D>
void Engine<D>::collide_pair(std::int32_t i, std::int32_t j) {
  advance(i);
  advance(j);
  const Vec<D> dr = grid_.minimum_image(pos_[j] - pos_[i]);
  const double dist = dr.norm();
  if (dist < 1.0 - 1e-9) {
    ++stats_.overlaps;
    stats_.max_overlap = std::max(stats_.max_overlap, 1.0 - dist);
  }
  const CollisionResult res =
      collide<D>(vel_[i], vel_[j], dr / dist, config_.restitution, config_.cutoff);
  if (res.impulse > 0) {
    ++stats_.collisions;
    stats_.inelastic += res.inelastic;
    stats_.virial += res.impulse * dist;
    ++counter_[i];
    ++counter_[j];
    mark_active(i);
    mark_active(j);
  }
  predict(i);
  predict(j);
}

// Exact sticky limit in 1D: the two clusters that meet merge and move on with their common
// centre-of-mass velocity (the paper's r = 0 calculation).
template <int D>
void Engine<D>::collide_sticky(std::int32_t i, std::int32_t j) {
  if constexpr (D == 1) {
    const auto n = static_cast<std::int32_t>(vel_.size());
    advance(i);
    advance(j);
    const bool i_left = grid_.minimum_image(pos_[j] - pos_[i])[0] > 0;
    const std::int32_t left = i_left ? i : j, right = i_left ? j : i;
    GS_CHECK((left + 1) % n == right);
    const std::int32_t lo = cluster_lo_[left], hi = cluster_hi_[right];
    const std::int32_t size_a = (left - lo + n) % n + 1, size_b = (hi - right + n) % n + 1;
    const Vec<D> v =
        (static_cast<double>(size_a) * vel_[left] + static_cast<double>(size_b) * vel_[right]) /
        static_cast<double>(size_a + size_b);
    ++stats_.collisions;
    ++stats_.inelastic;
    cluster_hi_[lo] = hi;
    cluster_lo_[hi] = lo;
    for (std::int32_t k = lo, m = 0; m < size_a + size_b; k = (k + 1) % n, ++m) {
      advance(k);
      vel_[k] = v;
      ++counter_[k];
      mark_active(k);
    }
    for (std::int32_t k = lo, m = 0; m < size_a + size_b; k = (k + 1) % n, ++m) predict(k);
  } else {
    GS_CHECK_MSG(false, "sticky coalescence exists only in 1D");
  }
}

template <int D>
void Engine<D>::cross_cell(std::int32_t i) {
  ++stats_.crossings;
  advance(i);
  const int k = cross_dir_[i] >> 1;
  const int step = (cross_dir_[i] & 1) ? 1 : -1;
  cell_remove(i, grid_.index(cell_[i]));
  int c = cell_[i][k] + step;
  if (c == grid_.per_side()) {
    c = 0;
    pos_[i][k] -= grid_.box();
    ++image_[i][k];
  } else if (c < 0) {
    c = grid_.per_side() - 1;
    pos_[i][k] += grid_.box();
    --image_[i][k];
  }
  cell_[i][k] = c;
  cell_insert(i, grid_.index(cell_[i]));

  // The best collision among the old neighbours is still the best unless its partner moved on;
  // then only the layer of cells that has just come into reach needs a look.
  const std::int32_t p = coll_partner_[i];
  if (p < 0 || counter_[p] != coll_counter_[i]) {
    predict(i);
    return;
  }
  const Vec<D> xi = pos_[i];
  grid_.for_each_in_layer(cell_[i], k, grid_.wrap(c + step),
                          [&](std::int32_t cell) { scan_cell(i, xi, cell); });
  predict_crossing(i, xi);
  schedule(i);
}

template <int D>
Sample Engine<D>::sample() const {
  Sample s;
  s.t = now_;
  s.collisions = stats_.collisions;
  s.events = stats_.events;
  Vec<D> com = Vec<D>::Zero();
  double v2_active = 0;
  for (std::int32_t i : moved_) {
    const double v2 = vel_[i].squaredNorm();
    s.energy += 0.5 * v2;
    for (int k = 0; k < D; ++k) s.momentum[k] += vel_[i][k];
    if (!active_[i]) continue;
    ++s.active;
    v2_active += v2;
    com += position(i);
  }
  if (s.active == 0) return s;
  com /= static_cast<double>(s.active);
  double r2 = 0;
  for (std::int32_t i : moved_)
    if (active_[i]) r2 += (position(i) - com).squaredNorm();
  s.radius_rms = std::sqrt(r2 / static_cast<double>(s.active));
  s.speed_rms = std::sqrt(v2_active / static_cast<double>(s.active));
  return s;
}

template <int D>
Snapshot Engine<D>::snapshot() const {
  Snapshot s;
  s.info.dim = D;
  s.info.box = grid_.box();
  s.info.time = now_;
  s.info.density = static_cast<double>(vel_.size()) / std::pow(grid_.box(), D);
  s.info.restitution = config_.restitution;
  s.info.cutoff = config_.cutoff;
  s.info.speed = config_.speed;
  s.info.seed = config_.seed;
  const std::size_t n = vel_.size();
  s.position.resize(n);
  s.velocity.resize(n);
  s.radius.assign(n, 0.5);
  s.active = active_;
  s.first_collision = first_collision_;
  for (std::size_t i = 0; i < n; ++i) {
    const Vec<D> x = position(static_cast<std::int32_t>(i));
    s.position[i].setZero();
    s.velocity[i].setZero();
    s.position[i].template head<D>() = x;
    s.velocity[i].template head<D>() = vel_[i];
  }
  return s;
}

template <int D>
double Engine<D>::max_overlap_now() const {
  const auto n = static_cast<std::int32_t>(vel_.size());
  double deepest = 0;
  for (std::int32_t i = 0; i < n; ++i) {
    const Vec<D> xi = pos_[i] + vel_[i] * (now_ - tloc_[i]);
    grid_.for_each_neighbour(cell_[i], [&](std::int32_t cell) {
      for (std::int32_t j = head_[cell]; j >= 0; j = next_[j])
        if (j > i) deepest = std::max(deepest, 1.0 - separation(i, xi, j).norm());
    });
  }
  return deepest;
}

std::unique_ptr<Simulation> make_simulation(const PhysicsConfig& c) {
  validate(c);
  switch (c.dim) {
    case 1: return std::make_unique<Engine<1>>(c, make_initial_state<1>(c));
    case 2: return std::make_unique<Engine<2>>(c, make_initial_state<2>(c));
    default: return std::make_unique<Engine<3>>(c, make_initial_state<3>(c));
  }
}

template class Engine<1>;
template class Engine<2>;
template class Engine<3>;

}  // namespace gs
