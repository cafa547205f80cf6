#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>

#include "analysis/ensemble.h"
#include "sim/error.h"
#include "sim/rng.h"

namespace gs {
namespace {

TEST(ExactSum, IsExactAndOrderIndependent) {
  ExactSum a;
  for (double x : {1e100, 1.0, -1e100}) a.add(x);
  EXPECT_EQ(a.value(), 1.0);  // naive left-to-right summation gives 0
  ExactSum b;
  for (int i = 0; i < 10; ++i) b.add(0.1);
  EXPECT_EQ(b.value(), 1.0);  // the correctly rounded sum; naive gives 0.9999999999999999

  Rng rng(5, 0, Stream::Positions);
  std::vector<double> x(5000);
  for (auto& v : x) v = std::ldexp(rng.normal(), int(rng.below(120)) - 60);
  ExactSum forward, backward, chunked;
  for (double v : x) forward.add(v);
  for (auto it = x.rbegin(); it != x.rend(); ++it) backward.add(*it);
  ExactSum part[3];
  for (std::size_t i = 0; i < x.size(); ++i) part[i % 3].add(x[i]);
  chunked.add(part[2]);
  chunked.add(part[0]);
  chunked.add(part[1]);
  EXPECT_EQ(forward.value(), backward.value());
  EXPECT_EQ(forward.value(), chunked.value());
  // A plain double sum of these numbers depends on the order: the test data must be hard enough.
  const double naive_f = std::accumulate(x.begin(), x.end(), 0.0);
  const double naive_b = std::accumulate(x.rbegin(), x.rend(), 0.0);
  EXPECT_NE(naive_f, naive_b);
}

Table realisation(std::uint64_t k, std::size_t rows) {
  Rng rng(11, k, Stream::Positions);
  Table t;
  std::vector<double> time(rows), paper(rows), active(rows), energy(rows);
  for (std::size_t i = 0; i < rows; ++i) {
    time[i] = 0.5 * double(i);
    paper[i] = time[i] * std::sqrt(0.25);
    active[i] = std::floor(1 + 10 * std::pow(time[i], 2.0 / 3.0) * (1 + 0.1 * rng.normal()));
    energy[i] = std::pow(1 + time[i], -2.0 / 3.0) * std::exp(0.3 * rng.normal());
  }
  t.add_column("t", time);
  t.add_column("t_paper", paper);
  t.add_column("active", active);
  t.add_column("energy", energy);
  return t;
}

TEST(Ensemble, ChunkedEqualsOneShotByteForByte) {
  constexpr std::uint64_t M = 23;
  EnsembleAverage one;
  for (std::uint64_t k = 0; k < M; ++k) one.add(k, realisation(k, 200), "r");
  // Three "threads" or "jobs" holding interleaved, shuffled subsets, merged in another order.
  EnsembleAverage part[3];
  std::vector<std::uint64_t> order(M);
  std::iota(order.begin(), order.end(), 0);
  std::reverse(order.begin(), order.end());
  for (auto k : order) part[k % 3 == 0 ? 0 : (k < 12 ? 1 : 2)].add(k, realisation(k, 200), "r");
  EnsembleAverage merged;
  merged.merge(part[2]);
  merged.merge(part[0]);
  merged.merge(part[1]);
  EXPECT_EQ(merged.realisations(), M);
  EXPECT_EQ(to_csv(merged.result()), to_csv(one.result()));

  // And the numbers are the mean and standard error, checked against a two-pass long double sum.
  const Table r = one.result();
  EXPECT_EQ(r.names, (std::vector<std::string>{"t", "t_paper", "active", "active_sem", "energy",
                                               "energy_sem"}));
  for (std::size_t i = 0; i < 200; i += 37) {
    long double s = 0;
    for (std::uint64_t k = 0; k < M; ++k) s += realisation(k, 200).column("energy")[i];
    const long double m = s / M;
    long double ss = 0;
    for (std::uint64_t k = 0; k < M; ++k) {
      const long double d = realisation(k, 200).column("energy")[i] - m;
      ss += d * d;
    }
    // Tolerance: the library rounds the exact sums once; the long double reference carries
    // ~1e-18 relative error, so agreement to 1e-15 relative (a few ulps) is expected.
    EXPECT_NEAR(r.column("energy")[i], double(m), 1e-15 * double(m));
    EXPECT_NEAR(r.column("energy_sem")[i], double(std::sqrt(ss / (M * (M - 1)))),
                1e-14 * double(std::sqrt(ss / (M * (M - 1)))));
  }
}

TEST(Ensemble, RejectsMismatchedRealisations) {
  EnsembleAverage e;
  e.add(0, realisation(0, 50), "r0");
  EXPECT_THROW(e.add(0, realisation(0, 50), "r0 again"), UserError);  // same index twice
  EXPECT_THROW(e.add(1, realisation(1, 49), "short"), UserError);     // other grid length
  Table shifted = realisation(2, 50);
  shifted.column("t")[3] += 1e-9;
  EXPECT_THROW(e.add(2, shifted, "shifted"), UserError);  // other time grid
  Table renamed = realisation(3, 50);
  renamed.names[2] = "collisions";
  EXPECT_THROW(e.add(3, renamed, "renamed"), UserError);
  EXPECT_EQ(e.realisations(), 1u);  // nothing was taken from the rejected ones
  EnsembleAverage other;
  other.add(0, realisation(0, 50), "r0");
  EXPECT_THROW(e.merge(other), UserError);  // both hold realisation 0
  Table no_time;
  no_time.add_column("energy", {1, 2});
  EnsembleAverage f;
  EXPECT_THROW(f.add(0, no_time, "no time"), UserError);
}

TEST(Ensemble, HistogramAverage) {
  HistogramAverage a, b, c;
  Rng rng(2, 0, Stream::Positions);
  for (int k = 0; k < 9; ++k) {
    std::vector<double> x(300);
    for (auto& v : x) v = std::fabs(rng.normal());
    const Histogram h = make_histogram(x, {.bins = 20, .lo = 0, .hi = 4});
    a.add(h, "h");
    (k < 4 ? b : c).add(h, "h");
  }
  c.merge(b);
  EXPECT_EQ(a.mean().values, c.mean().values);
  EXPECT_EQ(a.standard_error(), c.standard_error());
  // The mean of normalised histograms is normalised up to the samples outside [0, 4]; tolerance
  // 1e-12 is round-off of 20 terms, and the outside fraction is known exactly.
  const Histogram m = a.mean();
  EXPECT_NEAR(m.integral(), 1.0 - double(m.outside) / double(m.samples), 1e-12);
  EXPECT_THROW(a.add(make_histogram(std::vector<double>{1.0}, {.bins = 21, .lo = 0, .hi = 4}), "h"),
               UserError);
}

TEST(Ensemble, ProfileAverageWeighsParticlesNotRealisations) {
  // Realisation A: 10 particles at R ~ 1 with speed 1; realisation B: 30 at R ~ 1 with speed 3
  // and 5 at R ~ 3 with speed 2. Shell [0, 2): particle-weighted mean speed (10 + 90) / 40 = 2.5
  // (a mean of per-realisation means would give 2); shell [2, 4) is empty in A, 2 from B alone.
  auto make = [](int n_in, double v_in, int n_out, double v_out) {
    Snapshot s;
    s.info.dim = 2;
    auto ring = [&](int n, double R, double v) {
      for (int i = 0; i < n; ++i) {
        const Eigen::Vector3d u(std::cos(6.283185307179586 * i / n),
                                std::sin(6.283185307179586 * i / n), 0);
        s.position.push_back(R * u);
        s.velocity.push_back(v * u);
        s.active.push_back(1);
      }
    };
    ring(n_in, 1, v_in);
    if (n_out) ring(n_out, 3, v_out);
    return radial_profile(s, {.bins = 2, .lo = 0, .hi = 4});
  };
  ProfileAverage a, b;
  a.add(make(10, 1, 0, 0), "A");
  b.add(make(30, 3, 5, 2), "B");
  a.merge(b);
  const RadialProfile m = a.mean();
  // Tolerances: a handful of exact sums of symmetric rings; round-off only.
  EXPECT_NEAR(m.mean_speed[0], 2.5, 1e-12);
  EXPECT_NEAR(m.mean_speed[1], 2.0, 1e-12);
  EXPECT_NEAR(m.mean_radial_velocity[1], 2.0, 1e-12);
  EXPECT_EQ(m.count[0], 40u);
  EXPECT_NEAR(m.density[1], 0.5 * 5 / (3.141592653589793 * 12), 1e-12);
  // Other shells (a realisation binned on its own range) cannot be averaged in.
  Snapshot other;
  other.info.dim = 2;
  other.position = {Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(-1, 0, 0)};
  other.velocity = {Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(-1, 0, 0)};
  EXPECT_THROW(a.add(radial_profile(other), "C"), UserError);
}

}  // namespace
}  // namespace gs
