#pragma once
// Priority queue of the next event of each moving particle: a calendar queue (R. Brown, Commun.
// ACM 31, 1220 (1988); for event-driven MD, G. Paul, J. Comput. Phys. 221, 615 (2007)) with one
// entry per particle, so that rescheduling is an unlink and a link (no stale entries, no
// growth). Particles at rest are simply absent.
//
// Time is cut into buckets of width w; a "year" of nb consecutive buckets holds the events due
// in it, one doubly linked list per bucket, and later events wait in an overflow list that is
// sorted into the next year when this one is used up. Finding the earliest event walks to the
// first non-empty bucket and scans its short list. The cost is O(1) per event while a bucket
// holds a few events, so w follows the spacing of the earliest events (a kicked gas goes from
// one event per unit time to hundreds of thousands and back as the band slows) and nb follows
// the number of events: the occupancy near the front of the calendar is checked every ~size/4
// events, and the calendar is rebuilt when it is off. All storage is sized once for all
// particles (in the unbounded medium: reserved for the most it may make, and grown into as
// particles are made); the hot loop never allocates.
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <vector>

#include "sim/error.h"
#include "sim/huge_pages.h"
#include "sim/state_stream.h"

namespace gs {

class EventQueue {
 public:
  // Entries for particles 0 .. n-1, room (address space, not memory) for `capacity`.
  explicit EventQueue(std::size_t n, std::size_t capacity = 0) : capacity_(std::max(n, capacity)) {
    entry_.reserve(capacity_);
    entry_.resize(n);
    all_.reserve(capacity_);
    head_.reserve(std::bit_ceil(std::max(2 * capacity_, kMinBuckets)));
    rebuild(kMinBuckets);
  }

  // Entries for particles 0 .. n-1 (n up to the capacity): the unbounded medium's new particles.
  void grow(std::size_t n) {
    GS_CHECK(n <= capacity_);
    entry_.resize(n);
  }
  std::size_t particles() const { return entry_.size(); }

  bool empty() const { return size_ == 0; }
  std::size_t size() const { return size_; }
  bool contains(std::int32_t id) const { return entry_[id].prev != kAbsent; }

  // The particle with the earliest event (ties in no particular but a reproducible order).
  // The queue must not be empty.
  std::int32_t top() {
    find_top();
    return top_;
  }
  double top_time() {
    find_top();
    return entry_[top_].time;
  }

  // Inserts particle `id` with event time `t`, or moves it to `t` if already present.
  void set(std::int32_t id, double t) {
    if (contains(id))
      unlink(id);
    else
      ++size_;
    entry_[id].time = t;
    floor_ = std::min(floor_, t);
    link(id);
    if (top_ == id) {
      if (t > top_known_time_)
        top_ = kNone;  // it may have fallen behind another
      else
        top_known_time_ = t;
    } else if (top_ != kNone && t < top_known_time_) {
      top_ = id;
      top_known_time_ = t;
    }
  }

  // After top(): up to `count` (at most kMaxPeek) particles whose events follow the top's, so
  // that a caller can start loading their data while it handles the top. The top's bucket has
  // just been scanned, so its entries are taken in time order (the list is in no order); later
  // buckets, up to kPeekBuckets on, give only their first entry, whose line is requested, not
  // waited for. A pair that predicted each other has two entries due at the same instant (to
  // round-off), and handling the first reschedules the second: so an entry due with the one
  // before it is left out.
  static constexpr int kMaxPeek = 4;
  struct Soon {
    int count = 0;
    std::int32_t id[kMaxPeek];
  };
  Soon peek_soon(int count) const {
    count = std::min(count, kMaxPeek);
    std::int32_t id[kMaxPeek];
    double time[kMaxPeek];
    int n = 0, seen = 0;
    for (std::int32_t j = head_[static_cast<std::size_t>(cur_) & mask_];
         j != kNone && seen < kLongList; j = entry_[j].next, ++seen) {
      if (j == top_) continue;
      // Insertion into the sorted list of the earliest so far; when it is full, the last goes.
      const double t = entry_[j].time;
      if (n == kMaxPeek && t >= time[kMaxPeek - 1]) continue;
      int m = n < kMaxPeek ? n++ : kMaxPeek - 1;
      for (; m > 0 && time[m - 1] > t; --m) {
        time[m] = time[m - 1];
        id[m] = id[m - 1];
      }
      time[m] = t;
      id[m] = j;
    }
    Soon soon;
    double last = top_known_time_;
    for (int m = 0; m < n && soon.count < count; ++m) {
      if (time[m] - last <= 1e-12 * std::abs(time[m])) continue;
      soon.id[soon.count++] = id[m];
      last = time[m];
    }
    for (std::int64_t b = cur_ + 1; b < year_end_ && b <= cur_ + kPeekBuckets && soon.count < count;
         ++b)
      if (const std::int32_t h = head_[static_cast<std::size_t>(b) & mask_]; h != kNone) {
        __builtin_prefetch(&entry_[h]);
        soon.id[soon.count++] = h;
      }
    return soon;
  }

