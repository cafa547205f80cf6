#pragma once
// The periodic cell grid: cubic cells at least one diameter wide, so that spheres that can touch
// sit in the same or adjacent cells (a stencil of 3^d cells).
//
// Cells are numbered tile by tile, tiles of 4^d cells in row-major order and row-major within
// (the grid padded to whole tiles): the cells of a ball share pages and lines. Numbered by rows,
// every row through a blast would bring its whole length into memory, and a 3D box's cell
// heads would cost a moving sphere 100 B (sim/bytes_per_particle_3d).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "sim/error.h"
#include "sim/vec.h"

namespace gs {

template <int D>
class CellGrid {
 public:
  // Cells at least `min_side` (at least a diameter) wide.
  explicit CellGrid(double box, double min_side = 1.0) : box_(box) {
    GS_CHECK(min_side >= 1.0);
    // The margin keeps cells wider than a diameter even for positions a round-off outside them.
    per_side_ = static_cast<int>(std::floor(box / (1.0 + 1e-9)));
    GS_CHECK(per_side_ >= 1);
    // Wider cells: as many as fit, and at least the one a box of a diameter or more holds.
    const int wide = static_cast<int>(std::floor(box / (min_side * (1.0 + 1e-9))));
    per_side_ = std::clamp(wide, 1, per_side_);
    side_ = box / per_side_;
    const int tiles = (per_side_ + kTile - 1) / kTile;
    std::int64_t count = 1, tile_cells = 1;
    for (int k = 0; k < D; ++k) count *= tiles * kTile, tile_cells *= kTile;
    GS_CHECK(count <= INT32_MAX);
    count_ = static_cast<std::size_t>(count);
    // A cell's number is the sum of what its coordinate along each axis contributes.
    std::int64_t tile_stride = tile_cells, cell_stride = 1;
    for (int k = 0; k < D; ++k) {
      part_[k].resize(static_cast<std::size_t>(per_side_));
      for (int c = 0; c < per_side_; ++c)
        part_[k][c] = static_cast<std::int32_t>(c / kTile * tile_stride + c % kTile * cell_stride);
      tile_stride *= tiles;
      cell_stride *= kTile;
    }
  }

  double box() const { return box_; }
  double side() const { return side_; }
  int per_side() const { return per_side_; }
  std::size_t cell_count() const { return count_; }

  IVec<D> coords_of(const Vec<D>& x) const {
    IVec<D> c;
    for (int k = 0; k < D; ++k) {
      int ck = static_cast<int>(std::floor(x[k] / side_));
      c[k] = ck < 0 ? 0 : (ck >= per_side_ ? per_side_ - 1 : ck);  // x = L exactly, or -0.0
    }
    return c;
  }

  std::int32_t index(const IVec<D>& c) const {
    std::int32_t i = 0;
    for (int k = 0; k < D; ++k) i += part_[k][c[k]];
    return i;
  }
  // The coordinates of cell number i.
  IVec<D> coords(std::int32_t i) const {
    const int tiles = (per_side_ + kTile - 1) / kTile;
    std::int32_t tile = i, cell = i;
    for (int k = 0; k < D; ++k) tile /= kTile;
    IVec<D> c;
    for (int k = 0; k < D; ++k, tile /= tiles, cell /= kTile)
      c[k] = tile % tiles * kTile + cell % kTile;
    return c;
  }

  // Nearest periodic image of a separation that is less than 1.5 box sides long.
  Vec<D> minimum_image(Vec<D> d) const {
    for (int k = 0; k < D; ++k) d[k] = minimum_image(d[k]);
    return d;
  }
  // The same along one axis, on a plain double: the engine's neighbour search calls it for every
  // component of every neighbour and keeps the separations in registers.
  double minimum_image(double d) const {
    const double half = 0.5 * box_, down = d - box_, up = d + box_;
    return d > half ? down : (d < -half ? up : d);
  }

  // Calls f(cell index) for the 3^d cells around c (fewer, without repeats, on tiny grids).
  template <class F>
  void for_each_neighbour(const IVec<D>& c, F&& f) const {
    int list[D][3], len[D];
    for (int k = 0; k < D; ++k) len[k] = neighbours(c[k], list[k]);
    visit(list, len, f);
  }

  // The same, restricted to the layer of cells whose coordinate along `dim` is `coord`: the
  // cells that become neighbours when a particle steps into a new cell along `dim`.
  template <class F>
  void for_each_in_layer(const IVec<D>& c, int dim, int coord, F&& f) const {
    int list[D][3], len[D];
    for (int k = 0; k < D; ++k) len[k] = neighbours(c[k], list[k]);
    list[dim][0] = coord;
    len[dim] = 1;
    visit(list, len, f);
  }

  int wrap(int c) const { return c < 0 ? c + per_side_ : (c >= per_side_ ? c - per_side_ : c); }

 private:
  int neighbours(int c, int* out) const {
    if (per_side_ >= 3) {
      out[0] = wrap(c - 1);
      out[1] = c;
      out[2] = wrap(c + 1);
      return 3;
    }
    for (int k = 0; k < per_side_; ++k) out[k] = k;
    return per_side_;
  }

  template <class F>
  void visit(int (&list)[D][3], int (&len)[D], F& f) const {
    const auto& x = part_[0];
    if constexpr (D == 1) {
      for (int a = 0; a < len[0]; ++a) f(x[list[0][a]]);
    } else if constexpr (D == 2) {
      for (int b = 0; b < len[1]; ++b) {
        const std::int32_t row = part_[1][list[1][b]];
        for (int a = 0; a < len[0]; ++a) f(row + x[list[0][a]]);
      }
    } else {
      for (int z = 0; z < len[2]; ++z)
        for (int b = 0; b < len[1]; ++b) {
          const std::int32_t row = part_[2][list[2][z]] + part_[1][list[1][b]];
          for (int a = 0; a < len[0]; ++a) f(row + x[list[0][a]]);
        }
    }
  }

  static constexpr int kTile = 4;
  double box_;
  double side_;
  int per_side_;
  std::size_t count_;
  std::vector<std::int32_t> part_[D];
};

}  // namespace gs
