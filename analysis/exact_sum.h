#pragma once
// Exact summation of doubles (Shewchuk 1997, "Adaptive precision floating-point arithmetic and
// fast robust geometric predicates"; the algorithm of Python's math.fsum): the running sum is
// kept as a list of non-overlapping partials that represents it without error, and value()
// rounds it once. The result is the correctly rounded exact sum, so it does not depend on the
// order of the additions or on how they were grouped: an ensemble split over threads or jobs and
// merged gives the same bits as the one-shot ensemble.
#include <vector>

namespace gs {

class ExactSum {
 public:
  void add(double x);
  // x * y exactly, as the rounded product plus its error (an FMA recovers the error).
  void add_product(double x, double y);
  void add(const ExactSum& other);
  // The exact sum rounded to nearest, ties to even. Infinities and NaNs propagate as in an
  // ordinary sum.
  double value() const;
  // The partials, for multiplying the whole sum exactly.
  const std::vector<double>& partials() const { return partials_; }

 private:
  std::vector<double> partials_;  // increasing magnitude, non-overlapping
  double special_ = 0;            // sum of the non-finite inputs
  bool has_special_ = false;
};

}  // namespace gs
