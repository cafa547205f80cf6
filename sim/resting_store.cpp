#include "sim/resting_store.h"

#include <utility>

#include "sim/error.h"

namespace gs {

template <int D>
RestingStore<D>::RestingStore(VecArray<D>&& x, const CellGrid<D>& grid)
    : box_(true), x_(std::move(x)), resting_(static_cast<std::int64_t>(x_.size())) {
  CellRuns t = sort_into_cells(
      x_, grid.cell_count(), [&](const Vec<D>& p) { return grid.index(grid.coords_of(p)); }, false,
      tag_);
  base_ = std::move(t.base);
  offset_ = std::move(t.offset);
  const std::size_t cells = grid.cell_count();
  for (std::size_t c = 0; c < cells; ++c)
    if (base_[c / kBlock] + offset_[c] < base_[(c + 1) / kBlock] + offset_[c + 1])
      offset_[c] |= kLive;
}

template <int D>
RestingStore<D>::RestingStore(const CellGrid<D>& grid)
    : box_(true),
      base_(grid.cell_count() / kBlock + 1, 0),
      offset_(grid.cell_count() + 1, Touch::Dense) {}

template <int D>
RestingStore<D>::RestingStore(std::size_t cells, std::size_t capacity)
    : box_(false), runs_(cells, Touch::Sparse) {
  x_.reserve(capacity);
}

template <int D>
void RestingStore<D>::append_cell(std::int32_t cell, const VecArray<D>& x) {
  GS_CHECK(!box_ && x.size() < 256 && x_.size() + x.size() <= x_.capacity());
  runs_[cell] = static_cast<std::uint64_t>(x_.size()) << 8 | x.size();
  x_.insert(x_.end(), x.begin(), x.end());  // within the reserved capacity: nothing moves
  resting_ += static_cast<std::int64_t>(x.size());
}

template <int D>
IVec<D> RestingStore<D>::cell_of(std::int32_t r, const CellGrid<D>& grid) const {
  const IVec<D> home = grid.coords_of(x_[r]);
  constexpr int kStep[3] = {0, -1, 1};  // home first
  int combinations = 1;
  for (int k = 0; k < D; ++k) combinations *= 3;
  for (int m = 0; m < combinations; ++m) {
    IVec<D> c = home;
    for (int k = 0, rest = m; k < D; ++k, rest /= 3) c[k] = grid.wrap(home[k] + kStep[rest % 3]);
    if (in_run(r, grid.index(c))) return c;
  }
  GS_CHECK_MSG(false, "a resting particle outside its cell's neighbourhood");
  return home;
}

template <int D>
void RestingStore<D>::leave(std::int32_t r, std::int32_t cell) {
  x_[r][0] = std::numeric_limits<double>::quiet_NaN();
  --resting_;
  const Run s = run(cell);
  for (std::int32_t k = s.begin; k < s.end; ++k)
    if (!dead(k)) return;
  // The cell has no resting particle left: searches skip it.
  if (box_)
    offset_[cell] &= static_cast<std::uint16_t>(~kLive);
  else
    runs_[cell] &= ~std::uint64_t{0xff};
}

template <int D>
void RestingStore<D>::save(StateWriter& out, const std::vector<std::int32_t>& made) const {
  out.vector(x_);
  out.value(resting_);
  if (box_) {
    out.vector(tag_);
    out.vector(base_);
    out.bytes(offset_.data(), offset_.size() * sizeof(std::uint16_t));
  } else {
    std::vector<std::uint64_t> runs(made.size());
    for (std::size_t k = 0; k < made.size(); ++k) runs[k] = runs_[made[k]];
    out.vector(runs);
  }
}

template <int D>
void RestingStore<D>::load(StateReader& in, const std::vector<std::int32_t>& made) {
  in.vector(x_);  // within the reserved capacity of an unbounded store: nothing moves later
  in.value(resting_);
  in.expect(resting_ >= 0 && resting_ <= slots());
  const auto n = static_cast<std::uint64_t>(x_.size());
  if (box_) {
    in.vector(tag_);
    std::vector<std::uint32_t> base;
    in.vector(base);
    in.expect(tag_.size() == n && base.size() == base_.size());
    base_ = std::move(base);
    in.bytes(offset_.data(), offset_.size() * sizeof(std::uint16_t));
    const std::size_t cells = offset_.size() - 1;
    for (std::size_t c = 0; c < cells; ++c) {
      const std::uint64_t begin = base_[c / kBlock] + (offset_[c] & ~kLive),
                          end = base_[(c + 1) / kBlock] + (offset_[c + 1] & ~kLive);
      in.expect(begin <= end && end <= n);
    }
    for (std::int32_t t : tag_) in.expect(t >= 0 && static_cast<std::uint64_t>(t) < n);
  } else {
    std::vector<std::uint64_t> runs;
    in.vector(runs);
    in.expect(runs.size() == made.size());
    for (std::size_t k = 0; k < made.size(); ++k) {
      in.expect((runs[k] >> 8) + (runs[k] & 0xff) <= n);
      runs_[made[k]] = runs[k];
    }
  }
}

template class RestingStore<2>;
template class RestingStore<3>;

}  // namespace gs
