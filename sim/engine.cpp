#include "sim/engine.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <iterator>
#include <utility>

#include "sim/collision.h"
#include "sim/error.h"
#include "sim/format.h"
#include "sim/huge_pages.h"
#include "sim/observables.h"
#include "sim/rng.h"
#include "sim/stop.h"

namespace gs {

template <int D>
Engine<D>::Engine(const PhysicsConfig& c, InitialState<D> init)
    : config_(c), grid_(c.box()), queue_(0, init.position.size()) {
  const std::size_t n = init.position.size();
  GS_CHECK(n >= 2 && (init.velocity.empty() ? init.kicked >= 0 : init.velocity.size() == n));
  GS_CHECK(n < static_cast<std::size_t>(INT32_MAX));
  GS_CHECK(D == 1 || grid_.per_side() <= INT16_MAX);  // Prediction::cell; validate() tells users
  reserve_particles(n);
  head_ = ZeroPages<std::int32_t>(grid_.cell_count(), Touch::Sparse);
  if constexpr (kRests) {
    if (init.velocity.empty()) {
      // A kick: the particles wait in the resting store, which takes the initial positions
      // over, and the kicked one becomes the first record.
      const std::int32_t kicked = init.kicked;
      const Vec<D> kick = init.kick_velocity;
      rest_ = RestingStore<D>(std::move(init.position), grid_);
      init = InitialState<D>{};
      rests_ = true;
      compact_at_ = next_compaction();
      std::int32_t r = 0;
      while (rest_.tag(r) != kicked) ++r;
      const std::int32_t i = promote(r);
      kin_[i].v = kick;
      mark_moving(i);
      predict(i);
      return;
    }
  }
  // Every particle a record: 1D, whose sticky clusters rely on the order along the line, and
  // thermal starts, where all move.
  for (std::int32_t t : cell_order(init.position))
    add_record(init.position[t], init.velocity_of(t), t, grid_.coords_of(init.position[t]));
  init = InitialState<D>{};
  if (config_.sticky()) {
    for (std::size_t i = 1; i < n; ++i) GS_CHECK(kin_[i].x[0] >= kin_[i - 1].x[0]);
    cluster_lo_.resize(n);
    cluster_hi_.resize(n);
    for (std::size_t i = 0; i < n; ++i)
      cluster_lo_[i] = cluster_hi_[i] = static_cast<std::int32_t>(i);
  }
  for (std::size_t i = 0; i < n; ++i)
    if (kin_[i].v.squaredNorm() > 0) mark_moving(static_cast<std::int32_t>(i));
  for (std::int32_t i : moved_) predict(i);
}

template <int D>
Engine<D>::Engine(const PhysicsConfig& c)
    : config_(c), grid_(c.box()), queue_(0, static_cast<std::size_t>(c.particles)) {
  GS_CHECK(D > 1 && c.unbounded() && c.initial == Initial::Kick);
  GS_CHECK(grid_.side() == kUnboundedCellSide && grid_.per_side() <= INT16_MAX);
  reserve_particles(static_cast<std::size_t>(c.particles));
  head_offset_ = 2;
  head_ = ZeroPages<std::int32_t>(grid_.cell_count(), Touch::Sparse);
  medium_ = std::make_unique<UnboundedMedium<D>>(
      MediumOptions{D, c.density, grid_.side(), c.seed, c.realisation});
  kick_nearest_centre();
}

// The particles of the unbounded medium are made in rings of cells around the centre until the
// nearest one is known (every cell within its distance made); it gets the kick. The medium's
// origin is the box centre, where the kicks of box runs are too.
template <int D>
void Engine<D>::kick_nearest_centre() {
  const int middle = grid_.per_side() / 2;
  const double centre = middle * grid_.side();
  std::int32_t kicked = -1;
  double best = INFINITY;
  // Cells middle - ring .. middle + ring hold every point within ring cell sides of the centre
  // (the corner of cell `middle`).
  for (int ring = 1;; ++ring) {
    throw_if_stopped();  // validate() bounds the rings to tens, but a stop is honoured anyway
    const IVec<D> lo = IVec<D>::Constant(middle - ring);
    for (IVec<D> c = lo;;) {
      const std::int32_t cell = grid_.index(c);
      if (head_[cell] == kUnmadeCell) make_cell(cell);
      int k = 0;
      for (; k < D; ++k) {  // the next cell of the cube, x fastest
        if (++c[k] <= middle + ring) break;
        c[k] = lo[k];
      }
      if (k == D) break;
    }
    for (std::int32_t i = 0; i < moving(); ++i) {
      const double d = (kin_[i].x - Vec<D>::Constant(centre)).norm();
      if (d < best) best = d, kicked = i;  // ties: the first made
    }
    if (kicked >= 0 && best <= ring * grid_.side()) break;
  }
  Rng kick_rng(config_.seed, config_.realisation, Stream::Kick);
  kin_[kicked].v = config_.speed * random_direction<D>(kick_rng);
  mark_moving(kicked);
  predict(kicked);
}

// Room for n particles in every per-particle array, so that the unbounded medium's new particles
// never move them (references stay valid, the hot loop never reallocates). Reserved memory is
// address space until it is written.
template <int D>
void Engine<D>::reserve_particles(std::size_t n) {
  capacity_ = n;
  kin_.reserve(n);
  tag_.reserve(n);
  image_ = ZeroPages<Image>(n, Touch::Sparse);
  next_.reserve(n);
  pred_.reserve(n);
  first_collision_.reserve(n);
  moved_.reserve(n);
}

template <int D>
std::int32_t Engine<D>::add_record(const Vec<D>& x, const Vec<D>& v, std::int32_t tag,
                                   const IVec<D>& cell) {
  // Within the reserved capacity: nothing moves.
  GS_CHECK(kin_.size() < capacity_);
  const auto i = static_cast<std::int32_t>(kin_.size());
  kin_.push_back({x, 0.0, v, 0});
  tag_.push_back(tag);
  next_.push_back(-1);
  pred_.push_back(Prediction{});
  first_collision_.push_back(-1.0);
  queue_.grow(kin_.size());
  set_cell(i, cell);
  cell_insert(i, grid_.index(cell));
  return i;
}

// A resting particle gets its record as it was (at rest since t = 0), in the cell whose run held
// it.
template <int D>
std::int32_t Engine<D>::promote(std::int32_t r) {
  if constexpr (kRests) {
    const IVec<D> cell = grid_.coords_of(rest_.position(r));
    const std::int32_t i = add_record(rest_.position(r), Vec<D>::Zero(), rest_.tag(r), cell);
    rest_.leave(r, grid_.index(cell));
    return i;
  } else {
    GS_CHECK_MSG(false, "1D keeps no resting store");
    return r;
  }
}

template <int D>
void Engine<D>::compact_store() {
  if constexpr (kRests) {
    const auto rename = rest_.compact();
    for (Prediction& p : pred_)
      if (p.partner < -1) p.partner = resting_partner(rename(-2 - p.partner));
    compact_at_ = next_compaction();
  }
}

template <int D>
void Engine<D>::make_cell(std::int32_t cell) {
  const int side = grid_.per_side(), middle = side / 2;
  typename UnboundedMedium<D>::Cell key;
  const IVec<D> c = grid_.coords(cell);
  for (int k = 0; k < D; ++k) {
    key[k] = c[k] - middle;
    // The stencil of a particle in the outermost cells would wrap round the periodic grid.
    if (c[k] == 0 || c[k] == side - 1)
      throw UserError("--t-max " + format_double(config_.t_max) +
                      ": the front reached the edge of the unbounded medium's addressable "
                      "region (radius " +
                      format_double((middle - 1) * grid_.side()) +
                      " diameters, set by --particles) at t = " + format_double(now_) +
                      "; use a smaller --t-max or a larger --particles");
  }
  fresh_.clear();
  medium_->particles(key, fresh_);
  if (kin_.size() + fresh_.size() > capacity_)
    throw UserError("--particles " + std::to_string(config_.particles) +
                    ": the unbounded medium has made as many particles as it may by t = " +
                    format_double(now_) + "; raise --particles or lower --t-max");
  take_memory(fresh_.size());
  if (medium_->cached_candidates() > kMemoCandidates || medium_->memory_bytes() > kMemoBytes)
    medium_->clear();
  head_[cell] = kEmptyCell;
  made_.push_back(cell);
  const Vec<D> shift = Vec<D>::Constant(middle * grid_.side());
  // Records at once, in their medium cell whatever round-off the shift made (the engine tolerates
  // a hair outside): the medium is made just ahead of the front, where most particles are about
  // to be hit, and a resting store there costs a 3D r = 0.9 blast 20% more time per collision.
  for (const Vec<D>& x : fresh_)
    add_record(x + shift, Vec<D>::Zero(), static_cast<std::int32_t>(kin_.size()), c);
}

template <int D>
void Engine<D>::take_memory(std::size_t n) {
  if (bytes_each_ == 0)  // once: every cell made asks, and the estimate takes a pow
    bytes_each_ = static_cast<std::int64_t>(std::ceil(unbounded_bytes_per_particle(config_)));
  const std::int64_t each = bytes_each_;
  if (memory_.take(static_cast<std::int64_t>(n) * each)) return;
  const MemoryBudget& all = MemoryBudget::process();
  throw UserError("--t-max " + format_double(config_.t_max) + ": the unbounded medium's " +
                  std::to_string(kin_.size() + n) + " particles (about " + std::to_string(each) +
                  " B each) would not fit in this machine's " +
                  format_double(std::round(static_cast<double>(all.capacity()) / 1e8) / 10) +
                  " GB of memory" +
                  (all.taken() > memory_.bytes() ? " beside this process's other runs" : "") +
                  " at t = " + format_double(now_) + "; use a smaller --t-max");
}

namespace {

// A box's cell heads in a checkpoint: the first record of each cell or -1.
void save_heads(StateWriter& out, const ZeroPages<std::int32_t>& head, std::int32_t offset) {
  out.value(static_cast<std::uint64_t>(head.size()));
  std::int32_t chunk[4096];
  for (std::size_t at = 0; at < head.size(); at += std::size(chunk)) {
    const std::size_t n = std::min(std::size(chunk), head.size() - at);
    for (std::size_t k = 0; k < n; ++k) chunk[k] = head[at + k] - offset;
    out.bytes(chunk, n * sizeof(std::int32_t));
  }
}

void load_heads(StateReader& in, ZeroPages<std::int32_t>& head, std::int32_t offset) {
  in.expect(in.value<std::uint64_t>() == head.size());
  std::int32_t chunk[4096];
  for (std::size_t at = 0; at < head.size(); at += std::size(chunk)) {
    const std::size_t n = std::min(std::size(chunk), head.size() - at);
    in.bytes(chunk, n * sizeof(std::int32_t));
    for (std::size_t k = 0; k < n; ++k) head[at + k] = chunk[k] + offset;
  }
}

// The records' images as the vector of them that the stream held when they were one (the format
// is unchanged); loading writes only the non-zero ones, so that a resumed kick's images stay
// untouched zero pages.
template <class Image>
void save_images(StateWriter& out, const Image* image, std::size_t m) {
  out.value(static_cast<std::uint64_t>(m));
  out.bytes(image, m * sizeof(Image));
}

template <class Image>
void load_images(StateReader& in, Image* image, std::size_t m) {
  in.expect(in.value<std::uint64_t>() == m);
  Image chunk[1024];
  for (std::size_t at = 0; at < m; at += std::size(chunk)) {
    const std::size_t n = std::min(std::size(chunk), m - at);
    in.bytes(chunk, n * sizeof(Image));
    for (std::size_t k = 0; k < n; ++k)
      if (chunk[k] != Image{}) image[at + k] = chunk[k];
  }
}

}  // namespace

template <int D>
void Engine<D>::save(StateWriter& out) const {
  out.string(to_toml(config_));
  out.value(now_);
  out.value(stats_);
  out.vector(kin_);
  out.vector(tag_);
  save_images(out, image_.data(), kin_.size());
  if (medium_) {
    // The made cells and their heads: the rest of the grid is zero pages.
    std::vector<std::int32_t> heads(made_.size());
    for (std::size_t k = 0; k < made_.size(); ++k) heads[k] = head_[made_[k]];
    out.vector(made_);
    out.vector(heads);
  } else {
    save_heads(out, head_, head_offset_);
  }
  out.vector(next_);
  out.vector(pred_);
  queue_.save(out);
  out.vector(first_collision_);
  out.vector(moved_);
  out.vector(cluster_lo_);
  out.vector(cluster_hi_);
  out.value(rests_);
  if constexpr (kRests) {
    if (rests_) {
      rest_.save(out);
      out.value(compact_at_);
    }
  }
}

template <int D>
Engine<D>::Engine(const PhysicsConfig& c, StateReader& in)
    : config_(c), grid_(c.box()), queue_(0, static_cast<std::size_t>(c.particles)) {
  if (in.string() != to_toml(c))
    throw UserError("the checkpoint is of a run with other physics than its run.toml");
  const auto cap = static_cast<std::size_t>(c.particles);
  reserve_particles(cap);  // before reading: a stream's arrays must not move later
  in.value(now_);
  in.value(stats_);
  in.vector(kin_);
  in.expect(kin_.size() <= cap);
  const std::size_t m = kin_.size();
  in.vector(tag_);
  load_images(in, image_.data(), m);
  if (c.unbounded()) {
    GS_CHECK(D > 1);
    head_offset_ = 2;
    head_ = ZeroPages<std::int32_t>(grid_.cell_count(), Touch::Sparse);
    medium_ = std::make_unique<UnboundedMedium<D>>(
        MediumOptions{D, c.density, grid_.side(), c.seed, c.realisation});
    std::vector<std::int32_t> heads;
    in.vector(made_);
    in.vector(heads);
    in.expect(heads.size() == made_.size());
    for (std::size_t k = 0; k < made_.size(); ++k) {
      in.expect(made_[k] >= 0 && static_cast<std::size_t>(made_[k]) < head_.size() &&
                heads[k] >= kEmptyCell && heads[k] < static_cast<std::int64_t>(m) + head_offset_);
      head_[made_[k]] = heads[k];
    }
  } else {
    head_ = ZeroPages<std::int32_t>(grid_.cell_count(), Touch::Sparse);
    load_heads(in, head_, head_offset_);
  }
  in.vector(next_);
  in.vector(pred_);
  queue_.load(in);
  in.vector(first_collision_);
  in.vector(moved_);
  in.vector(cluster_lo_);
  in.vector(cluster_hi_);
  in.value(rests_);
  in.expect(!rests_ || (D > 1 && !c.unbounded()));
  if constexpr (kRests) {
    if (rests_) {
      rest_ = RestingStore<D>(grid_);
      rest_.load(in, c.particles);
      in.value(compact_at_);
      in.expect(compact_at_ > 0);
    }
  }
  in.expect(tag_.size() == m && next_.size() == m && pred_.size() == m &&
            first_collision_.size() == m && moved_.size() <= m && (!rests_ || moved_.empty()) &&
            queue_.particles() == m);
  // A partner is a record, none, or (where particles rest) a slot of the store.
  const std::int64_t slots = rests_ ? rest_.slots() : 0;
  for (const Prediction& p : pred_)
    in.expect(p.partner < static_cast<std::int64_t>(m) && -2 - std::int64_t{p.partner} < slots);
  if (c.unbounded()) {
    take_memory(m);
  } else {
    in.expect(static_cast<std::size_t>(size()) == cap);
  }
}

namespace {

// Interleaves the bits of the cell coordinates (Morton order): cells close in space get close
// codes in every direction, not only along x.
template <int D>
std::uint64_t morton(const IVec<D>& c) {
  std::uint64_t code = 0;
  for (int bit = 0; bit < 63 / D; ++bit)
    for (int k = 0; k < D; ++k)
      code |= ((static_cast<std::uint64_t>(c[k]) >> bit) & 1u) << (bit * D + k);
  return code;
}

}  // namespace

// The records in Morton order of their cells, so that the neighbours a search visits share cache
// lines and pages (for 1e5 spheres this halves the cost of a collision). In 1D the initial order
// already runs along the line, and sticky clusters rely on it. tag_ remembers the original
// numbering for snapshots.
template <int D>
std::vector<std::int32_t> Engine<D>::cell_order(const VecArray<D>& position) const {
  const std::size_t n = position.size();
  std::vector<std::int32_t> order(n);
  for (std::size_t i = 0; i < n; ++i) order[i] = static_cast<std::int32_t>(i);
  if constexpr (D > 1) {
    // Sorting (key, index) pairs keeps ties in index order and reads memory in sequence.
    std::vector<std::pair<std::uint64_t, std::int32_t>> keyed(n);
    for (std::size_t i = 0; i < n; ++i)
      keyed[i] = {morton<D>(grid_.coords_of(position[i])), static_cast<std::int32_t>(i)};
    std::sort(keyed.begin(), keyed.end());
    for (std::size_t i = 0; i < n; ++i) order[i] = keyed[i].second;
  }
  return order;
}

template <int D>
void Engine<D>::cell_insert(std::int32_t i, std::int32_t cell) {
  const std::int32_t first = head_[cell] - head_offset_;  // -1: the cell is empty
  next_[i] = first;
  head_[cell] = i + head_offset_;
}

template <int D>
void Engine<D>::cell_remove(std::int32_t i, std::int32_t cell) {
  // Singly linked: a cell holds a few records, and a back link would cost 4 B a record.
  std::int32_t j = head_[cell] - head_offset_;
  if (j == i) {
    head_[cell] = next_[i] + head_offset_;
    return;
  }
  for (;; j = next_[j]) {
    GS_CHECK(j >= 0);  // i is in its cell's list
    if (next_[j] == i) break;
  }
  next_[j] = next_[i];
}

template <int D>
void Engine<D>::mark_moving(std::int32_t i) {
  if (kin_[i].moving) return;
  kin_[i].moving = true;
  if (!rests_) moved_.push_back(i);  // capacity reserved for every particle: never reallocates
}

template <int D>
void Engine<D>::mark_active(std::int32_t i) {
  mark_moving(i);
  if (kin_[i].active) return;
  kin_[i].active = true;
  first_collision_[i] = now_;
}

template <int D>
void Engine<D>::advance(std::int32_t i) {
  Kinematics& k = kin_[i];
  k.x += k.v * (now_ - k.t);
  k.t = now_;
}

// A kick in a box makes the kicked particle the first record (the constructor) and records keep
// their order, so it is record 0; its counter is bumped at each of its collisions and nowhere
// else in 2D and 3D.
template <int D>
KickedParticle Engine<D>::kicked_particle() const {
  KickedParticle out;
  if (D < 2 || config_.initial != Initial::Kick || config_.unbounded() || kin_.empty()) return out;
  out.known = true;
  out.tag = tag_[0];
  const Vec<D> x = position(0) - Vec<D>::Constant(0.5 * grid_.box());
  for (int k = 0; k < D; ++k) out.displacement[k] = x[k];
  out.speed = kin_[0].v.norm();
  out.collisions = kin_[0].counter;
  return out;
}

template <int D>
Vec<D> Engine<D>::position(std::int32_t i) const {
  Vec<D> x = kin_[i].x + kin_[i].v * (now_ - kin_[i].t);
  for (int k = 0; k < D; ++k) x[k] += image_[i][k] * grid_.box();
  return x;
}

// Separation from i (at xi, current time) to j, nearest periodic image.
template <int D>
inline Vec<D> Engine<D>::separation(const Vec<D>& xi, std::int32_t j) const {
  const Kinematics& k = kin_[j];
  return grid_.minimum_image(k.x + k.v * (now_ - k.t) - xi);
}

// Lists the particles of the given cells other than i and requests their cache lines. A search
// is bound by memory latency: the cell lists are small and apart from the particle data, so
// walking them does not wait on the particles, and the particles' lines arrive while the lists
// of the other cells (or of the other sphere of a collision) are still being walked.
template <int D>
template <bool kMakes, class ForEachCell>
void Engine<D>::gather(std::int32_t i, Neighbours& nb, ForEachCell&& for_each_cell) {
  std::int32_t first[27], rest_begin[27], rest_end[27];  // not zeroed: a search's every cost counts
  int cells = 0, resting_cells = 0;
  for_each_cell([&](std::int32_t cell) {
    // A cell that comes into a moving particle's reach is made first.
    if constexpr (kMakes)
      if (head_[cell] == kUnmadeCell) [[unlikely]]
        make_cell(cell);
    const std::int32_t h = head_[cell] - head_offset_;
    first[cells] = h;
    cells += h >= 0;  // no branch: whether a cell is empty is a coin toss
    if constexpr (kRests) {
      if (rests_) {
        const auto run = rest_.run(cell);
        rest_begin[resting_cells] = run.begin;
        rest_end[resting_cells] = run.end;
        resting_cells += run.begin < run.end;
      }
    }
  });
  int count = 0;
  for (int c = 0; c < cells; ++c)
    for (std::int32_t j = first[c]; j >= 0; j = next_[j]) {
      if (j == i) continue;
      __builtin_prefetch(&kin_[j]);
      GS_DCHECK(count < Neighbours::kMax);  // the geometry bounds it (sim/engine.h)
      nb.who[count++] = j;
    }
  // Once per search in Release: an overrun of `who` lands in `rest`, filled only after this.
  GS_CHECK(count <= Neighbours::kMax);
  nb.count = count;
  // A cell's resting particles are one run of memory: their lines are requested as listed.
  int rest = 0;
  for (int c = 0; c < resting_cells; ++c) {
    if constexpr (kRests) __builtin_prefetch(rest_.positions() + rest_begin[c]);
    GS_CHECK(count + rest + (rest_end[c] - rest_begin[c]) <= Neighbours::kMax);  // per cell
    for (std::int32_t r = rest_begin[c]; r < rest_end[c]; ++r) nb.rest[rest++] = r;
  }
  nb.rest_count = rest;
}

template <int D>
void Engine<D>::gather_stencil(std::int32_t i, Neighbours& nb) {
  gather_cells(i, nb, [&](auto&& f) { grid_.for_each_neighbour(cell_of(i), f); });
}

namespace {

constexpr int kBatch = 64;  // pairs tested together

// Of a batch's pairs, those that will touch before `best`, in turn: take(m) for each new earliest.
template <class Take>
void earliest_contact(int count, double now, const double* bb, const double* rr, const double* disc,
                      double& best, Take&& take) {
  int hit[kBatch];
  int hits = 0;
  for (int m = 0; m < count; ++m) {
    hit[hits] = m;
    hits += will_touch(bb[m], disc[m]);
  }
  for (int h = 0; h < hits; ++h) {
    const int m = hit[h];
    const double t = now + contact_delay(bb[m], rr[m], disc[m]);
    if (t < best) {
      best = t;
      take(m);
    }
  }
}

}  // namespace

// Looks for a collision of i (at xi now) with the gathered particles earlier than its current
// one. Separations and relative velocities are gathered into small arrays, every pair is tested
// in a loop the compiler vectorises, and only those that will touch (about one in six at packing
// 0.5) go on to the square root and the division.
template <int D>
void Engine<D>::search(std::int32_t i, const Vec<D>& xi, const Neighbours& nb) {
  alignas(64) double dr[D][kBatch], dv[D][kBatch], bb[kBatch], rr[kBatch], disc[kBatch];
  double best = pred_[i].coll_time;
  const Vec<D> vi = kin_[i].v;
  for (int start = 0; start < nb.count; start += kBatch) {
    const std::int32_t* who = nb.who + start;
    const int count = std::min(kBatch, nb.count - start);
    // Component by component on plain doubles: through Eigen temporaries the compiler keeps the
    // separation on the stack and stalls on reading it back.
    for (int m = 0; m < count; ++m) {
      const Kinematics& k = kin_[who[m]];
      const double since = now_ - k.t;
      for (int a = 0; a < D; ++a) {
        dr[a][m] = grid_.minimum_image(k.x[a] + k.v[a] * since - xi[a]);
        dv[a][m] = k.v[a] - vi[a];
      }
    }
    for (int m = 0; m < count; ++m) {
      double b = 0, r2 = 0, a = 0;
      for (int k = 0; k < D; ++k) {
        b += dr[k][m] * dv[k][m];
        r2 += dr[k][m] * dr[k][m];
        a += dv[k][m] * dv[k][m];
      }
      bb[m] = b;
      rr[m] = r2;
      disc[m] = contact_discriminant(b, r2, a);
    }
    earliest_contact(count, now_, bb, rr, disc, best, [&](int m) {
      pred_[i].partner = who[m];
      pred_[i].partner_counter = kin_[who[m]].counter;
    });
  }
  if constexpr (kRests)
    if (nb.rest_count > 0) search_resting(i, xi, nb, best);
  pred_[i].coll_time = best;
}

// The same search over resting particles: their positions as they were at t = 0, their velocity
// zero (the arithmetic is the records' with v = 0, to the bit). A dead slot's NaN fails the test.
template <int D>
void Engine<D>::search_resting(std::int32_t i, const Vec<D>& xi, const Neighbours& nb,
                               double& best) {
  if constexpr (kRests) {
    alignas(64) double dr[D][kBatch], bb[kBatch], rr[kBatch], disc[kBatch];
    double dv[D], a = 0;
    for (int k = 0; k < D; ++k) {
      dv[k] = 0.0 - kin_[i].v[k];
      a += dv[k] * dv[k];
    }
    const Vec<D>* x = rest_.positions();
    for (int start = 0; start < nb.rest_count; start += kBatch) {
      const std::int32_t* who = nb.rest + start;
      const int count = std::min(kBatch, nb.rest_count - start);
      for (int m = 0; m < count; ++m)
        for (int k = 0; k < D; ++k) dr[k][m] = grid_.minimum_image(x[who[m]][k] - xi[k]);
      for (int m = 0; m < count; ++m) {
        double b = 0, r2 = 0;
        for (int k = 0; k < D; ++k) {
          b += dr[k][m] * dv[k];
          r2 += dr[k][m] * dr[k][m];
        }
        bb[m] = b;
        rr[m] = r2;
        disc[m] = contact_discriminant(b, r2, a);
      }
      earliest_contact(count, now_, bb, rr, disc, best, [&](int m) {
        pred_[i].partner = resting_partner(who[m]);
        pred_[i].partner_counter = 0;  // unused: a slot's particle has changed course once it left
      });
    }
  }
}

// A particle that has left the resting store since a prediction made while it rested has been
// hit (something changed its course, or it would still rest).
template <int D>
bool Engine<D>::partner_changed(std::int32_t i) const {
  const std::int32_t p = pred_[i].partner;
  if (p >= 0) return kin_[p].counter != pred_[i].partner_counter;
  if constexpr (kRests)
    if (p < -1) return rest_.dead(-2 - p);
  return false;
}

template <int D>
void Engine<D>::predict_crossing(std::int32_t i, const Vec<D>& xi) {
  double best = kNever;
  std::int8_t dir = 0;
  const double h = grid_.side();
  for (int k = 0; k < D; ++k) {
    const double v = kin_[i].v[k];
    if (v == 0) continue;
    const double wall = (pred_[i].cell[k] + (v > 0 ? 1 : 0)) * h;
    const double dt = std::max(0.0, (wall - xi[k]) / v);  // round-off can put xi a hair past it
    if (dt < best) {
      best = dt;
      dir = static_cast<std::int8_t>(2 * k + (v > 0 ? 1 : 0));
    }
  }
  pred_[i].cross_time = now_ + best;
  pred_[i].cross_dir = dir;
}

template <int D>
void Engine<D>::schedule(std::int32_t i) {
  const double t = std::min(pred_[i].coll_time, pred_[i].cross_time);
  if (t == kNever)
    queue_.remove(i);
  else
    queue_.set(i, t);
}

// Full prediction: every neighbour cell and the next crossing. Particles at rest do this too
// when they have just stopped, because a moving neighbour may be heading for them.
template <int D>
void Engine<D>::predict(std::int32_t i) {
  gather_stencil(i, near_[0]);
  predict_from(i, near_[0]);
  schedule(i);
}

// The same, with i's stencil already gathered, short of putting the event into the queue. The
// queue's bucket for it is requested, because that costs a cache miss too.
template <int D>
void Engine<D>::predict_from(std::int32_t i, const Neighbours& nb) {
  const Vec<D> xi = kin_[i].x + kin_[i].v * (now_ - kin_[i].t);
  pred_[i].coll_time = kNever;
  pred_[i].partner = -1;
  search(i, xi, nb);
  predict_crossing(i, xi);
  queue_.prefetch_bucket(std::min(pred_[i].coll_time, pred_[i].cross_time));
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
    // A stop is seen within kStopPollEvents events (a few ms), even where events pile up at one
    // instant and the clock does not move: one test of a counter an event, a relaxed load of the
    // flag per batch. The clock stays at the last event; the caller sees stop_requested().
    if ((stats_.events & (kStopPollEvents - 1)) == 0 && stop_requested()) [[unlikely]]
      return;
  }
  now_ = std::max(now_, t);
}

