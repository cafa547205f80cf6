#pragma once
// The particles of a kick that nothing has hit yet: a position each, kept cell by cell so that a
// neighbour search reads a cell's resting particles as one run of memory. A
// resting sphere costs its position, its tag and its cell's share of the run table: 36 B in 3D
// at n = 0.25, where it cost 161 B as an engine record (sim/bytes_per_particle_3d).
//
// A particle leaves the store when something first collides with it (Engine::promote) and its
// slot is left dead: a NaN first coordinate, which makes every contact test with it false
// without a branch (sim/collision.h will_touch) and tells a prediction made while it rested that
// it has been hit since. The engine compacts the store as records accumulate (compact()), so that
// a moving particle does not go on paying for the slot it left.
//
// The particles are sorted by cell in cell order (sim/cell_grid.h): a cell's run starts at its
// block's base (one per 64 cells) plus a 15-bit offset, and ends where the next cell's starts,
// so a cell costs 2 bytes (n = 0.25 puts 4 cells on each particle: a 4-byte start per cell alone
// would be 16 B a particle). A cell whose particles have all left loses its kLive flag and reads
// as empty, so that searches inside a blast skip it. Only a box's kicks keep a store: the
// unbounded medium makes its particles just ahead of the front, where they are about to be hit,
// and makes them records at once (sim/engine.h).
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "sim/cell_grid.h"
#include "sim/error.h"
#include "sim/state_stream.h"
#include "sim/vec.h"
#include "sim/zero_pages.h"

namespace gs {

// Where each cell's points lie once sorted by cell number: cell c's run starts at
// base[c / kBlock] + offset[c] and ends where cell c + 1's starts (offset has one entry past the
// last cell, whose start is the total).
struct CellRuns {
  static constexpr std::size_t kBlock = 64;
  std::vector<std::uint32_t> base;
  ZeroPages<std::uint16_t> offset;  // under 0x8000: the store keeps a flag in the 16th bit
};

// Sorts `x` in place by the number cell_of(point) in [0, cells) each point has; within a cell the
// points keep their order, or reverse it if `latest_first`. order[k] is the former index of the
// point now at k. Nothing but `order` (4 B a point, its storage reused) and the table (2 B a
// cell) is added to the points: the start of a 2e7-sphere box peaks at what its resting store
// keeps. A counting sort: the offsets count first and then serve as each cell's cursor, `order`
// is filled from them, and the points follow `order` cycle by cycle (an entry's sign bit marks a
// place done).
template <int D, class CellOf>
CellRuns sort_into_cells(VecArray<D>& x, std::size_t cells, CellOf&& cell_of, bool latest_first,
                         std::vector<std::int32_t>& order) {
  constexpr std::size_t kBlock = CellRuns::kBlock;
  const std::size_t n = x.size();
  GS_CHECK(n < static_cast<std::size_t>(INT32_MAX));
  CellRuns t;
  t.base.assign(cells / kBlock + 1, 0);
  t.offset = ZeroPages<std::uint16_t>(cells + 1, Touch::Dense);
  const auto cell_at = [&](std::size_t j) { return static_cast<std::size_t>(cell_of(x[j])); };
  std::vector<std::uint32_t> block_count(t.base.size(), 0);
  for (std::size_t j = 0; j < n; ++j) {
    const std::size_t c = cell_at(j);
    ++t.offset[c];
    ++block_count[c / kBlock];
  }
  std::uint32_t total = 0;
  for (std::size_t b = 0; b < t.base.size(); ++b) {
    t.base[b] = total;
    total += block_count[b];
  }
  block_count = std::vector<std::uint32_t>();
  // Counts to ends within each block. A block's points fit in 15 bits by far: 64 cells of side
  // under 1.5 hold a few hundred unit spheres at close packing.
  for (std::size_t c = 0; c <= cells; ++c) {
    const std::uint32_t count = c < cells ? t.offset[c] : 0;
    const std::uint32_t start = c % kBlock == 0 ? 0 : t.offset[c - 1];
    GS_CHECK(start + count < 0x8000);
    t.offset[c] = static_cast<std::uint16_t>(start + count);
  }
  // Ends step back to starts as the cells fill from their last place: the points taken first
  // come last in their cell.
  order.assign(n, 0);
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t j = latest_first ? k : n - 1 - k;
    const std::size_t c = cell_at(j);
    t.offset[c] = static_cast<std::uint16_t>(t.offset[c] - 1);
    order[t.base[c / kBlock] + t.offset[c]] = static_cast<std::int32_t>(j);
  }
  for (std::size_t k = 0; k < n; ++k) {
    if (order[k] < 0) continue;
    const Vec<D> first = x[k];
    std::size_t at = k;
    for (;;) {
      const auto from = static_cast<std::size_t>(order[at]);
      order[at] = ~order[at];
      if (from == k) {
        x[at] = first;
        break;
      }
      x[at] = x[from];
      at = from;
    }
  }
  for (auto& j : order) j = ~j;
  return t;
}

