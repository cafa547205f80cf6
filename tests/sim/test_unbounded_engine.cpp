// The engine in the unbounded medium (--medium unbounded): the medium it makes is the
// generator's, whatever order the front asks for its cells; it never overlaps; a kick in it
// conserves what it must; and its ensembles agree with box runs while their fronts are far from
// the box edge.
#include <gtest/gtest-spi.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <vector>

#include "sim/config.h"
#include "sim/engine.h"
#include "sim/error.h"
#include "sim/unbounded_medium.h"

namespace gs {
namespace {

PhysicsConfig unbounded(int dim, double r) {
  PhysicsConfig c;
  c.dim = dim;
  c.medium = Medium::Unbounded;
  c.particles = 200000;  // the most it may make
  c.restitution = r;
  c.seed = 7;
  return c;
}

TEST(UnboundedEngine, RefusesWhatItCannotDo) {
  PhysicsConfig c = unbounded(1, 0.5);
  EXPECT_THROW(validate(c), UsageError);
  c = unbounded(2, 0.5);
  c.initial = Initial::Thermal;
  EXPECT_THROW(validate(c), UsageError);
  c = unbounded(3, 0.5);
  c.density = 0.6;  // beyond the medium's calibration
  EXPECT_THROW(validate(c), UserError);
  EXPECT_NO_THROW(validate(unbounded(2, 0.5)));
  EXPECT_THROW(parse_medium("infinite"), UserError);
}

// The kicked particle starts nearest the centre; the medium is made only where the front is.
TEST(UnboundedEngine, KickIsAtTheCentreAndOnlyTheFrontsNeighbourhoodIsMade) {
  for (int dim : {2, 3}) {
    const PhysicsConfig c = unbounded(dim, 0.5);
    auto sim = make_simulation(c);
    const Snapshot s0 = sim->snapshot();
    const Eigen::Vector3d centre = Eigen::Vector3d::Constant(0.5 * c.box());
    std::size_t kicked = 0, nearest = 0;
    for (std::size_t i = 0; i < s0.size(); ++i) {
      if (s0.velocity[i].norm() > 0) kicked = i;
      if ((s0.position[i] - centre).norm() < (s0.position[nearest] - centre).norm()) nearest = i;
    }
    EXPECT_EQ(kicked, nearest) << dim << "D";
    EXPECT_NEAR(s0.velocity[kicked].norm(), c.speed, 1e-12);
    sim->run_until(100);
    const Snapshot s = sim->snapshot();
    double front = 0, made = 0;
    for (std::size_t i = 0; i < s.size(); ++i) {
      if (s.active[i]) front = std::max(front, (s.position[i] - centre).norm());
      made = std::max(made, (s.position[i] - centre).norm());
    }
    EXPECT_GT(sim->sample().active, 50) << dim << "D";
    // Made: the stencils of the particles that have moved, two cells beyond the front at most
    // (a moving particle's stencil reaches one cell past its own, diagonals included).
    EXPECT_LT(made, front + 2 * std::sqrt(dim) * kUnboundedCellSide + 1) << dim << "D";
  }
}

// Elastic kicks conserve energy and momentum to round-off, no pair ever overlaps, and the medium
// made around the front never overlaps (max_overlap_now scans every made pair).
TEST(UnboundedEngine, ElasticKickConservesAndNothingOverlaps) {
  for (int dim : {2, 3}) {
    const PhysicsConfig c = unbounded(dim, 1.0);
    auto sim = make_simulation(c);
    const Sample s0 = sim->sample();
    for (int k = 1; k <= 5; ++k) {
      sim->run_until(40.0 * k);
      const Sample s = sim->sample();
      // As in test_engine: 1e-12 relative is far above round-off, far below any bookkeeping slip.
      EXPECT_LT((s.momentum - s0.momentum).norm(), 1e-12 * std::max(1.0, s.active * c.speed));
      EXPECT_NEAR(s.energy / s0.energy, 1.0, 1e-12) << "t = " << s.t;
      EXPECT_LT(sim->max_overlap_now(), 1e-9) << "t = " << s.t;
    }
    EXPECT_GT(sim->stats().collisions, 1000) << dim << "D";
    EXPECT_EQ(sim->stats().overlaps, 0) << dim << "D";
  }
}

// Every particle at rest in a run is one the generator draws for its cell, so the medium does not
// depend on the order its cells were asked for (r = 1 and r = 0.2 fronts ask in different orders).
template <int D>
void expect_generators_particles(const PhysicsConfig& c, std::uint64_t reference_seed) {
  auto sim = make_simulation(c);
  sim->run_until(1000);
  const Snapshot s = sim->snapshot();
  const int middle = unbounded_cells_per_side(c) / 2;
  const double side = kUnboundedCellSide, shift = middle * side;
  UnboundedMedium<D> medium(MediumOptions{D, c.density, side, reference_seed, c.realisation});
  std::map<typename UnboundedMedium<D>::Cell, VecArray<D>> drawn;
  std::size_t checked = 0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (s.velocity[i].norm() > 0 || s.active[i]) continue;
    Vec<D> x = s.position[i].template head<D>();
    typename UnboundedMedium<D>::Cell cell;
    for (int k = 0; k < D; ++k)
      cell[k] = static_cast<std::int64_t>(std::floor((x[k] - shift) / side));
    auto [it, fresh] = drawn.try_emplace(cell);
    if (fresh) medium.particles(cell, it->second);
    const bool found = std::any_of(it->second.begin(), it->second.end(), [&](const Vec<D>& y) {
      return ((y + Vec<D>::Constant(shift)) - x).norm() < 1e-9;
    });
    ASSERT_TRUE(found) << D << "D, particle " << i;
    ++checked;
  }
  EXPECT_GT(checked, 50u);
}

TEST(UnboundedEngine, MadeParticlesAreTheGeneratorsWhateverTheOrder) {
  for (double r : {1.0, 0.2}) {
    expect_generators_particles<2>(unbounded(2, r), 7);
    expect_generators_particles<3>(unbounded(3, r), 7);
  }
}

TEST(UnboundedEngine, TheGeneratorCheckSeesAnotherSeed) {
  EXPECT_FATAL_FAILURE(expect_generators_particles<2>(unbounded(2, 1.0), 8), "found");
}

TEST(UnboundedEngine, RefusesToMakeMoreThanParticlesAllows) {
  PhysicsConfig c = unbounded(2, 0.5);
  c.particles = 2000;
  auto sim = make_simulation(c);
  try {
    sim->run_until(1e4);
    FAIL() << "no error";
  } catch (const UserError& e) {
    EXPECT_NE(std::string(e.what()).find("--particles 2000"), std::string::npos) << e.what();
  }
}

// Means and standard errors of N_t, E_t and R_t at time t over `runs` realisations.
struct Ensemble {
  double mean[3] = {}, error[3] = {};
  double reach = 0;  // the farthest an active particle got from the kick, in any run
};

Ensemble ensemble(PhysicsConfig c, int runs, double t) {
  double sum[3] = {}, sum2[3] = {};
  Ensemble e;
  for (int k = 0; k < runs; ++k) {
    c.realisation = static_cast<std::uint64_t>(k);
    auto sim = make_simulation(c);
    sim->run_until(t);
    const Sample s = sim->sample();
    std::vector<Eigen::Vector3d> active;
    sim->active_positions(active);
    for (const auto& x : active)
      e.reach =
          std::max(e.reach, (x - Eigen::Vector3d::Constant(0.5 * c.box())).head(c.dim).norm());
    const double x[3] = {static_cast<double>(s.active), s.energy, s.radius_rms};
    for (int m = 0; m < 3; ++m) sum[m] += x[m], sum2[m] += x[m] * x[m];
  }
  for (int m = 0; m < 3; ++m) {
    e.mean[m] = sum[m] / runs;
    const double var = (sum2[m] - runs * e.mean[m] * e.mean[m]) / (runs - 1);
    e.error[m] = std::sqrt(std::max(var, 0.0) / runs);
  }
  return e;
}

// The largest of the three differences in units of their combined standard error.
double worst_z(const Ensemble& a, const Ensemble& b) {
  double z = 0;
  for (int m = 0; m < 3; ++m)
    z = std::max(z, std::abs(a.mean[m] - b.mean[m]) / std::hypot(a.error[m], b.error[m]));
  return z;
}

// r = 0.5 kicks, `runs` realisations each (2 s of CPU in 2D, 4 in 3D; many small runs beat a few
// large ones for the same cost), in a box of `particles` whose front stays below 0.6 L/2 (checked) and in
// the unbounded medium. Seeds are fixed, so the test is deterministic. The bound is 3 standard
// errors: two means of 100 or so differ by more by chance in 0.3% of seed sets per observable
// (under 1% for the worst of three). A medium of the wrong density (0.3 against 0.25) must be seen.
void expect_agreement(int dim, std::int64_t particles, double t, int runs) {
  PhysicsConfig box;
  box.dim = dim;
  box.restitution = 0.5;
  box.particles = particles;
  box.kick_site = KickSite::Centre;
  box.seed = 21;
  PhysicsConfig open = box;
  open.medium = Medium::Unbounded;
  const Ensemble a = ensemble(box, runs, t), b = ensemble(open, runs, t);
  for (int m = 0; m < 3; ++m)
    std::printf("observable %d: box %.4g +- %.2g, unbounded %.4g +- %.2g\n", m, a.mean[m],
                a.error[m], b.mean[m], b.error[m]);
  std::printf("box reach %.3g of L/2 = %.3g, z %.3g\n", a.reach, box.box() / 2, worst_z(a, b));
  EXPECT_LT(a.reach, 0.6 * box.box() / 2) << "the box runs' front came near the box edge";
  EXPECT_LT(worst_z(a, b), 3.0);
  open.density = 0.3;
  const double wrong = worst_z(a, ensemble(open, runs, t));
  std::printf("wrong density: z %.3g\n", wrong);
  EXPECT_GT(wrong, 3.0) << "the comparison sees a wrong density";
}

// L/2 = 200, the farthest active disc 53 from the kick (R_t ~ 23): z = 1.3, the wrong density 10.
TEST(UnboundedEngine, EnsembleAgreesWithBoxRuns2D) {
  expect_agreement(2, 40000, 1000, 128);
}

// L/2 = 34, the farthest active sphere 16 from the kick (R_t ~ 5): z = 0.9, the wrong density 11.
TEST(UnboundedEngine, EnsembleAgreesWithBoxRuns3D) {
  expect_agreement(3, 80000, 30, 96);
}

}  // namespace
}  // namespace gs