  // Starts loading what set(id) or remove(id) will touch: the entry first, and once it has
  // arrived, its neighbours in its bucket.
  void prefetch(std::int32_t id) const { __builtin_prefetch(&entry_[id]); }
  void prefetch_neighbours(std::int32_t id) const {
    const Entry& e = entry_[id];
    if (e.next != kNone) __builtin_prefetch(&entry_[e.next]);
    if (e.prev != kNone) __builtin_prefetch(&entry_[e.prev]);
  }

  // Starts loading the head of the bucket that an event at time t will join.
  void prefetch_bucket(double t) const {
    const std::int64_t b = bucket_of(t);
    if (b < year_end_) __builtin_prefetch(&head_[static_cast<std::size_t>(b) & mask_]);
  }

  // Every member, so that a loaded queue breaks ties and rebuilds its calendar exactly as the
  // saved one would have.
  void save(StateWriter& out) const {
    out.vector(entry_);
    out.vector(head_);
    out.value(overflow_);
    out.value(mask_);
    out.value(width_);
    out.value(inv_width_);
    out.value(cur_);
    out.value(year_end_);
    out.value(size_);
    out.value(calendar_count_);
    out.value(overflow_count_);
    out.value(top_);
    out.value(top_known_time_);
    out.value(floor_);
    out.value(finds_);
    out.value(next_check_);
  }
  void load(StateReader& in) {
    in.vector(entry_);  // within the reserved capacity when the engine's checks pass
    in.vector(head_);
    in.expect(entry_.size() <= capacity_ && std::has_single_bit(head_.size()));
    head_.reserve(std::bit_ceil(std::max(2 * capacity_, kMinBuckets)));  // as the constructor
    in.value(overflow_);
    in.value(mask_);
    in.value(width_);
    in.value(inv_width_);
    in.value(cur_);
    in.value(year_end_);
    in.value(size_);
    in.value(calendar_count_);
    in.value(overflow_count_);
    in.value(top_);
    in.value(top_known_time_);
    in.value(floor_);
    in.value(finds_);
    in.value(next_check_);
    in.expect(mask_ + 1 == head_.size() && size_ <= entry_.size() &&
              calendar_count_ + overflow_count_ == size_);
  }

  void remove(std::int32_t id) {
    if (!contains(id)) return;
    unlink(id);
    --size_;
    if (top_ == id) top_ = kNone;
  }

 private:
  static constexpr std::int32_t kNone = -1, kAbsent = -2;  // kAbsent: prev of an entry not queued
  static constexpr std::int64_t kOverflow = -2;            // bucket of the entries beyond this year
  static constexpr std::size_t kMinBuckets = 64;
  static constexpr int kLongList = 64;  // entries: a bucket this full, or a sample this large
  static constexpr int kPeekBuckets = 16;

  // 16 bytes, four to a cache line: the entries are read at random. An entry's bucket is not
  // stored but recomputed from its time (bucket()), which gives the bucket it was linked into.
  struct Entry {
    double time = 0;
    std::int32_t next = kNone, prev = kAbsent;
  };
  static_assert(sizeof(Entry) == 16);

