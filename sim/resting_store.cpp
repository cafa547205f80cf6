#include "sim/resting_store.h"

#include <sys/mman.h>
#include <unistd.h>

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
  mark_live_cells();
}

// Runs hold no flags yet: every cell with a slot is flagged kLive.
template <int D>
void RestingStore<D>::mark_live_cells() {
  const std::size_t cells = offset_.size() - 1;
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

namespace {

// Gives the whole pages between v's end and its capacity back to the system (they read as zero
// if ever touched again, and v never grows into them).
template <class T, class A>
void release_tail(std::vector<T, A>& v) {
  const auto page = static_cast<std::uintptr_t>(sysconf(_SC_PAGESIZE));
  const auto end = reinterpret_cast<std::uintptr_t>(v.data() + v.size());
  const auto first = (end + page - 1) / page * page;
  const auto last = reinterpret_cast<std::uintptr_t>(v.data() + v.capacity()) / page * page;
  if (last > first) ::madvise(reinterpret_cast<void*>(first), last - first, MADV_DONTNEED);
}

}  // namespace

template <int D>
typename RestingStore<D>::Renaming RestingStore<D>::compact() {
  const std::size_t n = x_.size();
  Renaming rename;
  rename.live_.assign((n + 63) / 64, 0);
  rename.count_.resize(rename.live_.size());
  std::uint32_t live = 0;
  for (std::size_t w = 0; w < rename.live_.size(); ++w) {
    rename.count_[w] = live;
    for (std::size_t r = 64 * w; r < std::min(n, 64 * w + 64); ++r)
      rename.live_[w] |= std::uint64_t{!dead(static_cast<std::int32_t>(r))} << (r % 64);
    live += static_cast<std::uint32_t>(std::popcount(rename.live_[w]));
  }
  rename.gone_ = static_cast<std::int32_t>(live);
  // Each run starts where the live slots before it end.
  const std::size_t cells = offset_.size() - 1;
  for (std::size_t b = 0; b < base_.size(); ++b) {
    const std::uint32_t old_base = base_[b];
    const auto new_base = static_cast<std::uint32_t>(rename.before(old_base));
    for (std::size_t c = b * kBlock; c < std::min(cells + 1, (b + 1) * kBlock); ++c) {
      const std::uint32_t start = old_base + (offset_[c] & ~kLive);
      offset_[c] = static_cast<std::uint16_t>(rename.before(start) - new_base);
    }
    base_[b] = new_base;
  }
  mark_live_cells();
  std::size_t k = 0;
  for (std::size_t r = 0; r < n; ++r) {
    if (dead(static_cast<std::int32_t>(r))) continue;
    x_[k] = x_[r];
    tag_[k] = tag_[r];
    ++k;
  }
  x_.resize(k + 1);
  tag_.resize(k + 1);
  x_[k] = Vec<D>::Constant(std::numeric_limits<double>::quiet_NaN());  // the dead slot kept
  tag_[k] = 0;
  release_tail(x_);
  release_tail(tag_);
  return rename;
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
void RestingStore<D>::load(StateReader& in, std::int64_t particles) {
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
  for (std::int32_t t : tag_) in.expect(t >= 0 && t < particles);
}

template class RestingStore<2>;
template class RestingStore<3>;

}  // namespace gs