template <int D>
EventKind Engine<D>::process_next() {
  const std::int32_t i = queue_.top();
  // Events come in time order but anywhere in the box, so each starts with cache misses on its
  // particles' records. Those of the next two events are requested while this one is handled:
  // the one after next gets its own records, the next one (whose own came one event ago) its
  // partner's.
  const EventQueue::Soon soon = queue_.peek_soon(2);
  if (soon.count > 1) {
    const std::int32_t k = soon.id[1];
    __builtin_prefetch(&pred_[k]);
    __builtin_prefetch(&kin_[k]);
  }
  if (soon.count > 0)
    if (const std::int32_t p = pred_[soon.id[0]].partner; p >= 0) __builtin_prefetch(&kin_[p]);
  ++stats_.events;
  if (pred_[i].cross_time <= pred_[i].coll_time) {
    cross_cell(i);
    return EventKind::Crossing;
  }
  std::int32_t j = pred_[i].partner;
  if constexpr (kRests) {
    if (j < -1) {  // at rest when predicted: its record is made now, or it has moved since
      const std::int32_t r = -2 - j;
      if (rest_.dead(r)) {
        ++stats_.stale;
        predict(i);
        return EventKind::Stale;
      }
      j = promote(r);
      if (rest_.slots() - rest_.resting() >= compact_at_) [[unlikely]]
        compact_store();
    }
  }
  // The partner's records are needed only after i's search, but are requested now.
  __builtin_prefetch(&pred_[j]);
  queue_.prefetch(j);
  if (kin_[j].counter != pred_[i].partner_counter) {  // the partner has changed course since
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
  const Vec<D> dr = grid_.minimum_image(kin_[j].x - kin_[i].x);
  const double dist = dr.norm();
  if (dist < 1.0 - 1e-9) {
    ++stats_.overlaps;
    stats_.max_overlap = std::max(stats_.max_overlap, 1.0 - dist);
  }
  const CollisionResult res =
      collide<D>(kin_[i].v, kin_[j].v, dr / dist, config_.restitution, config_.cutoff);
  if (res.impulse > 0) {
    ++stats_.collisions;
    stats_.inelastic += res.inelastic;
    stats_.virial += res.impulse * dist;
    ++kin_[i].counter;
    ++kin_[j].counter;
    mark_active(i);
    mark_active(j);
  }
  // Both stencils are gathered first, so that j's particles arrive during i's search, and both
  // events are queued last, so that i's bucket in the queue arrives during j's search.
  gather_stencil(i, near_[0]);
  gather_stencil(j, near_[1]);
  predict_from(i, near_[0]);
  queue_.prefetch_neighbours(j);  // j's entry came during i's search; its neighbours come now
  predict_from(j, near_[1]);
  schedule(i);
  schedule(j);
}

// Exact sticky limit in 1D: the two clusters that meet merge and move on with their common
// centre-of-mass velocity (the paper's r = 0 calculation).
template <int D>
void Engine<D>::collide_sticky(std::int32_t i, std::int32_t j) {
  if constexpr (D == 1) {
    const auto n = static_cast<std::int32_t>(kin_.size());
    advance(i);
    advance(j);
    const bool i_left = grid_.minimum_image(kin_[j].x - kin_[i].x)[0] > 0;
    const std::int32_t left = i_left ? i : j, right = i_left ? j : i;
    GS_CHECK((left + 1) % n == right);
    const std::int32_t lo = cluster_lo_[left], hi = cluster_hi_[right];
    const std::int32_t size_a = (left - lo + n) % n + 1, size_b = (hi - right + n) % n + 1;
    const Vec<D> v =
        (static_cast<double>(size_a) * kin_[left].v + static_cast<double>(size_b) * kin_[right].v) /
        static_cast<double>(size_a + size_b);
    ++stats_.collisions;
    ++stats_.inelastic;
    cluster_hi_[lo] = hi;
    cluster_lo_[hi] = lo;
    for (std::int32_t k = lo, m = 0; m < size_a + size_b; k = (k + 1) % n, ++m) {
      advance(k);
      kin_[k].v = v;
      ++kin_[k].counter;
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
  const int k = pred_[i].cross_dir >> 1;
  const int step = (pred_[i].cross_dir & 1) ? 1 : -1;
  IVec<D> cell = cell_of(i);
  cell_remove(i, grid_.index(cell));
  int c = cell[k] + step;
  if (c == grid_.per_side()) {
    c = 0;
    kin_[i].x[k] -= grid_.box();
    ++image_[i][k];
  } else if (c < 0) {
    c = grid_.per_side() - 1;
    kin_[i].x[k] += grid_.box();
    --image_[i][k];
  }
  cell[k] = c;
  set_cell(i, cell);
  cell_insert(i, grid_.index(cell));

  // Only the layer of cells that has just come into reach needs a look, unless i's best
  // collision was with a partner that has changed course since: then i's next collision is
  // unknown. With no partner the layer is enough too: an old neighbour that changed course
  // after i's last search searched its own stencil, i included, and holds any collision with i
  // (or re-searches at its own earlier event). In a 3D kick 31% of crossings have no partner and
  // 19% a stale one.
  if (partner_changed(i)) {
    predict(i);
    return;
  }
  // The next crossing needs no search, so it comes first and the queue's bucket for the event
  // is requested while the layer is searched (a new, earlier collision there is the exception).
  const Vec<D> xi = kin_[i].x;
  predict_crossing(i, xi);
  queue_.prefetch_bucket(std::min(pred_[i].coll_time, pred_[i].cross_time));
  gather_cells(i, near_[0],
               [&](auto&& f) { grid_.for_each_in_layer(cell, k, grid_.wrap(c + step), f); });
  search(i, xi, near_[0]);
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
  for_each_moved([&](std::int32_t i) {
    const double v2 = kin_[i].v.squaredNorm();
    s.energy += 0.5 * v2;
    for (int k = 0; k < D; ++k) s.momentum[k] += kin_[i].v[k];
    if (!kin_[i].active) return;
    ++s.active;
    v2_active += v2;
    com += position(i);
  });
  if (s.active == 0) return s;
  com /= static_cast<double>(s.active);
  Eigen::Matrix<double, D, D> gyration = Eigen::Matrix<double, D, D>::Zero();
  for_each_moved([&](std::int32_t i) {
    if (!kin_[i].active) return;
    const Vec<D> d = position(i) - com;
    gyration += d * d.transpose();
  });
  gyration /= static_cast<double>(s.active);
  s.radius_rms = std::sqrt(gyration.trace());
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, D, D>> eigen(gyration);
  Eigen::Vector3d lambda = Eigen::Vector3d::Zero();
  for (int k = 0; k < D; ++k) lambda[k] = eigen.eigenvalues()[D - 1 - k];  // descending
  s.anisotropy = anisotropy_index(D, lambda);
  s.speed_rms = std::sqrt(v2_active / static_cast<double>(s.active));
  return s;
}

template <int D>
void Engine<D>::active_positions(std::vector<Eigen::Vector3d>& out) const {
  out.clear();
  for_each_moved([&](std::int32_t i) {
    if (!kin_[i].active) return;
    Eigen::Vector3d x = Eigen::Vector3d::Zero();
    x.head<D>() = position(i);
    out.push_back(x);
  });
}

template <int D>
void Engine<D>::snapshot_info(Snapshot& s) const {
  s.info = {};
  s.info.dim = D;
  s.info.set_cubic_box(grid_.box());
  s.info.time = now_;
  // An event-driven run has no time step: its step is the collisions so far, which grows with
  // the time as a step does (GSD's configuration/step, OVITO's Timestep).
  s.info.step = stats_.collisions;
  // The unbounded medium's box is the addressable region, almost all of it never made.
  s.info.density =
      medium_ ? config_.density : static_cast<double>(size()) / std::pow(grid_.box(), D);
  s.info.restitution = config_.restitution;
  s.info.cutoff = config_.cutoff;
  s.info.speed = config_.speed;
  s.info.seed = config_.seed;
  s.info.unbounded = medium_ != nullptr;
  s.info.kick = config_.initial == Initial::Kick;
}

template <int D>
void Engine<D>::snapshot(Snapshot& s) const {
  snapshot_info(s);
  const auto n = static_cast<std::size_t>(size());
  reserve_huge(s.position, n);
  reserve_huge(s.velocity, n);
  reserve_huge(s.radius, n);
  reserve_huge(s.first_collision, n);
  s.position.resize(n);
  s.velocity.resize(n);
  s.radius.assign(n, 0.5);
  s.active.resize(n);
  s.first_collision.resize(n);
  for (std::int32_t i = 0; i < moving(); ++i) {
    const auto t = static_cast<std::size_t>(tag_[i]);
    s.position[t].setZero();
    s.velocity[t].setZero();
    s.position[t].template head<D>() = position(i);
    s.velocity[t].template head<D>() = kin_[i].v;
    s.active[t] = kin_[i].active;
    s.first_collision[t] = first_collision_[i];
  }
  if constexpr (kRests) {
    for (std::int32_t r = 0; r < rest_.slots(); ++r) {
      if (rest_.dead(r)) continue;
      const auto t = static_cast<std::size_t>(rest_.tag(r));
      s.position[t].setZero();
      s.velocity[t].setZero();
      s.position[t].template head<D>() = rest_.position(r);
      s.active[t] = 0;
      s.first_collision[t] = -1.0;
    }
  }
}

template <int D>
void Engine<D>::active_snapshot(Snapshot& s) const {
  snapshot_info(s);
  std::vector<std::int32_t> active;
  for_each_moved([&](std::int32_t i) {
    if (kin_[i].active) active.push_back(i);
  });
  // snapshot()'s order is the initial state's (tag_), which active_subset keeps.
  std::sort(active.begin(), active.end(),
            [&](std::int32_t a, std::int32_t b) { return tag_[a] < tag_[b]; });
  const std::size_t n = active.size();
  s.position.assign(n, Eigen::Vector3d::Zero());
  s.velocity.assign(n, Eigen::Vector3d::Zero());
  s.radius.assign(n, 0.5);
  s.active.assign(n, 1);
  s.first_collision.resize(n);
  for (std::size_t k = 0; k < n; ++k) {
    const std::int32_t i = active[k];
    s.position[k].template head<D>() = position(i);
    s.velocity[k].template head<D>() = kin_[i].v;
    s.first_collision[k] = first_collision_[i];
  }
}

template <int D>
double Engine<D>::max_overlap_now() const {
  double deepest = 0;
  const auto overlap = [&](const Vec<D>& xi, const Vec<D>& xj) {
    deepest = std::max(deepest, 1.0 - grid_.minimum_image(xj - xi).norm());
  };
  // Each pair once: records with later records and every resting particle, resting particles
  // with later slots.
  for (std::int32_t i = 0; i < moving(); ++i) {
    const Vec<D> xi = kin_[i].x + kin_[i].v * (now_ - kin_[i].t);
    grid_.for_each_neighbour(cell_of(i), [&](std::int32_t cell) {
      for (std::int32_t j = head_[cell] - head_offset_; j >= 0; j = next_[j])
        if (j > i) deepest = std::max(deepest, 1.0 - separation(xi, j).norm());
      if constexpr (kRests)
        if (rests_)
          for (auto run = rest_.run(cell); run.begin < run.end; ++run.begin)
            overlap(xi, rest_.position(run.begin));
    });
  }
  if constexpr (kRests) {
    for (std::int32_t r = 0; r < rest_.slots(); ++r) {
      if (rest_.dead(r)) continue;
      grid_.for_each_neighbour(grid_.coords_of(rest_.position(r)), [&](std::int32_t cell) {
        for (auto run = rest_.run(cell); run.begin < run.end; ++run.begin)
          if (run.begin > r) overlap(rest_.position(r), rest_.position(run.begin));
      });
    }
  }
  return deepest;
}

std::unique_ptr<Simulation> load_simulation(const PhysicsConfig& c, StateReader& in) {
  validate(c);
  if (in.identity().dim != c.dim ||
      in.identity().particles != static_cast<std::uint64_t>(c.particles))
    throw UserError("the checkpoint is of a run with other physics than its run.toml");
  switch (c.dim) {
    case 1:
      return std::make_unique<Engine<1>>(c, in);
    case 2:
      return std::make_unique<Engine<2>>(c, in);
    default:
      return std::make_unique<Engine<3>>(c, in);
  }
}

std::unique_ptr<Simulation> make_simulation(const PhysicsConfig& c) {
  validate(c);
  if (c.unbounded()) {  // validate() allows it in 2D and 3D only
    if (c.dim == 2) return std::make_unique<Engine<2>>(c);
    return std::make_unique<Engine<3>>(c);
  }
  switch (c.dim) {
    case 1:
      return std::make_unique<Engine<1>>(c, make_initial_state<1>(c));
    case 2:
      return std::make_unique<Engine<2>>(c, make_initial_state<2>(c));
    default:
      return std::make_unique<Engine<3>>(c, make_initial_state<3>(c));
  }
}

template class Engine<1>;
template class Engine<2>;
template class Engine<3>;

}  // namespace gs