  std::int64_t bucket_of(double t) const {
    // Events are never due before the bucket being walked (times only move forward), except in
    // direct use of the queue; those join the current bucket, where the scan still finds them.
    const double b = std::floor(t * inv_width_);
    return std::max(cur_, b < 9e18 ? static_cast<std::int64_t>(b) : year_end_);
  }
  // The bucket that holds a queued entry due at t: that of bucket_of() when it was linked, since
  // the walk never passes a non-empty bucket (so an entry clamped to the bucket then walked is
  // still in the one walked now) and width and year change only when every entry is relinked.
  std::int64_t bucket(double t) const {
    const std::int64_t b = bucket_of(t);
    return b < year_end_ ? b : kOverflow;
  }
  std::int32_t& head_of(std::int64_t bucket) {
    return bucket == kOverflow ? overflow_ : head_[static_cast<std::size_t>(bucket) & mask_];
  }

  void link(std::int32_t id) {
    Entry& e = entry_[id];
    const std::int64_t b = bucket(e.time);
    (b == kOverflow ? overflow_count_ : calendar_count_)++;
    std::int32_t& head = head_of(b);
    e.prev = kNone;
    e.next = head;
    if (head != kNone) entry_[head].prev = id;
    head = id;
  }

  void unlink(std::int32_t id) {
    Entry& e = entry_[id];
    const std::int64_t b = bucket(e.time);
    (b == kOverflow ? overflow_count_ : calendar_count_)--;
    if (e.prev != kNone)
      entry_[e.prev].next = e.next;
    else
      head_of(b) = e.next;
    if (e.next != kNone) entry_[e.next].prev = e.prev;
    e.prev = kAbsent;
  }

  void find_top() {
    if (top_ != kNone) return;
    GS_CHECK_MSG(size_ > 0, "top of an empty event queue");
    if (++finds_ >= next_check_) check();
    while (calendar_count_ == 0) next_year();
    while (head_[static_cast<std::size_t>(cur_) & mask_] == kNone) ++cur_;
    // The first entry due at the floor is the earliest (the same one a full scan would pick):
    // a lattice start can put a whole bucket's worth of events at one instant.
    std::int32_t best = head_[static_cast<std::size_t>(cur_) & mask_];
    int scanned = 1;
    for (std::int32_t j = entry_[best].next; j != kNone && entry_[best].time > floor_;
         j = entry_[j].next, ++scanned)
      if (entry_[j].time < entry_[best].time) best = j;
    top_ = best;
    top_known_time_ = floor_ = entry_[best].time;
    if (scanned > kLongList) next_check_ = std::min(next_check_, finds_ + kLongList);
  }

  // This year's buckets are all empty: start the next year at the earliest waiting event and
  // sort into it what falls due in it.
  void next_year() {
    double earliest = INFINITY;
    for (std::int32_t j = overflow_; j != kNone; j = entry_[j].next)
      earliest = std::min(earliest, entry_[j].time);
    cur_ = std::max(cur_, static_cast<std::int64_t>(std::floor(earliest * inv_width_)));
    year_end_ = cur_ + static_cast<std::int64_t>(mask_ + 1);
    std::int32_t j = overflow_;
    overflow_ = kNone;
    overflow_count_ = 0;
    while (j != kNone) {
      const std::int32_t next = entry_[j].next;
      link(j);
      j = next;
    }
  }

  // Rebuilds the calendar when the number of buckets no longer suits the number of events, when
  // most events wait beyond this year, or when the buckets about to be walked hold far more or
  // far fewer than a few events each.
  void check() {
    next_check_ = finds_ + std::max<std::size_t>(size_ / 4, 64);
    const std::size_t buckets = std::bit_ceil(std::max(2 * size_, kMinBuckets));
    bool rebuild_now = buckets > 2 * (mask_ + 1) || 4 * buckets < mask_ + 1 ||
                       4 * calendar_count_ < overflow_count_;
    if (!rebuild_now && calendar_count_ > 0) {
      std::size_t seen = 0;
      std::int64_t b = cur_;
      for (; b < year_end_ && seen < kLongList; ++b)
        for (std::int32_t j = head_[static_cast<std::size_t>(b) & mask_]; j != kNone;
             j = entry_[j].next)
          ++seen;
      const double per_bucket = static_cast<double>(seen) / static_cast<double>(b - cur_);
      rebuild_now = per_bucket > 8 || per_bucket < 0.25;
    }
    if (rebuild_now) rebuild(buckets);
  }

