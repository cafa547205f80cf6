#pragma once
// Priority queue of the next event of each moving particle: an indexed 4-ary min-heap with one
// slot per particle, so that rescheduling a particle is a key update in place (no stale entries,
// no growth). Particles at rest are simply absent. The four children of a node share one cache
// line, which halves the misses of a binary heap when the queue outgrows the cache. Storage is
// sized once for all particles; the hot loop never allocates.
#include <algorithm>
#include <cstdint>
#include <new>
#include <vector>

#include "sim/error.h"

namespace gs {

template <class T, std::size_t Align>
struct AlignedAllocator {
  using value_type = T;
  template <class U>
  struct rebind {
    using other = AlignedAllocator<U, Align>;
  };
  AlignedAllocator() = default;
  template <class U>
  AlignedAllocator(const AlignedAllocator<U, Align>&) {}
  T* allocate(std::size_t n) {
    return static_cast<T*>(::operator new (n * sizeof(T), std::align_val_t{Align}));
  }
  void deallocate(T* p, std::size_t) { ::operator delete (p, std::align_val_t{Align}); }
  template <class U>
  bool operator==(const AlignedAllocator<U, Align>&) const {
    return true;
  }
};

class EventQueue {
 public:
  explicit EventQueue(std::size_t n) : where_(n, kAbsent) { storage_.resize(n + kPad); }

  bool empty() const { return size_ == 0; }
  std::size_t size() const { return static_cast<std::size_t>(size_); }
  std::int32_t top() const { return heap(0).id; }
  double top_time() const { return heap(0).time; }
  bool contains(std::int32_t id) const { return where_[id] != kAbsent; }

  // Inserts particle `id` with event time `t`, or moves it to `t` if already present.
  void set(std::int32_t id, double t) {
    std::int32_t k = where_[id];
    if (k == kAbsent) {
      k = size_++;
      heap(k) = {t, id};
      where_[id] = k;
      sift_up(k);
    } else if (t < heap(k).time) {
      heap(k).time = t;
      sift_up(k);
    } else {
      heap(k).time = t;
      sift_down(k);
    }
  }

  void remove(std::int32_t id) {
    const std::int32_t k = where_[id];
    if (k == kAbsent) return;
    where_[id] = kAbsent;
    const Node last = heap(--size_);
    if (k == size_) return;
    heap(k) = last;
    where_[last.id] = k;
    sift_up(k);
    sift_down(where_[last.id]);
  }

 private:
  static constexpr std::int32_t kAbsent = -1;
  struct alignas(16) Node {
    double time;
    std::int32_t id;
  };
  // Node k lives at storage_[k + kPad]: the children 4k+1..4k+4 then start on a multiple of 4,
  // i.e. on a 64-byte boundary.
  static constexpr std::int32_t kPad = 3;

  Node& heap(std::int32_t k) { return storage_[static_cast<std::size_t>(k + kPad)]; }
  const Node& heap(std::int32_t k) const { return storage_[static_cast<std::size_t>(k + kPad)]; }

  void sift_up(std::int32_t k) {
    const Node x = heap(k);
    while (k > 0) {
      const std::int32_t p = (k - 1) / 4;
      if (!(x.time < heap(p).time)) break;
      heap(k) = heap(p);
      where_[heap(k).id] = k;
      k = p;
    }
    heap(k) = x;
    where_[x.id] = k;
  }

  void sift_down(std::int32_t k) {
    const Node x = heap(k);
    for (;;) {
      const std::int32_t first = 4 * k + 1;
      if (first >= size_) break;
      const std::int32_t last = std::min(first + 4, size_);
      std::int32_t c = first;
      for (std::int32_t m = first + 1; m < last; ++m)
        if (heap(m).time < heap(c).time) c = m;
      if (!(heap(c).time < x.time)) break;
      heap(k) = heap(c);
      where_[heap(k).id] = k;
      k = c;
    }
    heap(k) = x;
    where_[x.id] = k;
  }

  std::vector<Node, AlignedAllocator<Node, 64>> storage_;
  std::int32_t size_ = 0;
  std::vector<std::int32_t> where_;  // heap slot of each particle, or kAbsent
};

}  // namespace gs
