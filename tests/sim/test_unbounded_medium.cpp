// The unbounded medium (sim/unbounded_medium.h): the same particles whatever order cells are
// asked in, no overlaps across cells, the box runs' density, and the structure of RSA in a
// periodic box (g(r), number variance in windows of 10 and 30 diameters).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <tuple>
#include <type_traits>
#include <vector>

#include "sim/error.h"
#include "sim/initial.h"
#include "sim/rng.h"
#include "sim/unbounded_medium.h"

namespace gs {
namespace {

template <int D>
using Cell = typename UnboundedMedium<D>::Cell;

// Every cell of [origin, origin + side)^D in lexicographic order.
template <int D>
std::vector<Cell<D>> cells_of_cube(int side, std::int64_t origin = 0) {
  std::vector<Cell<D>> out;
  Cell<D> c;
  c.fill(origin);
  for (;;) {
    out.push_back(c);
    int k = 0;
    while (k < D && c[k] == origin + side - 1) c[k] = origin, ++k;
    if (k == D) break;
    ++c[k];
  }
  return out;
}

template <int D>
VecArray<D> cube(UnboundedMedium<D>& m, int side, std::int64_t origin = 0) {
  VecArray<D> x;
  for (const auto& c : cells_of_cube<D>(side, origin)) m.particles(c, x);
  return x;
}

template <int D>
MediumOptions options(double density, std::uint64_t realisation) {
  MediumOptions o;
  o.dim = D;
  o.density = density;
  o.seed = 31;
  o.realisation = realisation;
  return o;
}

template <int D>
void expect_same_whatever_the_order(double density, int side) {
  UnboundedMedium<D> in_order(options<D>(density, 0));
  UnboundedMedium<D> shuffled(options<D>(density, 0));
  auto cells = cells_of_cube<D>(side);
  std::vector<VecArray<D>> first(cells.size());
  for (std::size_t i = 0; i < cells.size(); ++i) in_order.particles(cells[i], first[i]);
  // The reverse order, a seeded shuffle, the memo dropped half way, and a cell asked alone.
  std::vector<std::size_t> order(cells.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = order.size() - 1 - i;
  Rng rng(5, 0, Stream::Kick);
  for (std::size_t i = order.size(); i > 1; --i) std::swap(order[i - 1], order[rng.below(i)]);
  std::size_t checked = 0, particles = 0;
  for (std::size_t n = 0; n < order.size(); ++n) {
    if (n == order.size() / 2) shuffled.clear();
    const std::size_t i = order[n];
    VecArray<D> again;
    shuffled.particles(cells[i], again);
    ASSERT_EQ(again.size(), first[i].size()) << "cell " << i;
    for (std::size_t p = 0; p < again.size(); ++p)
      for (int k = 0; k < D; ++k) ASSERT_EQ(again[p][k], first[i][p][k]);  // bit for bit
    ++checked;
    particles += again.size();
  }
  UnboundedMedium<D> alone(options<D>(density, 0));
  VecArray<D> one;
  alone.particles(cells[cells.size() / 3], one);
  ASSERT_EQ(one.size(), first[cells.size() / 3].size());
  for (std::size_t p = 0; p < one.size(); ++p) EXPECT_EQ(one[p], first[cells.size() / 3][p]);
  EXPECT_EQ(checked, cells.size());
  EXPECT_GT(particles, cells.size() * density / 2);
}

TEST(UnboundedMedium, SameParticlesWhateverTheOrderCellsAreMadeIn) {
  expect_same_whatever_the_order<1>(0.6, 400);
  expect_same_whatever_the_order<2>(0.25, 40);
  expect_same_whatever_the_order<2>(0.5, 30);  // near the table's end: long chains
  expect_same_whatever_the_order<3>(0.25, 12);
  expect_same_whatever_the_order<3>(0.5, 10);
}

// The medium is part of every unbounded run's history: these cells were drawn by the generator
// before its cells' seeding shared the mixing of their leading coordinates, which must leave
// every cell's stream, and so every particle, bit for bit as it was.
template <int D>
void expect_pinned(double candidate_density, const std::array<std::int64_t, D>& cell,
                   const std::vector<double>& coordinates) {
  UnboundedMedium<D> medium(candidate_density, 2.5, 7, 3);
  VecArray<D> out;
  medium.particles(cell, out);
  ASSERT_EQ(out.size() * D, coordinates.size());
  for (std::size_t i = 0; i < out.size(); ++i)
    for (int k = 0; k < D; ++k) EXPECT_EQ(out[i][k], coordinates[i * D + k]) << i << " " << k;
}

TEST(UnboundedMedium, CellsAreTheGeneratorsOfBefore) {
  expect_pinned<3>(0.4, {-9, 4, 17},
                   {-0x1.45dc0480ab4acp+4, 0x1.8de50ce67d8p+3, 0x1.5e894cf3c3ac1p+5,
                    -0x1.56625c106561fp+4, 0x1.75f67533e3af6p+3, 0x1.5cfa0ef73e2afp+5,
                    -0x1.4e51871437a7ap+4, 0x1.5e46bf1eedfbbp+3, 0x1.568fcedb80539p+5,
                    -0x1.43454a5f1319cp+4, 0x1.51f56092d92edp+3, 0x1.64f2163643f84p+5});
  expect_pinned<3>(0.4, {0, -1, 2},
                   {0x1.6efc3dde43142p-2, -0x1.319917d45f03cp+1, 0x1.b794da93806ecp+2,
                    0x1.20276c61996dp+1, -0x1.09274f9bc0edp+1, 0x1.97d00af1d6ebap+2,
                    0x1.21550fc4fd67cp+0, -0x1.106656b63da22p+0, 0x1.46ccf713c3888p+2});
  expect_pinned<2>(0.5, {5, -33},
                   {0x1.d545bbc802948p+3, -0x1.42565081554fbp+6, 0x1.b52ab1923e5bfp+3,
                    -0x1.4150f3547a66ap+6});
  expect_pinned<1>(0.5, {-300}, {-0x1.76c44cf9e823dp+9});
}

// A stream seeded through RngSeed key by key is the keyed constructor's stream.
TEST(UnboundedMedium, SharedSeedingIsTheKeyedStream) {
  const RngSeed base(11, 2, Stream::Medium);
  for (const std::array<std::int64_t, 3> key : {std::array<std::int64_t, 3>{0, 0, 0},
                                                {-1, 7, -123456789}, {1 << 30, -5, 3}}) {
    Rng keyed(11, 2, Stream::Medium, key), shared(base.then(key[0]).then(key[1]).then(key[2]));
    for (int i = 0; i < 8; ++i) EXPECT_EQ(keyed.next(), shared.next());
  }
  Rng plain(11, 2, Stream::Medium), unkeyed{base};
  EXPECT_EQ(plain.next(), unkeyed.next());
}

TEST(UnboundedMedium, OtherRealisationsAndCellSidesGiveOtherMedia) {
  UnboundedMedium<2> a(options<2>(0.25, 0)), b(options<2>(0.25, 1));
  auto o = options<2>(0.25, 0);
  o.cell_side = 1.5;
  UnboundedMedium<2> c(o);
  VecArray<2> xa, xb, xc;
  for (std::int64_t i = 0; i < 20; ++i) {
    a.particles({i, 0}, xa);
    b.particles({i, 0}, xb);
    c.particles({i, 0}, xc);
  }
  ASSERT_FALSE(xa.empty());
  EXPECT_FALSE(xa.size() == xb.size() && std::equal(xa.begin(), xa.end(), xb.begin()));
  EXPECT_FALSE(xa.size() == xc.size() && std::equal(xa.begin(), xa.end(), xc.begin()));
}

// All pairs closer than `r` (centres in a D-cube of side `side`, cells of side >= r).
template <int D>
std::size_t close_pairs(const VecArray<D>& x, double side, double r) {
  const int g = std::max(1, static_cast<int>(side / r));
  const double w = side / g;
  std::vector<std::vector<std::int32_t>> grid(static_cast<std::size_t>(std::pow(g, D)));
  auto index = [&](const Cell<D>& c) {
    std::size_t i = 0;
    for (int k = D - 1; k >= 0; --k) i = i * g + static_cast<std::size_t>(c[k]);
    return i;
  };
  auto cell_of = [&](const Vec<D>& p) {
    Cell<D> c;
    for (int k = 0; k < D; ++k)
      c[k] = std::clamp<std::int64_t>(static_cast<std::int64_t>(p[k] / w), 0, g - 1);
    return c;
  };
  for (std::size_t i = 0; i < x.size(); ++i)
    grid[index(cell_of(x[i]))].push_back(static_cast<std::int32_t>(i));
  std::size_t pairs = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const Cell<D> c = cell_of(x[i]);
    Cell<D> d;
    for (int k = 0; k < D; ++k) d[k] = -1;
    for (;;) {
      Cell<D> n;
      bool inside = true;
      for (int k = 0; k < D; ++k) {
        n[k] = c[k] + d[k];
        inside = inside && n[k] >= 0 && n[k] < g;
      }
      if (inside)
        for (const std::int32_t j : grid[index(n)])
          if (static_cast<std::size_t>(j) > i && (x[j] - x[i]).squaredNorm() < r * r) ++pairs;
      int k = 0;
      while (k < D && d[k] == 1) d[k] = -1, ++k;
      if (k == D) break;
      ++d[k];
    }
  }
  return pairs;
}

TEST(UnboundedMedium, NoOverlapsAcrossCells) {
  for (const double n : {0.25, 0.5}) {
    UnboundedMedium<1> m1(options<1>(n + 0.15, 2));
    UnboundedMedium<2> m2(options<2>(n, 2));
    UnboundedMedium<3> m3(options<3>(n, 2));
    const auto x1 = cube(m1, 3000);
    const auto x2 = cube(m2, 100);
    const auto x3 = cube(m3, 25);
    EXPECT_EQ(close_pairs(x1, 3000, 1.0), 0u);
    EXPECT_EQ(close_pairs(x2, 100, 1.0), 0u);
    EXPECT_EQ(close_pairs(x3, 25, 1.0), 0u);
    // The check itself sees pairs just beyond contact, which RSA has in plenty.
    EXPECT_GT(close_pairs(x2, 100, 1.1), 100u);
    EXPECT_GT(close_pairs(x3, 25, 1.1), 100u);
  }
}

// The medium is drawn in blocks of cells, found by floor division of the cell coordinates: cubes
// across the origin (blocks -1 and 0 meet there) and across other block edges have no overlaps
// either, and the particles of a cell are the same whether it is asked alone or with the cube.
TEST(UnboundedMedium, NoOverlapsAcrossTheOriginAndBlockEdges) {
  auto check = [](auto dim, int side, std::int64_t origin) {
    constexpr int D = decltype(dim)::value;
    UnboundedMedium<D> m(options<D>(0.45, 4));
    VecArray<D> x = cube(m, side, origin);
    for (Vec<D>& p : x) p -= Vec<D>::Constant(static_cast<double>(origin) * m.cell_side());
    EXPECT_EQ(close_pairs(x, side * m.cell_side(), 1.0), 0u) << D << "D from " << origin;
    EXPECT_GT(close_pairs(x, side * m.cell_side(), 1.1), 50u);
    UnboundedMedium<D> alone(options<D>(0.45, 4));
    const Cell<D> corner = cells_of_cube<D>(side, origin).front();
    VecArray<D> a, b;
    alone.particles(corner, a);
    m.particles(corner, b);
    EXPECT_EQ(a, b);
  };
  check(std::integral_constant<int, 1>{}, 2000, -1000);
  check(std::integral_constant<int, 2>{}, 60, -30);
  check(std::integral_constant<int, 2>{}, 40, -37);
  check(std::integral_constant<int, 3>{}, 20, -10);
  check(std::integral_constant<int, 3>{}, 14, -21);
}

TEST(UnboundedMedium, OneDimensionalMediumFollowsRenyi) {
  // 1D RSA has an exact density at every candidate density (Renyi 1958): the construction itself
  // is checked against it, without any table. 40 realisations of 20000 cells; the tolerance is
  // 4 standard errors of the mean over realisations.
  for (const double rho : {0.3, 1.0, 3.0}) {
    double sum = 0, sum2 = 0;
    const int m = 40;
    for (int r = 0; r < m; ++r) {
      UnboundedMedium<1> medium(rho, 1.0, 7, static_cast<std::uint64_t>(r));
      const double n = static_cast<double>(cube(medium, 20000).size()) / 20000.0;
      sum += n;
      sum2 += n * n;
    }
    const double mean = sum / m;
    const double se = std::sqrt((sum2 / m - mean * mean) / (m - 1));
    std::printf("1D rho %.1f: density %.5f +- %.5f, Renyi %.5f\n", rho, mean, se,
                renyi_density(rho));
    EXPECT_NEAR(mean, renyi_density(rho), 4 * se);
  }
  EXPECT_NEAR(renyi_density(60.0), 0.7476, 0.006);  // the jamming limit, approached as 1/rho
  EXPECT_NEAR(renyi_density(medium_candidate_density(1, 0.5)), 0.5, 1e-10);
}

TEST(UnboundedMedium, DensityIsTheBoxRunsDensity) {
  // 12 realisations of a cube; tolerance: 4 standard errors of the mean over realisations (the
  // table's own error, from 12 regions 4x to 16x larger, is below a third of that).
  auto check = [](auto dim, double target, int side) {
    constexpr int D = decltype(dim)::value;
    const int m = 12;
    double sum = 0, sum2 = 0;
    for (int r = 0; r < m; ++r) {
      UnboundedMedium<D> medium(options<D>(target, static_cast<std::uint64_t>(100 + r)));
      const double n = static_cast<double>(cube(medium, side).size()) / std::pow(side, D);
      sum += n;
      sum2 += n * n;
    }
    const double mean = sum / m;
    const double se = std::sqrt((sum2 / m - mean * mean) / (m - 1));
    std::printf("%dD target %.3f: density %.5f +- %.5f\n", D, target, mean, se);
    EXPECT_NEAR(mean, target, 4 * se) << D << "D";
  };
  check(std::integral_constant<int, 1>{}, 0.25, 40000);
  check(std::integral_constant<int, 2>{}, 0.25, 256);
  check(std::integral_constant<int, 2>{}, 0.45, 160);
  check(std::integral_constant<int, 3>{}, 0.25, 40);
  check(std::integral_constant<int, 3>{}, 0.5, 32);
}

TEST(UnboundedMedium, RefusesDensitiesOutsideItsCalibration) {
  EXPECT_THROW(medium_candidate_density(2, 0.6), UserError);
  EXPECT_THROW(medium_candidate_density(3, 0.0), UserError);
  EXPECT_THROW(medium_candidate_density(1, 0.75), UserError);
  EXPECT_THROW(UnboundedMedium<2>(1.0, 0.5, 1, 0), UserError);
}

// Structure of one sample: g(r) in bins of 0.1 from contact to 3, and the number variance in
// cubic windows of side 10 and 30 tiling the sample.
struct Structure {
  std::vector<double> g;
  double variance10 = 0, variance30 = 0;
};

constexpr double kBin = 0.1;
constexpr int kBins = 20;

template <int D>
double shell_volume(double r0, double r1) {
  if constexpr (D == 2) return std::numbers::pi * (r1 * r1 - r0 * r0);
  return 4.0 / 3.0 * std::numbers::pi * (r1 * r1 * r1 - r0 * r0 * r0);
}

// `periodic`: a box of side `side` (minimum image), else a region cut from the medium, whose
// centres for g(r) are those at least 3 from its faces.
template <int D>
Structure structure(const VecArray<D>& x, double side, bool periodic) {
  Structure s;
  s.g.assign(kBins, 0.0);
  const double n = static_cast<double>(x.size()) / std::pow(side, D);
  const double rmax = kBins * kBin + 1.0;
  const int g = static_cast<int>(side / rmax);
  const double w = side / g;
  std::vector<std::vector<std::int32_t>> grid(static_cast<std::size_t>(std::pow(g, D)));
  auto coords = [&](const Vec<D>& p) {
    std::array<int, D> c;
    for (int k = 0; k < D; ++k) c[k] = std::clamp(static_cast<int>(p[k] / w), 0, g - 1);
    return c;
  };
  auto index = [&](const std::array<int, D>& c) {
    std::size_t i = 0;
    for (int k = D - 1; k >= 0; --k) i = i * g + static_cast<std::size_t>(c[k]);
    return i;
  };
  for (std::size_t i = 0; i < x.size(); ++i)
    grid[index(coords(x[i]))].push_back(static_cast<std::int32_t>(i));
  double centres = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    bool inner = true;
    for (int k = 0; k < D; ++k) inner = inner && x[i][k] >= rmax && x[i][k] < side - rmax;
    if (!periodic && !inner) continue;
    centres += 1;
    const auto c = coords(x[i]);
    std::array<int, D> d;
    d.fill(-1);
    for (;;) {
      std::array<int, D> nb;
      bool ok = true;
      for (int k = 0; k < D; ++k) {
        nb[k] = c[k] + d[k];
        if (periodic) nb[k] = (nb[k] + g) % g;
        ok = ok && nb[k] >= 0 && nb[k] < g;
      }
      if (ok)
        for (const std::int32_t j : grid[index(nb)]) {
          if (static_cast<std::size_t>(j) == i) continue;
          Vec<D> dx = x[j] - x[i];
          if (periodic)
            for (int k = 0; k < D; ++k) dx[k] -= side * std::round(dx[k] / side);
          const int b = static_cast<int>((dx.norm() - 1.0) / kBin);
          if (b >= 0 && b < kBins) s.g[b] += 1;
        }
      int k = 0;
      while (k < D && d[k] == 1) d[k] = -1, ++k;
      if (k == D) break;
      ++d[k];
    }
  }
  for (int b = 0; b < kBins; ++b)
    s.g[b] /= centres * n * shell_volume<D>(1.0 + b * kBin, 1.0 + (b + 1) * kBin);
  auto variance = [&](int window) {
    const int per_axis = static_cast<int>(side) / window;
    std::vector<double> count(static_cast<std::size_t>(std::pow(per_axis, D)), 0.0);
    for (const auto& p : x) {
      std::size_t i = 0;
      for (int k = D - 1; k >= 0; --k)
        i = i * per_axis + static_cast<std::size_t>(std::min(static_cast<int>(p[k] / window),
                                                             per_axis - 1));
      count[i] += 1;
    }
    // The sample variance with k - 1: in the box, whose k windows hold exactly N, it estimates
    // the infinite-volume variance (the fixed total removes a fraction 1/k of it).
    double mean = 0, sq = 0;
    for (const double c : count) mean += c;
    mean /= static_cast<double>(count.size());
    for (const double c : count) sq += (c - mean) * (c - mean);
    return sq / static_cast<double>(count.size() - 1);
  };
  s.variance10 = variance(10);
  s.variance30 = variance(30);
  return s;
}

struct Estimate {
  double mean = 0, se = 0;
};

Estimate estimate(const std::vector<double>& v) {
  Estimate e;
  for (const double x : v) e.mean += x;
  e.mean /= static_cast<double>(v.size());
  double sq = 0;
  for (const double x : v) sq += (x - e.mean) * (x - e.mean);
  e.se = std::sqrt(sq / static_cast<double>(v.size() - 1) / static_cast<double>(v.size()));
  return e;
}

// The medium against the project's RSA in a periodic box of the same side, realisations of each.
// The errors are estimated from the spread over realisations, so they are themselves uncertain
// (by a quarter with 8 realisations) and z has a t-like tail: the limits are 6 per g(r) bin, a
// mean z^2 below 2.5 over the 20 bins (a box at density 0.30 against the medium at 0.25 gives a
// largest z of 8.9 and a mean z^2 of 11), and 4 per number variance. RSA to a fixed N and RSA
// to a fixed number of trials differ by a 1/N share of the box's count, far below these errors.
template <int D>
void compare_with_box(double density, int side, int m, double box_density) {
  std::vector<std::vector<double>> g_box(kBins), g_medium(kBins);
  std::vector<double> v10_box, v10_medium, v30_box, v30_medium;
  const auto n = static_cast<std::int64_t>(std::llround(box_density * std::pow(side, D)));
  for (int r = 0; r < m; ++r) {
    Rng rng(31, static_cast<std::uint64_t>(r), Stream::Positions);
    const auto box = structure<D>(random_sequential_addition<D>(n, side, rng), side, true);
    UnboundedMedium<D> medium(options<D>(density, static_cast<std::uint64_t>(200 + r)));
    const auto free = structure<D>(cube(medium, side), side, false);
    for (int b = 0; b < kBins; ++b) {
      g_box[b].push_back(box.g[b]);
      g_medium[b].push_back(free.g[b]);
    }
    v10_box.push_back(box.variance10);
    v10_medium.push_back(free.variance10);
    v30_box.push_back(box.variance30);
    v30_medium.push_back(free.variance30);
  }
  double chi2 = 0;
  for (int b = 0; b < kBins; ++b) {
    const Estimate a = estimate(g_box[b]), c = estimate(g_medium[b]);
    const double z = (c.mean - a.mean) / std::hypot(a.se, c.se);
    chi2 += z * z;
    if (b % 4 == 0 || std::abs(z) > 3)
      std::printf("%dD g(%.2f): box %.4f +- %.4f, medium %.4f +- %.4f (z %.2f)\n", D,
                  1.0 + (b + 0.5) * kBin, a.mean, a.se, c.mean, c.se, z);
    EXPECT_LT(std::abs(z), 6.0) << D << "D g(r) bin " << b;
  }
  std::printf("%dD g(r): mean z^2 %.2f over %d bins\n", D, chi2 / kBins, kBins);
  EXPECT_LT(chi2 / kBins, 2.5) << D << "D g(r)";
  for (const auto& [name, a, c] : {std::tuple{"10", estimate(v10_box), estimate(v10_medium)},
                                   std::tuple{"30", estimate(v30_box), estimate(v30_medium)}}) {
    const double z = (c.mean - a.mean) / std::hypot(a.se, c.se);
    std::printf("%dD number variance, window %s: box %.2f +- %.2f, medium %.2f +- %.2f (z %.2f)\n",
                D, name, a.mean, a.se, c.mean, c.se, z);
    EXPECT_LT(std::abs(z), 4.0) << D << "D number variance, window " << name;
  }
}

TEST(UnboundedMedium, StructureIsThatOfRsaInABox2D) { compare_with_box<2>(0.25, 180, 32, 0.25); }
TEST(UnboundedMedium, StructureIsThatOfRsaInABox3D) { compare_with_box<3>(0.25, 90, 8, 0.25); }

}  // namespace
}  // namespace gs
