#pragma once
// Priority queue of the next event of each moving particle: an indexed binary min-heap with one
// slot per particle, so that rescheduling a particle is a key update in place (no stale entries,
// no growth). Particles at rest are simply absent. Storage is sized once for all particles; the
// hot loop never allocates.
#include <cstdint>
#include <vector>

#include "sim/error.h"

namespace gs {

class EventQueue {
 public:
  explicit EventQueue(std::size_t n) : where_(n, kAbsent) { heap_.reserve(n); }

  bool empty() const { return heap_.empty(); }
  std::size_t size() const { return heap_.size(); }
  std::int32_t top() const { return heap_.front().id; }
  double top_time() const { return heap_.front().time; }
  bool contains(std::int32_t id) const { return where_[id] != kAbsent; }

  // Inserts particle `id` with event time `t`, or moves it to `t` if already present.
  void set(std::int32_t id, double t) {
    std::int32_t k = where_[id];
    if (k == kAbsent) {
      k = static_cast<std::int32_t>(heap_.size());
      heap_.push_back({t, id});
      where_[id] = k;
      sift_up(k);
    } else if (t < heap_[k].time) {
      heap_[k].time = t;
      sift_up(k);
    } else {
      heap_[k].time = t;
      sift_down(k);
    }
  }

  void remove(std::int32_t id) {
    const std::int32_t k = where_[id];
    if (k == kAbsent) return;
    where_[id] = kAbsent;
    const Node last = heap_.back();
    heap_.pop_back();
    if (k == static_cast<std::int32_t>(heap_.size())) return;
    heap_[k] = last;
    where_[last.id] = k;
    sift_up(k);
    sift_down(where_[last.id]);
  }

 private:
  static constexpr std::int32_t kAbsent = -1;
  struct Node {
    double time;
    std::int32_t id;
  };

  void sift_up(std::int32_t k) {
    const Node x = heap_[k];
    while (k > 0) {
      const std::int32_t p = (k - 1) / 2;
      if (!(x.time < heap_[p].time)) break;
      heap_[k] = heap_[p];
      where_[heap_[k].id] = k;
      k = p;
    }
    heap_[k] = x;
    where_[x.id] = k;
  }

  void sift_down(std::int32_t k) {
    const std::int32_t n = static_cast<std::int32_t>(heap_.size());
    const Node x = heap_[k];
    for (;;) {
      std::int32_t c = 2 * k + 1;
      if (c >= n) break;
      if (c + 1 < n && heap_[c + 1].time < heap_[c].time) ++c;
      if (!(heap_[c].time < x.time)) break;
      heap_[k] = heap_[c];
      where_[heap_[k].id] = k;
      k = c;
    }
    heap_[k] = x;
    where_[x.id] = k;
  }

  std::vector<Node> heap_;
  std::vector<std::int32_t> where_;  // heap slot of each particle, or kAbsent
};

}  // namespace gs
