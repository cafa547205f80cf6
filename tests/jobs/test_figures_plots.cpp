// What the figures' scripts are drawn from, without pixels: the local-slope panels' y-range.
#include <gtest/gtest.h>

#include <cmath>

#include "jobs/figures_plots.h"

namespace gs::jobs {
namespace {

// A local slope on 20 points a decade over t = 10..1e3 that swings by +-amplitude before t = 100
// (the first collisions, a front quantised in shells) and sits near 1/3 after, with a band of
// +-0.02 around it.
ExponentFit noisy_early_slope(double amplitude) {
  ExponentFit e;
  e.theory = 1.0 / 3;
  for (int i = 0; i <= 40; ++i) {
    const double t = 10 * std::pow(10.0, i / 20.0);
    const double s = t < 100 ? 1.0 / 3 + amplitude * (i % 2 ? 1 : -1)
                             : 1.0 / 3 + 0.01 * std::sin(i);
    e.slope.t.push_back(t);
    e.slope.slope.push_back(s);
    e.slope.lo.push_back(s - 0.02);
    e.slope.hi.push_back(s + 0.02);
  }
  return e;
}

TEST(FiguresPlots, SlopeRangeFollowsTheLateSlopeNotTheEarlyNoise) {
  // Before, the range spanned the band's min and max over the last 1.5 decades, which here
  // holds the swings of +-3 (R_front in --full: an axis from -3 to 6 for a slope of 1/3).
  const auto [lo, hi] = slope_yrange(noisy_early_slope(3));
  EXPECT_LT(lo, 1.0 / 3 - 0.02);  // the band and the theory inside
  EXPECT_GT(hi, 1.0 / 3 + 0.02);
  EXPECT_GT(lo, 0.15);  // and none of the early swings
  EXPECT_LT(hi, 0.55);
}

TEST(FiguresPlots, SlopeRangeTakesInThePlateauFitAndTheTheory) {
  ExponentFit e = noisy_early_slope(0);
  e.theory = 0.5;  // far above the data: still on the axis
  e.fit.exponent = 0.3;
  e.fit.window = {1e2, 1e3};
  const auto [lo, hi] = slope_yrange(e);
  EXPECT_LT(lo, 0.3);
  EXPECT_GT(hi, 0.5);
  EXPECT_LT(hi - lo, 1.0);
}

TEST(FiguresPlots, SlopeRangeOfNoFiniteSlopeIsLeftToGnuplot) {
  ExponentFit e = noisy_early_slope(0);
  for (double& s : e.slope.slope) s = std::nan("");
  EXPECT_TRUE(std::isnan(slope_yrange(e).first));
  EXPECT_TRUE(std::isnan(slope_yrange(ExponentFit{}).first));
}

}  // namespace
}  // namespace gs::jobs
