#pragma once
// Two simulations that must make the same history: a resumed one against one never stopped, a
// kick through the resting store against the same state held as records.
#include <gtest/gtest.h>

#include <cstring>

#include "sim/engine.h"

namespace gs::test {

// Steps both engines `events` times; every event must be of the same kind at the same time,
// and the states must end identical to the last bit.
inline void expect_same_history(Simulation& a, Simulation& b, int events) {
  for (int k = 0; k < events; ++k) {
    const EventKind ka = a.step(), kb = b.step();
    ASSERT_EQ(ka, kb) << "event " << k;
    ASSERT_EQ(a.time(), b.time()) << "event " << k;
    if (ka == EventKind::None) break;
  }
  const Snapshot sa = a.snapshot(), sb = b.snapshot();
  ASSERT_EQ(sa.size(), sb.size());
  for (std::size_t i = 0; i < sa.size(); ++i) {
    ASSERT_EQ(sa.position[i], sb.position[i]) << i;
    ASSERT_EQ(sa.velocity[i], sb.velocity[i]) << i;
    ASSERT_EQ(sa.first_collision[i], sb.first_collision[i]) << i;
  }
  EXPECT_EQ(std::memcmp(&a.stats(), &b.stats(), sizeof(EngineStats)), 0);
}

}  // namespace gs::test