// In 2D and 3D boxes; the 1D engine keeps every particle a record.
template <int D>
class RestingStore {
 public:
  struct Run {
    std::int32_t begin = 0, end = 0;
  };

  RestingStore() = default;
  // The particles at `x` (their tags are their indices there), sorted here by the cells of
  // `grid`; the order within a cell is the tags'.
  RestingStore(VecArray<D>&& x, const CellGrid<D>& grid);
  // An empty store of `grid`, for load().
  explicit RestingStore(const CellGrid<D>& grid);

  // The slots of a cell's particles (the cell of grid.coords_of(position)), empty once they
  // have all left; a dead slot within is possible.
  Run run(std::int32_t cell) const {
    // Without a branch: whether a cell still holds a resting particle is a coin toss.
    const std::uint16_t here = offset_[cell];
    const std::size_t next = static_cast<std::size_t>(cell) + 1;
    const auto begin = static_cast<std::int32_t>(base_[cell / kBlock] + (here & ~kLive));
    const auto end = static_cast<std::int32_t>(base_[next / kBlock] + (offset_[next] & ~kLive));
    return {begin, (here & kLive) ? end : begin};
  }

  const Vec<D>& position(std::int32_t r) const { return x_[r]; }
  const Vec<D>* positions() const { return x_.data(); }
  bool dead(std::int32_t r) const { return std::isnan(x_[r][0]); }
  std::int32_t tag(std::int32_t r) const { return tag_[r]; }
  std::int32_t slots() const { return static_cast<std::int32_t>(x_.size()); }
  std::int64_t resting() const { return resting_; }

  // Marks slot r (in `cell`) dead: its particle has left.
  void leave(std::int32_t r, std::int32_t cell);

  // A slot's number after compact(): a live slot's place among the live ones, which keep their
  // order; a dead slot's, the one dead slot kept at the end, so that a prediction made while its
  // particle rested still finds it gone.
  class Renaming {
   public:
    std::int32_t operator()(std::int32_t old) const {
      const auto r = static_cast<std::size_t>(old);
      return (live_[r / 64] >> (r % 64)) & 1 ? before(r) : gone_;
    }

   private:
    friend class RestingStore;
    std::int32_t before(std::size_t r) const {  // live slots below r
      if (r / 64 == live_.size()) return gone_;
      const std::uint64_t below = live_[r / 64] & ((std::uint64_t{1} << (r % 64)) - 1);
      return static_cast<std::int32_t>(count_[r / 64] + std::popcount(below));
    }
    std::vector<std::uint64_t> live_;   // a bit a slot
    std::vector<std::uint32_t> count_;  // live slots before each word
    std::int32_t gone_ = 0;
  };
  // Drops the dead slots and gives their memory back to the system: the 28 B (3D) a record's
  // slot held.
  Renaming compact();

  void save(StateWriter& out) const;
  // Into a store made for the same grid, of a state of `particles` (tags below it).
  void load(StateReader& in, std::int64_t particles);

 private:
  static constexpr std::size_t kBlock = CellRuns::kBlock;
  static constexpr std::uint16_t kLive = 0x8000;  // the cell still holds a resting particle
  void mark_live_cells();

  VecArray<D> x_;
  std::int64_t resting_ = 0;
  // Each slot's tag; each cell's start as the base of its block of kBlock cells plus its offset
  // (with kLive), for the cells and one past the last, whose start is the total.
  std::vector<std::int32_t> tag_;
  std::vector<std::uint32_t> base_;
  ZeroPages<std::uint16_t> offset_;
};

}  // namespace gs
