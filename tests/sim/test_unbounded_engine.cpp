// The engine in the unbounded medium (--medium unbounded): the medium it makes is the
// generator's, whatever order the front asks for its cells; it never overlaps; a kick in it
// conserves what it must; and its ensembles agree with box runs while their fronts are far from
// the box edge.
#include <gtest/gtest-spi.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <map>
#include <vector>

#include "sim/config.h"
#include "sim/engine.h"
#include "sim/error.h"
#include "sim/memory_budget.h"
#include "sim/observables.h"
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

// How far a front gets is what a run measures, so an unbounded run is not refused on its cap
// (a box of that many is); its engines take the memory of what they make from the process's
// budget and the run ends, naming the memory, when the next cell would not fit.
TEST(UnboundedEngine, ARunEndsWhenItsMediumWouldNotFitInMemory) {
  PhysicsConfig c = unbounded(3, 0.5);
  c.particles = 100000000;  // 63 GB if all were made
  EXPECT_NO_THROW(validate(c));
  PhysicsConfig box = c;
  box.medium = Medium::Box;
  EXPECT_THROW(check_memory(box), UserError);

  MemoryBudget& budget = MemoryBudget::process();
  const std::int64_t machine = budget.capacity();
  ASSERT_EQ(budget.taken(), 0);
  {
    auto first = make_simulation(c);
    first->run_until(300);
    const std::int64_t held = budget.taken();
    // What it holds is what it made, at the bytes per particle the estimate uses.
    EXPECT_EQ(held, std::int64_t(std::ceil(unbounded_bytes_per_particle(c))) *
                        std::int64_t(first->snapshot().size()));
    // A machine of 3 MB more: a second run gets no further than about 5000 spheres.
    budget.set_capacity(held + 3000000);
    auto second = make_simulation(c);
    try {
      second->run_until(1e5);
      ADD_FAILURE() << "a run past the machine's memory went on";
    } catch (const UserError& e) {
      const std::string m = e.what();
      EXPECT_NE(m.find("would not fit in this machine's"), std::string::npos) << m;
      EXPECT_NE(m.find("beside this process's other runs"), std::string::npos) << m;
    }
    EXPECT_LE(budget.taken(), held + 3000000);
    // One that cannot even make the kick's neighbourhood is refused in its constructor, and
    // gives back what it took.
    budget.set_capacity(budget.taken() + 1000);
    const std::int64_t before = budget.taken();
    EXPECT_THROW(make_simulation(c), UserError);
    EXPECT_EQ(budget.taken(), before);
  }
  budget.set_capacity(machine);
  EXPECT_EQ(budget.taken(), 0);  // every engine gave its memory back
}

// One ensemble at time t: per realisation N_t, E_t, R_t and the active particles' speeds.
struct Ensemble {
  std::vector<std::array<double, 3>> scalars;
  std::vector<std::vector<double>> speeds;
  double reach = 0;  // the farthest an active particle got from the kick, in any run
};

Ensemble ensemble(PhysicsConfig c, int runs, double t) {
  Ensemble e;
  Snapshot active;
  for (int k = 0; k < runs; ++k) {
    c.realisation = static_cast<std::uint64_t>(k);
    auto sim = make_simulation(c);
    sim->run_until(t);
    const Sample s = sim->sample();
    sim->active_snapshot(active);
    // The kick's site; 2D positions have z = 0.
    const double half = 0.5 * c.box();
    const Eigen::Vector3d centre(half, half, c.dim == 3 ? half : 0.0);
    for (const auto& x : active.position) e.reach = std::max(e.reach, (x - centre).norm());
    e.scalars.push_back({static_cast<double>(s.active), s.energy, s.radius_rms});
    e.speeds.push_back(active_speeds(active));
  }
  return e;
}

struct MeanError {
  double mean = 0, error = 0;
};

MeanError mean_error(const std::vector<double>& x) {
  const double n = static_cast<double>(x.size());
  double sum = 0, sum2 = 0;
  for (double v : x) sum += v, sum2 += v * v;
  const double mean = sum / n;
  return {mean, std::sqrt(std::max(sum2 - n * mean * mean, 0.0) / (n - 1) / n)};
}

double z_of(const MeanError& a, const MeanError& b) {
  return std::abs(a.mean - b.mean) / std::hypot(a.error, b.error);
}

// P(v,t) in kSpeedBins bins of equal probability in the box ensemble (edges at the quantiles of
// its pooled speeds): each realisation's fraction of active particles per bin, so that the
// correlations within a realisation are in the realisation-to-realisation error.
constexpr int kSpeedBins = 8;

std::vector<double> speed_edges(const Ensemble& box) {
  std::vector<double> all;
  for (const auto& v : box.speeds) all.insert(all.end(), v.begin(), v.end());
  std::sort(all.begin(), all.end());
  std::vector<double> edges;
  for (int k = 1; k < kSpeedBins; ++k) edges.push_back(all[all.size() * k / kSpeedBins]);
  return edges;
}

std::vector<MeanError> speed_fractions(const Ensemble& e, const std::vector<double>& edges,
                                       double factor) {
  std::vector<std::vector<double>> fraction(kSpeedBins);
  for (const auto& speeds : e.speeds) {
    std::vector<double> count(kSpeedBins, 0.0);
    for (double v : speeds)
      count[std::upper_bound(edges.begin(), edges.end(), v * factor) - edges.begin()] += 1;
    for (int k = 0; k < kSpeedBins; ++k)
      fraction[k].push_back(count[k] / std::max<double>(1, speeds.size()));
  }
  std::vector<MeanError> out;
  for (const auto& f : fraction) out.push_back(mean_error(f));
  return out;
}

