// Inputs that once hung the engine or its set-up, and the stop that ends its loop whatever the
// clock does.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "sim/collision.h"
#include "sim/config.h"
#include "sim/engine.h"
#include "sim/error.h"
#include "sim/stop.h"

namespace gs {
namespace {

// Two touching spheres with the same normal velocity but for a round-off approach, as r = 0
// leaves them: the rule must change their velocities so that they recede (a reflection of
// 1e-18 changed no bit, and the engine found the same collision again forever).
TEST(Hangs, GrazingPairParts) {
  const Vec<3> n = Vec<3>(1.0, 2.0, 2.0) / 3.0;
  for (double w : {1e-18, 0.0, -1e-18}) {
    const Vec<3> tangent = Vec<3>(2.0, -1.0, 0.0) * 0.1;  // n.tangent = 0: they also slide
    Vec<3> v1(0.3, -0.7, 0.2), v2 = v1 - w * n + tangent;
    const Vec<3> p0 = v1 + v2;
    const double speeds = v1.norm() + v2.norm();
    const CollisionResult res = collide<3>(v1, v2, n, 0.0, 1e-4);
    EXPECT_GT(res.impulse, 0) << w;
    EXPECT_FALSE(res.inelastic) << w;
    // Recedes at kGrazingFraction of the speeds (to round-off of the speeds, 1e-16).
    EXPECT_NEAR(n.dot(v1 - v2), -kGrazingFraction * speeds, 1e-15) << w;
    EXPECT_LT((v1 + v2 - p0).norm(), 1e-15);
  }
  // A pair receding by more is left alone, an approaching one collides as before.
  Vec<3> v1(0.0, 0.0, 0.0), v2 = 1e-6 * n;
  EXPECT_EQ(collide<3>(v1, v2, n, 0.0, 1e-4).impulse, 0);
  Vec<3> u1 = 1e-2 * n, u2(0.0, 0.0, 0.0);
  EXPECT_TRUE(collide<3>(u1, u2, n, 0.0, 1e-4).inelastic);
  EXPECT_NEAR(n.dot(u1 - u2), 0.0, 1e-17);  // r = 0: no normal speed left, to round-off
}

// r = 0 in 2D and 3D reaches t_max in a bounded number of events; it used to stop the clock at
// t = 15.6 (2D) or 5.4 (3D), colliding a grazing pair forever. The runs take 2e4-1.4e5 events
// with the cutoffs 1e-4 and 0.1 and 5.4e6 in 2D without one (clusters then collide at
// kRoundoffCutoff's speeds): the limits are 10 times those.
TEST(Hangs, ZeroRestitutionReachesTMaxIn2DAnd3D) {
  for (int dim : {2, 3})
    for (double cutoff : {1e-4, 0.1, 0.0}) {
      PhysicsConfig c;
      c.dim = dim;
      c.particles = 20000;
      c.restitution = 0;
      c.cutoff = cutoff;
      c.t_max = 2000;
      validate(c);
      const auto sim = make_simulation(c);
      const double e0 = sim->sample().energy;
      const std::int64_t most = cutoff > 0 ? 2000000 : 60000000;
      std::int64_t events = 0;
      while (sim->time() < c.t_max && events < most) {
        if (sim->step() == EventKind::None) break;
        ++events;
      }
      EXPECT_LT(events, most) << dim << "D cutoff " << cutoff << " stuck at t = " << sim->time();
      const Sample s = sim->sample();
      EXPECT_LT(s.energy, e0) << dim << "D";  // r = 0 dissipates
      EXPECT_NEAR(s.momentum.norm(), c.speed, 1e-9) << dim << "D";  // the kick's, conserved
      std::printf("%dD r = 0 cutoff %g: t = %g after %lld events, %lld active, E = %g\n", dim,
                  cutoff, sim->time(), static_cast<long long>(events),
                  static_cast<long long>(s.active), s.energy);
    }
}

// The rule is continuous in r, and r = 0 (pairs left touching, parted when grazing) is the limit
// of r -> 0: the same kick with r = 1e-9, whose every post-collision normal speed differs by 1e-9
// of itself, ends with the same N_t and E_t but for what the chaos of a few thousand collisions
// makes of that difference (seen: N_t within 0.4%, E_t within 1% at t = 2000, seeds 1-4).
TEST(Hangs, ZeroRestitutionIsTheLimitOfSmallR) {
  for (int dim : {2, 3})
    for (std::uint64_t seed : {1, 2}) {
      Sample s[2];
      for (int k = 0; k < 2; ++k) {
        PhysicsConfig c;
        c.dim = dim;
        c.particles = 20000;
        c.restitution = k == 0 ? 0.0 : 1e-9;
        c.seed = seed;
        c.t_max = 2000;
        const auto sim = make_simulation(c);
        sim->run_until(c.t_max);
        s[k] = sim->sample();
      }
      const double n = static_cast<double>(s[1].active);
      EXPECT_NEAR(static_cast<double>(s[0].active), n, 0.03 * n) << dim << "D seed " << seed;
      EXPECT_NEAR(s[0].energy, s[1].energy, 0.03 * s[1].energy) << dim << "D seed " << seed;
    }
}

// A stop asked for ends run_until within kStopPollEvents events, the clock short of the target,
// and nothing is lost: run_until goes on to the same state as a run never stopped.
TEST(Hangs, RunUntilHonoursAStopByEventCount) {
  PhysicsConfig c;
  c.dim = 2;
  c.particles = 400;
  c.initial = Initial::Thermal;
  c.density = 0.3;
  c.restitution = 1;
  c.t_max = 1e4;
  validate(c);
  const auto stopped = make_simulation(c), straight = make_simulation(c);
  request_stop();
  stopped->run_until(1e4);  // about 1e7 events if the stop were not seen
  clear_stop();
  EXPECT_EQ(stopped->stats().events, Simulation::kStopPollEvents);
  const double t = stopped->time();
  EXPECT_LT(t, 1e4);
  straight->run_until(t);  // the events up to the stop's, as a slice would end there
  EXPECT_EQ(stopped->stats().events, straight->stats().events);
  stopped->run_until(t + 20);
  straight->run_until(t + 20);
  EXPECT_EQ(stopped->stats().events, straight->stats().events);
  EXPECT_EQ(stopped->snapshot().position, straight->snapshot().position);
}

// The unbounded medium refuses a density whose kicked particle would fly out of its reach before
// its first collision, naming the density it needs; the box refused such values already.
TEST(Hangs, VanishingUnboundedDensityIsRefused) {
  for (int dim : {2, 3}) {
    PhysicsConfig c;
    c.dim = dim;
    c.medium = Medium::Unbounded;
    c.particles = 20000;
    const double least = min_unbounded_density(dim);
    EXPECT_GT(least, 0);
    EXPECT_LT(least, dim == 2 ? 1e-3 : 1e-2);  // dilute gases stay possible
    for (double density : {1e-9, 1e-30, 1e-320, 0.99 * least}) {
      c.density = density;
      try {
        validate(c);
        ADD_FAILURE() << dim << "D density " << density << " accepted";
      } catch (const UserError& e) {
        const std::string m = e.what();
        EXPECT_EQ(m.rfind("--density ", 0), 0u) << m;
        EXPECT_NE(m.find(" or more"), std::string::npos) << m;
      }
    }
    c.density = least;
    EXPECT_NO_THROW(validate(c)) << dim << "D";
  }
}

}  // namespace
}  // namespace gs
