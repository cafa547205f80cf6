#pragma once
// The periodic cell grid: cubic cells at least one diameter wide, so that spheres that can touch
// sit in the same or adjacent cells (a stencil of 3^d cells).
#include <cmath>
#include <cstdint>

#include "sim/error.h"
#include "sim/vec.h"

namespace gs {

template <int D>
class CellGrid {
 public:
  explicit CellGrid(double box) : box_(box) {
    // The margin keeps cells wider than a diameter even for positions a round-off outside them.
    per_side_ = static_cast<int>(std::floor(box / (1.0 + 1e-9)));
    GS_CHECK(per_side_ >= 1);
    side_ = box / per_side_;
    count_ = 1;
    for (int k = 0; k < D; ++k) count_ *= static_cast<std::size_t>(per_side_);
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
    for (int k = D - 1; k >= 0; --k) i = i * per_side_ + c[k];
    return i;
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
    const int n = per_side_;
    if constexpr (D == 1) {
      for (int a = 0; a < len[0]; ++a) f(list[0][a]);
    } else if constexpr (D == 2) {
      for (int b = 0; b < len[1]; ++b)
        for (int a = 0; a < len[0]; ++a) f(list[1][b] * n + list[0][a]);
    } else {
      for (int z = 0; z < len[2]; ++z)
        for (int b = 0; b < len[1]; ++b) {
          const int row = (list[2][z] * n + list[1][b]) * n;
          for (int a = 0; a < len[0]; ++a) f(row + list[0][a]);
        }
    }
  }

  double box_;
  double side_;
  int per_side_;
  std::size_t count_;
};

}  // namespace gs