// Worst z of N_t, E_t, R_t (E_t left out at r = 1, where it is the kick's energy to round-off in
// both media) and of P(v,t)'s bins, the unbounded ensemble's speeds scaled by `factor`.
struct Verdict {
  double scalars = 0, speeds = 0;
};

Verdict compare(const Ensemble& box, const Ensemble& open, bool elastic, double factor = 1.0,
                bool print = false) {
  static const char* kNames[3] = {"N_t", "E_t", "R_t"};
  Verdict v;
  for (int m = 0; m < 3; ++m) {
    if (m == 1 && elastic) continue;
    std::vector<double> a, b;
    for (const auto& s : box.scalars) a.push_back(s[m]);
    for (const auto& s : open.scalars) b.push_back(s[m]);
    const MeanError x = mean_error(a), y = mean_error(b);
    v.scalars = std::max(v.scalars, z_of(x, y));
    if (print)
      std::printf("  %s: box %.5g +- %.2g, unbounded %.5g +- %.2g, z %.2f\n", kNames[m], x.mean,
                  x.error, y.mean, y.error, z_of(x, y));
  }
  const std::vector<double> edges = speed_edges(box);
  const auto a = speed_fractions(box, edges, 1.0), b = speed_fractions(open, edges, factor);
  for (int k = 0; k < kSpeedBins; ++k) v.speeds = std::max(v.speeds, z_of(a[k], b[k]));
  if (print) {
    std::printf("  P(v,t) fractions in %d bins (edges", kSpeedBins);
    for (double x : edges) std::printf(" %.3g", x);
    std::printf("):\n    box      ");
    for (const auto& x : a) std::printf(" %.4f", x.mean);
    std::printf("\n    unbounded");
    for (const auto& x : b) std::printf(" %.4f", x.mean);
    std::printf("\n  worst z: N_t/E_t/R_t %.2f, P(v,t) %.2f\n", v.scalars, v.speeds);
  }
  return v;
}

// Kicks with restitution r, `runs` realisations each (many small runs beat a few large ones for
// the same cost) in a box of `particles` whose front stays below 0.6 L/2 (checked) and in the
// unbounded medium; seeds are fixed, so the test is deterministic. The bounds: 3 standard errors
// on the worst of N_t, E_t, R_t, crossed by chance in under 3 x 0.27% of seed sets, and 3.5 on the
// worst of P(v,t)'s 8 bins, under 8 x 0.047%. Both must be crossed by a medium of the wrong density
// (0.3 against 0.25), and the second by P(v,t) shifted by `shift` (unbounded speeds x (1 + shift)):
// 5% in 2D; 10% in 3D, whose fronts of 50-90 spheres by the time they near 0.6 L/2 resolve less.
constexpr double kScalarBound = 3.0, kSpeedBound = 3.5;

bool agree(const Verdict& v) {
  return v.scalars < kScalarBound && v.speeds < kSpeedBound;
}

void expect_agreement(int dim, double r, std::int64_t particles, double t, int runs, double shift) {
  PhysicsConfig box;
  box.dim = dim;
  box.restitution = r;
  box.particles = particles;
  box.kick_site = KickSite::Centre;
  box.seed = 21;
  PhysicsConfig open = box;
  open.medium = Medium::Unbounded;
  const bool elastic = r == 1.0;
  const Ensemble a = ensemble(box, runs, t), b = ensemble(open, runs, t);
  std::printf("%dD r = %g, t = %g, %d + %d realisations; box front %.3g of 0.6 L/2 = %.3g\n", dim,
              r, t, runs, runs, a.reach, 0.6 * box.box() / 2);
  const Verdict same = compare(a, b, elastic, 1.0, true);
  EXPECT_LT(a.reach, 0.6 * box.box() / 2) << "the box runs' front came near the box edge";
  EXPECT_LT(same.scalars, kScalarBound);
  EXPECT_LT(same.speeds, kSpeedBound);
  const double shifted = compare(a, b, elastic, 1 + shift).speeds;
  open.density = 0.3;
  const Verdict wrong = compare(a, ensemble(open, runs, t), elastic);
  std::printf("  must fail: P(v,t) x %.3g z %.2f; density 0.3 z %.2f (P(v,t) %.2f)\n", 1 + shift,
              shifted, wrong.scalars, wrong.speeds);
  EXPECT_GT(shifted, kSpeedBound) << "the comparison sees P(v,t) shifted by " << shift;
  EXPECT_FALSE(agree(wrong)) << "the comparison sees a wrong density";
}

TEST(UnboundedEngine, EnsembleAgreesWithBoxRuns2DInelastic) {
  expect_agreement(2, 0.1, 40000, 1000, 128, 0.05);
}

TEST(UnboundedEngine, EnsembleAgreesWithBoxRuns2D) {
  expect_agreement(2, 0.5, 40000, 1000, 128, 0.05);
}

TEST(UnboundedEngine, EnsembleAgreesWithBoxRuns2DElastic) {
  expect_agreement(2, 1.0, 40000, 300, 128, 0.05);
}

TEST(UnboundedEngine, EnsembleAgreesWithBoxRuns3DInelastic) {
  expect_agreement(3, 0.1, 80000, 30, 96, 0.1);
}

TEST(UnboundedEngine, EnsembleAgreesWithBoxRuns3D) {
  expect_agreement(3, 0.5, 80000, 30, 96, 0.1);
}

TEST(UnboundedEngine, EnsembleAgreesWithBoxRuns3DElastic) {
  expect_agreement(3, 1.0, 80000, 20, 96, 0.1);
}

}  // namespace
}  // namespace gs
