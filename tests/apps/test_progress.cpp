// The progress line's ETA (apps/progress.h): extrapolated from the measured growth of the work.
#include <gtest/gtest.h>

#include <cmath>

#include "apps/progress.h"

namespace gs::app {
namespace {

TEST(Progress, SteadyRateGivesTheLinearEstimate) {
  // A quarter done after 10 s with no earlier sample: 30 s left.
  EXPECT_DOUBLE_EQ(Progress::eta(0, 0, 10, 0.25), 30);
  // Steady rate seen from a sample half-way: beta = 1, the same answer.
  EXPECT_NEAR(Progress::eta(5, 0.125, 10, 0.25), 30, 1e-9);
}

TEST(Progress, SlowingWorkIsFollowed) {
  // f = sqrt(wall / 20), as simulated time advances more and more slowly: done at 20 s, so 10 s
  // are left at 10 s, where the elapsed time scaled by t / t_max would say 4.1 s.
  EXPECT_NEAR(Progress::eta(5, std::sqrt(0.25), 10, std::sqrt(0.5)), 10, 1e-9);
  const double naive = 10 * (1 - std::sqrt(0.5)) / std::sqrt(0.5);
  EXPECT_LT(naive, 4.2);
}

TEST(Progress, NoEstimateWithoutProgress) {
  EXPECT_LT(Progress::eta(0, 0, 10, 0), 0);
  EXPECT_LT(Progress::eta(5, 0.5, 10, 1), 0);
  // Stalled over the last half: the steady rate since the start is all there is.
  EXPECT_DOUBLE_EQ(Progress::eta(5, 0.5, 10, 0.5), 10);
  // A figures job past its quick cases, 68% of realisations in 2 min and 70% in 4: beta 0.04
  // would say 1e4 hours are left; the steady rate since the start says 103 s.
  EXPECT_NEAR(Progress::eta(120, 0.68, 240, 0.70), 240 / 0.7 - 240, 1e-9);
  // beta 0.26 is still followed: 240 (1/0.6)^(1/0.263) - 240 = 1.6e3 s.
  EXPECT_NEAR(Progress::eta(120, 0.5, 240, 0.6), 240 * std::pow(1 / 0.6, 1 / 0.26303) - 240, 1);
}

}  // namespace
}  // namespace gs::app
