#include "sim/resting_store.h"

#include <utility>

#include "sim/error.h"

namespace gs {

template <int D>
RestingStore<D>::RestingStore(VecArray<D>&& x, const CellGrid<D>& grid)
    : x_(std::move(x)), resting_(static_cast<std::int64_t>(x_.size())) {
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
    : base_(grid.cell_count() / kBlock + 1, 0), offset_(grid.cell_count() + 1, Touch::Dense) {}

template <int D>
void RestingStore<D>::leave(std::int32_t r, std::int32_t cell) {
  x_[r][0] = std::numeric_limits<double>::quiet_NaN();
  --resting_;
  const Run s = run(cell);
  for (std::int32_t k = s.begin; k < s.end; ++k)
    if (!dead(k)) return;
  offset_[cell] &= static_cast<std::uint16_t>(~kLive);  // none left: searches skip the cell
}

template <int D>
void RestingStore<D>::save(StateWriter& out) const {
  out.vector(x_);
  out.value(resting_);
  out.vector(tag_);
  out.vector(base_);
  out.bytes(offset_.data(), offset_.size() * sizeof(std::uint16_t));
}

template <int D>
void RestingStore<D>::load(StateReader& in) {
  in.vector(x_);
  in.value(resting_);
  const auto n = static_cast<std::uint64_t>(x_.size());
  in.expect(resting_ >= 0 && static_cast<std::uint64_t>(resting_) <= n);
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
}

template class RestingStore<2>;
template class RestingStore<3>;

}  // namespace gs
