#pragma once
#include <cmath>
#include <vector>

namespace gs::test {

// Log-spaced times, `per_decade` samples per decade from t0 to t1: the grid synthetic time
// series of the analysis tests are sampled on.
inline std::vector<double> log_grid(double t0, double t1, int per_decade) {
  std::vector<double> t;
  const int n = int(std::lround(std::log10(t1 / t0) * per_decade));
  for (int i = 0; i <= n; ++i) t.push_back(t0 * std::pow(10.0, double(i) / per_decade));
  return t;
}

}  // namespace gs::test
