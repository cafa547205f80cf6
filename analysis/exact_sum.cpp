#include "analysis/exact_sum.h"

#include <cmath>

#include "sim/error.h"

namespace gs {

void ExactSum::add(double x) {
  if (!std::isfinite(x)) {
    special_ += x;
    has_special_ = true;
    return;
  }
  std::size_t i = 0;
  for (double y : partials_) {
    if (std::fabs(x) < std::fabs(y)) std::swap(x, y);
    const double hi = x + y;
    const double lo = y - (hi - x);  // Fast-Two-Sum: exact since |x| >= |y|
    if (lo != 0) partials_[i++] = lo;
    x = hi;
  }
  GS_CHECK_MSG(std::isfinite(x), "exact sum overflowed");
  partials_.resize(i);
  partials_.push_back(x);
}

void ExactSum::add_product(double x, double y) {
  const double p = x * y;
  add(p);
  if (std::isfinite(p)) add(std::fma(x, y, -p));
}

void ExactSum::add(const ExactSum& other) {
  for (double p : other.partials_) add(p);
  if (other.has_special_) add(other.special_);
}

double ExactSum::value() const {
  if (has_special_) return special_;
  // Round the expansion once, as CPython's math.fsum does: add from the largest partial down
  // until the sum becomes inexact, then correct a half-way case using the sign of the rest.
  std::size_t n = partials_.size();
  if (n == 0) return 0.0;
  double hi = partials_[--n];
  double lo = 0;
  while (n > 0) {
    const double x = hi;
    const double y = partials_[--n];
    hi = x + y;
    const double yr = hi - x;
    lo = y - yr;
    if (lo != 0) break;
  }
  if (n > 0 && ((lo < 0 && partials_[n - 1] < 0) || (lo > 0 && partials_[n - 1] > 0))) {
    const double y = lo * 2;
    const double x = hi + y;
    const double yr = x - hi;
    if (y == yr) hi = x;
  }
  return hi;
}

}  // namespace gs
