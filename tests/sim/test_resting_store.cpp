#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <vector>

#include "sim/cell_grid.h"
#include "sim/engine.h"
#include "sim/initial.h"
#include "sim/resting_store.h"
#include "sim/rng.h"
#include "tests/sim/same_history.h"

namespace gs {
namespace {

template <int D>
VecArray<D> random_points(int n, double box, std::uint64_t seed) {
  Rng rng(seed, 0, Stream::Positions);
  VecArray<D> x(static_cast<std::size_t>(n));
  for (auto& p : x)
    for (int k = 0; k < D; ++k) p[k] = rng.uniform() * box;
  return x;
}

// Every number of a grid's cells is used once, within cell_count(), and read back by coords().
template <int D>
void expect_numbering_is_a_bijection(double box) {
  const CellGrid<D> grid(box);
  std::vector<int> seen(grid.cell_count(), 0);
  const int n = grid.per_side();
  IVec<D> c = IVec<D>::Zero();
  for (;;) {
    const std::int32_t i = grid.index(c);
    ASSERT_GE(i, 0);
    ASSERT_LT(static_cast<std::size_t>(i), grid.cell_count());
    ++seen[i];
    EXPECT_EQ(grid.coords(i), c);
    int k = 0;
    for (; k < D; ++k) {
      if (++c[k] < n) break;
      c[k] = 0;
    }
    if (k == D) break;
  }
  EXPECT_EQ(*std::max_element(seen.begin(), seen.end()), 1);
  std::size_t used = 0;
  for (int s : seen) used += s;
  EXPECT_EQ(used, static_cast<std::size_t>(std::pow(n, D)));
}

TEST(CellGrid, TiledNumberingIsABijection) {
  expect_numbering_is_a_bijection<2>(37.5);  // 37 cells a side: padded to 40
  expect_numbering_is_a_bijection<3>(13.2);  // 13: padded to 16
  expect_numbering_is_a_bijection<3>(8.0);   // whole tiles
  expect_numbering_is_a_bijection<1>(10.5);
}

// A ball of cells spans few pages of cell heads: numbered by rows, each row through it would
// bring a page of its own (why the grid is tiled).
TEST(CellGrid, ABallOfCellsTouchesFewerPagesThanRowsWould) {
  const CellGrid<3> grid(256.5);
  const int r = 20, mid = 128, n = grid.per_side();
  std::set<std::int64_t> tiled, rows;  // 4 KiB pages of 4-byte heads: 1024 cell numbers
  for (int z = -r; z <= r; ++z)
    for (int y = -r; y <= r; ++y)
      for (int x = -r; x <= r; ++x) {
        if (x * x + y * y + z * z > r * r) continue;
        const IVec<3> c(mid + x, mid + y, mid + z);
        tiled.insert(grid.index(c) / 1024);
        rows.insert((static_cast<std::int64_t>(c[2] * n + c[1]) * n + c[0]) / 1024);
      }
  // Rows: about 450 pages; tiles: about 200 (a page holds a row of 16 tiles, of which the ball
  // takes 11).
  EXPECT_LT(static_cast<double>(tiled.size()), 0.6 * static_cast<double>(rows.size()))
      << tiled.size() << " pages against " << rows.size();
}

TEST(SortIntoCells, PutsEachCellsPointsInOneRunInTheAskedOrder) {
  const CellGrid<3> grid(11.3);
  for (bool latest_first : {false, true}) {
    const VecArray<3> before = random_points<3>(2000, grid.box(), 7);
    VecArray<3> x = before;
    std::vector<std::int32_t> order;
    const auto number = [&](const Vec<3>& p) { return grid.index(grid.coords_of(p)); };
    const CellRuns t = sort_into_cells(x, grid.cell_count(), number, latest_first, order);
    ASSERT_EQ(order.size(), before.size());
    std::vector<int> taken(before.size(), 0);
    for (std::size_t k = 0; k < x.size(); ++k) {
      ++taken[order[k]];
      EXPECT_EQ(x[k], before[order[k]]);  // the points moved with their order
    }
    EXPECT_EQ(*std::min_element(taken.begin(), taken.end()), 1);
    EXPECT_EQ(*std::max_element(taken.begin(), taken.end()), 1);
    std::size_t covered = 0;
    for (std::size_t c = 0; c < grid.cell_count(); ++c) {
      const std::uint32_t begin = t.base[c / CellRuns::kBlock] + t.offset[c],
                          end = t.base[(c + 1) / CellRuns::kBlock] + t.offset[c + 1];
      ASSERT_LE(begin, end);
      ASSERT_EQ(begin, covered);  // runs follow each other in cell order
      covered = end;
      for (std::uint32_t k = begin; k < end; ++k) {
        EXPECT_EQ(static_cast<std::size_t>(number(x[k])), c);
        if (k > begin) {
          EXPECT_EQ(order[k] < order[k - 1], latest_first);
        }
      }
    }
    EXPECT_EQ(covered, x.size());
  }
}

TEST(RestingStore, ABoxStoreHoldsEveryParticleInItsCellsRunUntilItLeaves) {
  const CellGrid<2> grid(40.7);
  const VecArray<2> given = random_points<2>(400, grid.box(), 3);
  RestingStore<2> store(VecArray<2>(given), grid);
  ASSERT_EQ(store.slots(), 400);
  std::vector<int> seen(given.size(), 0);
  for (std::int32_t r = 0; r < store.slots(); ++r) {
    EXPECT_EQ(store.position(r), given[store.tag(r)]);
    ++seen[store.tag(r)];
    const auto run = store.run(grid.index(grid.coords_of(store.position(r))));
    EXPECT_TRUE(run.begin <= r && r < run.end);
  }
  EXPECT_EQ(*std::max_element(seen.begin(), seen.end()), 1);

  // A cell whose particles all leave is empty to searches.
  std::int32_t cell = -1;
  for (std::int32_t c = 0; c < static_cast<std::int32_t>(grid.cell_count()) && cell < 0; ++c)
    if (store.run(c).end - store.run(c).begin >= 2) cell = c;
  ASSERT_GE(cell, 0);
  const auto run = store.run(cell);
  store.leave(run.begin, cell);
  EXPECT_TRUE(store.dead(run.begin));
  EXPECT_EQ(store.run(cell).begin, run.begin);  // others still rest there
  for (std::int32_t r = run.begin + 1; r < run.end; ++r) store.leave(r, cell);
  EXPECT_EQ(store.run(cell).begin, store.run(cell).end);
  EXPECT_EQ(store.resting(), 400 - (run.end - run.begin));
}

// Compaction drops the dead slots and keeps the live ones in their cells' runs, in their order,
// and renames a dead slot to one that reads as dead.
TEST(RestingStore, CompactionKeepsTheLiveSlotsInTheirRunsAndOrder) {
  const CellGrid<3> grid(20.3);
  RestingStore<3> store(random_points<3>(2000, grid.box(), 5), grid);
  const auto cell_of = [&](std::int32_t r) {
    return grid.index(grid.coords_of(store.position(r)));
  };
  Rng rng(9, 0, Stream::Positions);
  std::vector<std::int32_t> live_tags;
  std::vector<bool> left(2000, false);
  for (std::int32_t r = 0; r < store.slots(); ++r) {
    if (rng.uniform() < 0.6) {
      left[r] = true;
      store.leave(r, cell_of(r));
    } else {
      live_tags.push_back(store.tag(r));
    }
  }
  std::vector<Vec<3>> old_position(2000);
  for (std::int32_t r = 0; r < 2000; ++r) old_position[r] = store.position(r);
  const auto rename = store.compact();
  ASSERT_EQ(store.resting(), static_cast<std::int64_t>(live_tags.size()));
  ASSERT_EQ(store.slots(), store.resting() + 1);  // and the dead slot kept
  for (std::int32_t r = 0; r < store.resting(); ++r) {
    EXPECT_EQ(store.tag(r), live_tags[r]);  // in their order
    const auto run = store.run(cell_of(r));
    EXPECT_TRUE(run.begin <= r && r < run.end);
  }
  std::int32_t in_runs = 0;
  for (std::int32_t c = 0; c < static_cast<std::int32_t>(grid.cell_count()); ++c)
    in_runs += store.run(c).end - store.run(c).begin;
  EXPECT_EQ(in_runs, store.resting());
  for (std::int32_t r = 0; r < 2000; ++r) {
    if (left[r]) {
      EXPECT_TRUE(store.dead(rename(r)));
    } else {
      EXPECT_FALSE(store.dead(rename(r)));
      EXPECT_EQ(store.position(rename(r)), old_position[r]);
    }
  }
}

// The resting store changes where a kick's particles live, not what they do: the same state
// started with every particle an engine record (as a thermal start is) gives the same history
// to the bit, event by event, with every position and every count.
template <int D>
void expect_same_history_with_and_without_store(int events) {
  PhysicsConfig c;
  c.dim = D;
  c.particles = 20000;
  c.restitution = 0.8;
  InitialState<D> kick = make_initial_state<D>(c);
  ASSERT_TRUE(kick.velocity.empty());
  InitialState<D> records = kick;
  records.velocity.resize(records.position.size());
  for (std::size_t i = 0; i < records.position.size(); ++i)
    records.velocity[i] = kick.velocity_of(i);
  Engine<D> stored(c, std::move(kick)), plain(c, std::move(records));
  test::expect_same_history(stored, plain, events);
  EXPECT_GT(stored.stats().collisions, 5000);
  // Past the first compaction of the store (at 1024 dead slots, Engine::kCompactAt).
  EXPECT_GT(stored.sample().active, 1100);
  EXPECT_EQ(stored.max_overlap_now(), plain.max_overlap_now());
}

TEST(RestingStore, AKickHasTheHistoryOfTheSameStateHeldAsRecords2D) {
  expect_same_history_with_and_without_store<2>(20000);
}
TEST(RestingStore, AKickHasTheHistoryOfTheSameStateHeldAsRecords3D) {
  expect_same_history_with_and_without_store<3>(20000);
}

}  // namespace
}  // namespace gs
