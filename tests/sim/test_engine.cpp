#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>

#include "io/simulation_file.h"
#include "sim/engine.h"
#include "sim/error.h"
#include "sim/initial.h"
#include "sim/observables.h"
#include "tests/sim/thermal_config.h"

namespace gs {
namespace {

using test::thermal;

double momentum_scale(const Snapshot& s) {
  double sum = 0;
  for (const auto& v : s.velocity) sum += v.norm();
  return sum;
}

// Conservation to round-off: 1e-12 relative is ~1e4 times the double epsilon, room for the
// rounding of ~1e5 collisions adding up as a random walk, far below any real bookkeeping error.
void expect_conservation(Simulation& sim_ref, double t_end, int samples, bool elastic) {
  Simulation* sim = &sim_ref;
  const Sample s0 = sim->sample();
  const double scale = momentum_scale(sim->snapshot());
  for (int k = 1; k <= samples; ++k) {
    sim->run_until(t_end * k / samples);
    const Sample s = sim->sample();
    EXPECT_LT((s.momentum - s0.momentum).norm(), 1e-12 * scale) << "t = " << s.t;
    if (elastic) {
      EXPECT_NEAR(s.energy / s0.energy, 1.0, 1e-12) << "t = " << s.t;
    }
    // A pair may sit a round-off inside contact, never more.
    EXPECT_LT(sim->max_overlap_now(), 1e-9) << "t = " << s.t;
  }
  EXPECT_GT(sim->stats().collisions, 1000);
  EXPECT_EQ(sim->stats().overlaps, 0);
}

void expect_conservation(const PhysicsConfig& c, double t_end, int samples, bool elastic) {
  expect_conservation(*make_simulation(c), t_end, samples, elastic);
}

TEST(Engine, ElasticThermalGasConserves2D) {
  expect_conservation(thermal(2, 2000, 1.0), 20, 10, true);
}
TEST(Engine, ElasticThermalGasConserves3D) {
  expect_conservation(thermal(3, 2000, 1.0), 20, 10, true);
}

TEST(Engine, DenseElasticGasStaysApart3D) {
  // Packing 0.5, beyond random sequential addition: a lattice start that melts.
  PhysicsConfig c = thermal(3, 4096, 1.0);
  c.density = 0.5 * 6 / M_PI;
  InitialState<3> init;
  Rng lattice_rng(1, 0, Stream::Positions);  // 16^3 sites, none left empty: unused
  init.position = cubic_lattice<3>(c.particles, c.box(), lattice_rng);
  Rng rng(1, 0, Stream::Velocities);
  init.velocity = thermal_velocities<3>(c.particles, 1.0, rng);
  Engine<3> sim(c, std::move(init));
  expect_conservation(sim, 5, 5, true);
}

TEST(Engine, KickConservesMomentumAndBandNeverOverlaps) {
  PhysicsConfig c;
  c.dim = 2;
  c.particles = 40000;
  c.restitution = 0.1;  // the densest bands (packing ~0.8)
  c.t_max = 20000;
  expect_conservation(c, c.t_max, 8, false);
}

TEST(Engine, ElasticKickConservesEnergy1D) {
  PhysicsConfig c;
  c.dim = 1;
  c.particles = 2000;
  c.restitution = 1.0;
  expect_conservation(c, 6000, 6, true);
}

TEST(Engine, ElasticKickConservesEnergy3D) {
  PhysicsConfig c;
  c.dim = 3;
  c.particles = 20000;
  c.restitution = 1.0;
  expect_conservation(c, 300, 6, true);
}

// Paper, 1D sticky limit: the cluster of mass m moves at v0 / m and needs gap * m / v0 to reach
// the next particle, so it reaches mass m at t_m = gap m (m - 1) / (2 v0), gap = a - 1.
TEST(Engine, StickyClusterFollowsExactFormula) {
  PhysicsConfig c;
  c.dim = 1;
  c.particles = 3001;
  c.lattice = 2.5;
  c.restitution = 0.0;
  c.speed = 1.7;
  c.kick_site = KickSite::Centre;
  ASSERT_TRUE(c.sticky());
  auto sim = make_simulation(c);
  const double gap = c.lattice - 1.0;
  std::int64_t seen = 0;
  while (seen < 1200) {
    ASSERT_NE(sim->step(), EventKind::None);
    if (sim->stats().collisions == seen) continue;
    ASSERT_EQ(sim->stats().collisions, seen + 1);  // one merge per collision
    ++seen;
    const double m = static_cast<double>(seen + 1);
    const double exact = gap * m * (m - 1) / (2 * c.speed);
    ASSERT_NEAR(sim->time(), exact, 1e-9 * exact) << "collision " << seen;
    const Sample s = sim->sample();
    ASSERT_EQ(s.active, seen + 1);
    ASSERT_NEAR(s.speed_rms, c.speed / m, 1e-12);  // every member moves at v0 / m
  }
  EXPECT_NEAR(sim->sample().momentum.x() * (sim->sample().momentum.x() > 0 ? 1 : -1), c.speed,
              1e-12);
}

TEST(Engine, SameSeedSameHistoryOtherSeedOther) {
  PhysicsConfig c;
  c.particles = 5000;
  c.restitution = 0.5;
  auto a = make_simulation(c), b = make_simulation(c);
  c.seed = 2;
  auto other = make_simulation(c);
  a->run_until(500);
  b->run_until(500);
  other->run_until(500);
  EXPECT_EQ(a->stats().events, b->stats().events);
  EXPECT_EQ(a->sample().energy, b->sample().energy);  // bit for bit
  EXPECT_EQ(a->sample().radius_rms, b->sample().radius_rms);
  EXPECT_NE(a->sample().energy, other->sample().energy);
}

// active_snapshot visits only the particles that have moved, and must give active_subset of the
// whole snapshot to the bit (same order, same header), in 2D and 3D.
TEST(Engine, ActiveSnapshotIsTheActiveSubsetOfTheSnapshot) {
  for (int dim : {2, 3}) {
    PhysicsConfig c;
    c.dim = dim;
    c.particles = 20000;
    c.restitution = 0.5;
    auto sim = make_simulation(c);
    sim->run_until(300);
    const Snapshot all = active_subset(sim->snapshot());
    Snapshot active;
    sim->active_snapshot(active);
    ASSERT_GT(active.size(), 10u);
    ASSERT_EQ(active.size(), all.size());
    EXPECT_EQ(active.info.time, all.info.time);
    EXPECT_EQ(active.info.step, all.info.step);
    EXPECT_EQ(active.info.box, all.info.box);
    EXPECT_EQ(active.position, all.position);
    EXPECT_EQ(active.velocity, all.velocity);
    EXPECT_EQ(active.radius, all.radius);
    EXPECT_EQ(active.active, all.active);
    EXPECT_EQ(active.first_collision, all.first_collision);
  }
}

TEST(Engine, ParticlesAtRestHaveNoEvents) {
  // The same kick in a box 16 times larger: the events up to a time the disturbance cannot
  // cross the small box are the events of the active region only, so the counts are alike.
  PhysicsConfig c;
  c.particles = 20000;
  c.restitution = 0.5;
  c.kick_site = KickSite::Centre;
  auto small = make_simulation(c);
  c.particles = 320000;
  auto large = make_simulation(c);
  small->run_until(3000);
  large->run_until(3000);
  const double ratio =
      static_cast<double>(large->stats().events) / static_cast<double>(small->stats().events);
  // Different random packings give different histories; a cost that grew with N would give 16.
  EXPECT_GT(ratio, 0.5);
  EXPECT_LT(ratio, 2.0);
}

TEST(InitialState, RandomSequentialAdditionHasNoOverlaps) {
  for (int dim : {2, 3}) {
    PhysicsConfig c;
    c.dim = dim;
    c.particles = 4000;
    c.density = dim == 2 ? 0.6 : 0.6;
    validate(c);
    auto sim = make_simulation(c);  // at rest: max_overlap_now scans the initial packing
    EXPECT_EQ(sim->snapshot().size(), 4000u);
    EXPECT_LT(sim->max_overlap_now(), 1e-12);
  }
}

TEST(InitialState, KickedParticleAtCentreWithSpeedV0) {
  PhysicsConfig c;
  c.dim = 3;
  c.particles = 5000;
  c.speed = 2.5;
  const auto s = make_initial_state<3>(c);
  ASSERT_GE(s.kicked, 0);
  EXPECT_NEAR(s.velocity_of(s.kicked).norm(), 2.5, 1e-14);
  EXPECT_NEAR((s.position[s.kicked] - Vec<3>::Constant(0.5 * c.box())).norm(), 0.0, 1e-9);
  // A kick stores no velocities: every particle but the kicked one is at rest.
  EXPECT_TRUE(s.velocity.empty());
  int moving = 0;
  for (std::size_t i = 0; i < s.position.size(); ++i) moving += s.velocity_of(i).squaredNorm() > 0;
  EXPECT_EQ(moving, 1);
}

TEST(InitialState, ThermalHasExactTemperatureAndZeroMomentum) {
  const auto s = make_initial_state<2>(thermal(2, 3000, 1.0));
  Vec<2> p = Vec<2>::Zero();
  double v2 = 0;
  for (const auto& v : s.velocity) p += v, v2 += v.squaredNorm();
  EXPECT_LT(p.norm(), 1e-11);
  EXPECT_NEAR(v2 / (2 * 3000), 1.0, 1e-12);
}

}  // namespace
// The kicked particle of a box kick: free flight from the box centre at v0 until its first
// collision, which is the run's first; then the snapshot's unwrapped position and velocity of
// its tag, and the same after a save and a load (records keep their order).
TEST(Engine, KickedParticleIsFollowedFromTheBoxCentre) {
  for (int d : {2, 3}) {
    PhysicsConfig c;
    c.dim = d;
    c.particles = d == 2 ? 4000 : 8000;
    c.restitution = 1.0;
    auto sim = make_simulation(c);
    const double centre = 0.5 * c.box();
    KickedParticle k = sim->kicked_particle();
    ASSERT_TRUE(k.known);
    while (sim->stats().collisions == 0) {
      k = sim->kicked_particle();
      EXPECT_EQ(k.collisions, 0);
      EXPECT_NEAR(k.displacement.norm(), c.speed * sim->time(), 1e-9);
      EXPECT_NEAR(k.speed, c.speed, 1e-12);
      sim->step();
    }
    EXPECT_EQ(sim->kicked_particle().collisions, 1) << d;  // the first collision is its own
    sim->run_until(60);
    k = sim->kicked_particle();
    const Snapshot s = sim->snapshot();
    const auto tag = std::size_t(k.tag);
    Eigen::Vector3d x = s.position[tag];
    for (int a = 0; a < d; ++a) x[a] -= centre;
    EXPECT_NEAR((x - k.displacement).norm(), 0, 1e-9) << d;
    EXPECT_NEAR(s.velocity[tag].norm(), k.speed, 1e-12) << d;
    EXPECT_GT(k.collisions, 1) << d;
    EXPECT_LT(k.collisions, sim->stats().collisions) << d;
    const auto file = std::filesystem::temp_directory_path() /
                      ("gs_kicked_" + std::to_string(::getpid()) + ".state");
    save_simulation(*sim, file);
    const KickedParticle back = load_simulation_file(file)->kicked_particle();
    std::filesystem::remove(file);
    EXPECT_EQ(back.tag, k.tag);
    EXPECT_EQ(back.collisions, k.collisions);
    EXPECT_EQ(back.displacement, k.displacement);
  }
  // Not known where its record is not kept.
  PhysicsConfig u;
  u.dim = 2;
  u.medium = Medium::Unbounded;
  u.particles = 20000;
  EXPECT_FALSE(make_simulation(u)->kicked_particle().known);
}

}  // namespace gs