  // Sorts every entry into a new calendar of `buckets` buckets whose width puts about one of
  // the earliest events in each; a width that cannot be measured (ties) is kept.
  void rebuild(std::size_t buckets) {
    all_.clear();
    for (std::int32_t h : head_)
      for (std::int32_t j = h; j != kNone; j = entry_[j].next) all_.push_back(j);
    for (std::int32_t j = overflow_; j != kNone; j = entry_[j].next) all_.push_back(j);
    double earliest = 0;
    if (!all_.empty()) {
      // The links are free until the relinking: each entry's next holds its place in all_, so
      // that all_ can be selected on by time (no copy of the times, 8 B an event) and then put
      // back in the order of the relinking, which breaks ties as before.
      for (std::size_t k = 0; k < all_.size(); ++k)
        entry_[all_[k]].next = static_cast<std::int32_t>(k);
      const auto time = [&](std::size_t k) { return entry_[all_[k]].time; };
      const auto earlier = [&](std::int32_t a, std::int32_t b) {
        return entry_[a].time < entry_[b].time;
      };
      // The m-th earliest event, with m grown past any events tied with the earliest.
      const std::size_t last = all_.size() - 1;
      std::size_t m = std::min<std::size_t>(last, kLongList);
      for (;; m = std::min(last, 8 * m)) {
        const auto nth = all_.begin() + static_cast<std::ptrdiff_t>(m);
        std::nth_element(all_.begin(), nth, all_.end(), earlier);
        earliest = entry_[*std::min_element(all_.begin(), nth + 1, earlier)].time;
        if (m == last || time(m) > earliest) break;
      }
      const double width = m > 0 ? (time(m) - earliest) / static_cast<double>(m) : 0;
      // Bucket numbers must stay exact integers in a double.
      if (width > 1e-12 * std::max(1.0, std::abs(earliest))) width_ = width;
      for (std::size_t k = 0; k < all_.size(); ++k)
        while (static_cast<std::size_t>(entry_[all_[k]].next) != k)
          std::swap(all_[k], all_[static_cast<std::size_t>(entry_[all_[k]].next)]);
    }
    inv_width_ = 1.0 / width_;
    head_.assign(buckets, kNone);
    mask_ = buckets - 1;
    overflow_ = kNone;
    calendar_count_ = overflow_count_ = 0;
    cur_ = static_cast<std::int64_t>(std::floor(earliest * inv_width_));
    year_end_ = cur_ + static_cast<std::int64_t>(buckets);
    for (std::int32_t j : all_) link(j);
    top_ = kNone;
  }

  std::size_t capacity_;
  HugeVector<Entry> entry_;  // read at random, like the engine's particle arrays
  std::vector<std::int32_t> head_;
  std::int32_t overflow_ = kNone;
  std::size_t mask_ = 0;
  double width_ = 1, inv_width_ = 1;  // 1: a start for gases with unit speeds and spacings
  std::int64_t cur_ = 0;              // the bucket being walked
  std::int64_t year_end_ = 0;         // first bucket beyond this year
  std::size_t size_ = 0, calendar_count_ = 0, overflow_count_ = 0;
  std::int32_t top_ = kNone;   // cached earliest entry, or kNone
  double top_known_time_ = 0;  // its time
  double floor_ = INFINITY;    // no entry is due before this: the last top's time, or earlier
  std::size_t finds_ = 0, next_check_ = 0;
  std::vector<std::int32_t> all_;  // scratch of rebuild
};

}  // namespace gs
