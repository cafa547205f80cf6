#pragma once
// Ensemble averages over realisations: mean and standard error per entry, with every sum kept
// exact (analysis/exact_sum.h). The result is therefore the same to the last bit whatever the
// order in which realisations arrive, however they were split over threads or cluster jobs and
// merged (docs/design.md: results do not depend on the split). This is stronger than reducing in
// realisation order and needs no buffering of early arrivals: memory is two exact sums per
// entry, independent of the number of realisations.
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "analysis/exact_sum.h"
#include "analysis/table.h"
#include "sim/histogram.h"
#include "sim/observables.h"

namespace gs {

// Mean and standard error of fixed-length arrays of numbers, one array per realisation.
class MeanAccumulator {
 public:
  explicit MeanAccumulator(std::size_t length = 0);
  std::size_t length() const { return sum_.size(); }
  std::uint64_t count() const { return count_; }
  void add(std::span<const double> values);  // values.size() == length()
  void merge(const MeanAccumulator& other);  // same length
  // Mean over realisations, correctly rounded.
  std::vector<double> mean() const;
  // Standard error of the mean, sqrt(sum (x - m)^2 / (M (M - 1))) with m = mean(), the sum of
  // squares computed exactly; NaN when fewer than two realisations.
  std::vector<double> standard_error() const;

 private:
  std::vector<ExactSum> sum_, sum_sq_;
  std::uint64_t count_ = 0;
};

// Averages the time series of realisations (each a Table such as timeseries.csv) on their shared
// time grid. Grid columns (those of `grid` that the tables have, e.g. t and t_paper) are copied
// and must agree bit for bit; every other column c is averaged into c (mean) and c_sem.
class EnsembleAverage {
 public:
  explicit EnsembleAverage(std::vector<std::string> grid = {"t", "t_paper"});
  // `source` names the realisation in error messages (a file or "realisation 7"). UserError if
  // the index was added before, or if columns, rows or the time grid differ from the first.
  void add(std::uint64_t realisation, const Table& table, const std::string& source);
  // Exact: the merged average equals the one of adding every realisation to one accumulator.
  void merge(const EnsembleAverage& other);
  std::uint64_t realisations() const { return indices_.size(); }
  const std::vector<std::uint64_t>& indices() const { return indices_; }  // sorted
  // Grid columns, then c and c_sem for each averaged column, in input order. Needs >= 1
  // realisation.
  Table result() const;

 private:
  void check_compatible(const Table& table, const std::string& source) const;
  void insert_index(std::uint64_t realisation, const std::string& source);

  std::vector<std::string> grid_request_;
  Table grid_;                         // grid columns of the first realisation
  std::vector<std::string> names_;     // all columns of the first realisation, in order
  std::vector<std::size_t> averaged_;  // indices into names_ of the averaged columns
  MeanAccumulator acc_;                // row-major: row * averaged_.size() + k
  std::vector<std::uint64_t> indices_;
  std::string first_;                  // the source of the first realisation, for messages
};

// The average of histograms with identical edges (P(R,t), P(v,t), packing distributions).
class HistogramAverage {
 public:
  void add(const Histogram& h, const std::string& source);  // UserError if the edges differ
  void merge(const HistogramAverage& other);
  std::uint64_t count() const { return acc_.count(); }
  // Mean densities on the common edges; samples and outside are summed over realisations.
  Histogram mean() const;
  std::vector<double> standard_error() const { return acc_.standard_error(); }

 private:
  std::vector<double> edges_;
  MeanAccumulator acc_;
  std::uint64_t samples_ = 0, outside_ = 0;
  std::string first_;  // the source of the first histogram, for messages
};

// The average of radial profiles with identical shells. Densities are averaged per shell; mean
// speed and mean radial velocity are ratios of summed sums to summed counts (particle-weighted),
// so a shell empty in some realisations is still defined by the others.
class ProfileAverage {
 public:
  void add(const RadialProfile& p, const std::string& source);  // UserError if the shells differ
  void merge(const ProfileAverage& other);
  std::uint64_t count() const { return density_.count(); }
  // density: mean over realisations; count: total; the means as described above.
  RadialProfile mean() const;
  std::vector<double> density_standard_error() const { return density_.standard_error(); }

 private:
  std::vector<double> edges_;
  MeanAccumulator density_;
  std::vector<ExactSum> speed_, radial_;
  std::vector<std::uint64_t> count_;
  std::string first_;  // the source of the first profile, for messages
};

}  // namespace gs
