#pragma once
// The q-quantile of sorted samples, linear between order statistics (type 7 of Hyndman & Fan,
// the default of R and NumPy): the one rule for every bootstrap interval and band quantile.
#include <cmath>
#include <span>

#include "sim/error.h"

namespace gs {

inline double sorted_quantile(std::span<const double> sorted, double q) {
  GS_CHECK(!sorted.empty());
  const double pos = q * double(sorted.size() - 1);
  const auto i = std::size_t(std::floor(pos));
  const double f = pos - double(i);
  return i + 1 < sorted.size() ? sorted[i] * (1 - f) + sorted[i + 1] * f : sorted[i];
}

}  // namespace gs
