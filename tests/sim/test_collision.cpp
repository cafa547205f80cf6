#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <utility>
#include <vector>

#include "sim/collision.h"
#include "sim/event_queue.h"
#include "sim/rng.h"

namespace gs {
namespace {

TEST(CollisionRule, HeadOnScalesNormalSpeedByR) {
  Vec<2> v1(1.0, 0.0), v2(0.0, 0.0);
  const auto res = collide<2>(v1, v2, Vec<2>(1.0, 0.0), 0.5, 1e-4);
  EXPECT_TRUE(res.inelastic);
  // eps = 0.75: v1 = 1 - 0.75, v2 = 0.75; relative normal speed 0.5 = r * 1.
  EXPECT_DOUBLE_EQ(v1.x(), 0.25);
  EXPECT_DOUBLE_EQ(v2.x(), 0.75);
  EXPECT_DOUBLE_EQ(v2.x() - v1.x(), 0.5);
  EXPECT_DOUBLE_EQ(res.impulse, 0.75);
}

TEST(CollisionRule, ObliqueKeepsTangentAndMomentum) {
  Rng rng(7, 0, Stream::Velocities);
  for (int trial = 0; trial < 1000; ++trial) {
    Vec<3> v1, v2, n;
    for (int k = 0; k < 3; ++k) v1[k] = rng.normal(), v2[k] = rng.normal(), n[k] = rng.normal();
    n.normalize();
    const double r = rng.uniform();
    const Vec<3> p0 = v1 + v2, g0 = v1 - v2;
    const double w0 = n.dot(g0);
    const Vec<3> t0 = g0 - w0 * n;
    const auto res = collide<3>(v1, v2, n, r, 1e-4);
    const Vec<3> g1 = v1 - v2;
    if (w0 <= 0) {  // receding pairs are left alone
      EXPECT_EQ(res.impulse, 0);
      continue;
    }
    EXPECT_LT((v1 + v2 - p0).norm(), 1e-15 * (1 + p0.norm()));  // momentum exact
    EXPECT_NEAR((g1 - n.dot(g1) * n - t0).norm(), 0.0, 1e-14);  // tangent unchanged
    const double expected = w0 >= 1e-4 ? -r * w0 : -w0;         // normal part scaled
    EXPECT_NEAR(n.dot(g1), expected, 1e-14);
  }
}

TEST(CollisionRule, BelowCutoffIsElastic) {
  Vec<2> v1(5e-5, 0.0), v2(0.0, 0.0);
  const auto res = collide<2>(v1, v2, Vec<2>(1.0, 0.0), 0.1, 1e-4);
  EXPECT_FALSE(res.inelastic);
  EXPECT_DOUBLE_EQ(v1.x(), 0.0);  // equal masses exchange velocities in an elastic head-on hit
  EXPECT_DOUBLE_EQ(v2.x(), 5e-5);
  Vec<2> u1(2e-4, 0.0), u2(0.0, 0.0);
  EXPECT_TRUE(collide<2>(u1, u2, Vec<2>(1.0, 0.0), 0.1, 1e-4).inelastic);
}

TEST(ContactTime, MatchesGeometry) {
  // Approaching along x from distance 3 at relative speed 2: contact (distance 1) after 1.
  EXPECT_DOUBLE_EQ(contact_time<2>(Vec<2>(3.0, 0.0), Vec<2>(-2.0, 0.0)), 1.0);
  // Grazing miss: impact parameter 1.5 > diameter.
  EXPECT_EQ(contact_time<2>(Vec<2>(3.0, 1.5), Vec<2>(-1.0, 0.0)), kNever);
  // Receding.
  EXPECT_EQ(contact_time<2>(Vec<2>(3.0, 0.0), Vec<2>(1.0, 0.0)), kNever);
  // Oblique: impact parameter 0.6, contact when x = sqrt(1 - 0.36) = 0.8.
  EXPECT_NEAR(contact_time<2>(Vec<2>(2.8, 0.6), Vec<2>(-1.0, 0.0)), 2.0, 1e-14);
  // Overlapping and approaching: at once; overlapping and receding: never.
  EXPECT_EQ(contact_time<2>(Vec<2>(0.999, 0.0), Vec<2>(-1.0, 0.0)), 0.0);
  EXPECT_EQ(contact_time<2>(Vec<2>(0.999, 0.0), Vec<2>(1.0, 0.0)), kNever);
}

TEST(EventQueue, PopsInTimeOrderUnderUpdates) {
  Rng rng(3, 0, Stream::Positions);
  const int n = 2000;
  EventQueue q(n);
  std::vector<double> key(n);
  for (int i = 0; i < n; ++i) q.set(i, key[i] = rng.uniform());
  for (int k = 0; k < 5000; ++k) {  // random reschedules and removals
    const int i = static_cast<int>(rng.below(n));
    if (rng.uniform() < 0.2) {
      q.remove(i);
      key[i] = -1;
    } else {
      q.set(i, key[i] = rng.uniform());
    }
  }
  std::vector<double> expected;
  for (double k : key)
    if (k >= 0) expected.push_back(k);
  std::sort(expected.begin(), expected.end());
  ASSERT_EQ(q.size(), expected.size());
  for (double e : expected) {
    ASSERT_EQ(q.top_time(), e);
    q.remove(q.top());
  }
  EXPECT_TRUE(q.empty());
}

// The queue as the engine drives it, against an ordered set: the earliest event is taken and
// rescheduled later, others are rescheduled or dropped, new ones arrive. Event spacings sweep
// six decades while the population grows to 4000 and shrinks again, and one event in twenty is
// far in the future, so the calendar must re-choose its width and size and carry events over
// years; every top must still be the true earliest, and the events peeked at after it (for
// prefetching) must be other queued events, later than it and in time order.
TEST(EventQueue, FollowsEventRatesOverSixDecades) {
  Rng rng(5, 0, Stream::Positions);
  const int n = 4000, steps = 300000;
  EventQueue q(n);
  std::set<std::pair<double, int>> ref;
  std::vector<double> key(n, -1);
  auto put = [&](int i, double t) {
    if (key[i] >= 0) ref.erase({key[i], i});
    ref.insert({key[i] = t, i});
    q.set(i, t);
  };
  auto drop = [&](int i) {
    if (key[i] < 0) return;
    ref.erase({key[i], i});
    key[i] = -1;
    q.remove(i);
  };
  int born = 0;
  put(born++, 0.5);
  for (int k = 0; k < steps; ++k) {
    ASSERT_EQ(q.size(), ref.size());
    ASSERT_EQ(q.top_time(), ref.begin()->first) << "step " << k;
    ASSERT_EQ(q.top(), ref.begin()->second) << "step " << k;
    const double now = ref.begin()->first;
    const EventQueue::Soon soon = q.peek_soon(2);
    for (int m = 0; m < soon.count; ++m) {
      ASSERT_NE(soon.id[m], q.top());
      ASSERT_GT(key[soon.id[m]], m > 0 ? key[soon.id[m - 1]] : now);
    }
    const double spacing = 1e-3 * std::pow(1e6, static_cast<double>(k) / steps);
    auto later = [&] {
      const double t = -std::log(1 - rng.uniform()) * spacing * q.size();
      return now + (rng.uniform() < 0.05 ? 1e4 * t : t);
    };
    put(ref.begin()->second, later());
    const bool growing = k < steps / 2;
    if (growing && born < n) put(born++, later());
    const int other = static_cast<int>(rng.below(static_cast<std::uint64_t>(born)));
    if (!growing && ref.size() > 1 && rng.uniform() < 0.02)
      drop(other);
    else if (key[other] >= 0)
      put(other, later());
  }
}

// Peeking looks past the order of a bucket's list (the last set comes first) and past the entry
// of the top's partner, due at the top's instant: the next two events are 3 and 4.
TEST(EventQueue, PeekSortsTheBucketAndSkipsThePartner) {
  EventQueue q(8);
  const double time[] = {0.1, 0.1, 0.5, 0.3, 0.4};  // one bucket: the first is 1 wide
  for (int i = 0; i < 5; ++i) q.set(i, time[i]);
  ASSERT_EQ(q.top_time(), 0.1);
  const std::int32_t partner = q.top() == 0 ? 1 : 0;
  const EventQueue::Soon soon = q.peek_soon(2);
  ASSERT_EQ(soon.count, 2);
  EXPECT_EQ(soon.id[0], 3);
  EXPECT_EQ(soon.id[1], 4);
  EXPECT_NE(soon.id[0], partner);
}

// A lattice start can put thousands of events at one instant (every sphere on a cell wall): the
// calendar must take them all at that instant, then find a width for the events after them,
// and an entry set before the last top (direct use of the queue) must still come first.
TEST(EventQueue, TiesAtOneInstantThenSpreadEvents) {
  Rng rng(7, 0, Stream::Positions);
  const int n = 4000;
  EventQueue q(n);
  std::set<std::pair<double, int>> ref;
  std::vector<double> key(n);
  auto put = [&](int i, double t) {
    ref.erase({key[i], i});
    ref.insert({key[i] = t, i});
    q.set(i, t);
  };
  for (int i = 0; i < n; ++i) put(i, i < 3000 ? 0.0 : 1 + rng.uniform());
  for (int k = 0; k < 20000; ++k) {
    ASSERT_EQ(q.top_time(), ref.begin()->first) << "step " << k;
    const auto [now, i] = *ref.begin();
    ASSERT_EQ(key[q.top()], now) << "step " << k;
    put(i, now + 1e-3 * rng.uniform());
    if (k == 10000) {  // one entry before the last top, then one at it, in the same bucket
      put((i + 1) % n, now / 2);
      put((i + 2) % n, now);
    }
  }
}

}  // namespace
}  // namespace gs
