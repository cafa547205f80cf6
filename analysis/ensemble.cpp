#include "analysis/ensemble.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include "sim/error.h"

namespace gs {

MeanAccumulator::MeanAccumulator(std::size_t length) : sum_(length), sum_sq_(length) {}

void MeanAccumulator::add(std::span<const double> values) {
  GS_CHECK_MSG(values.size() == length(), "array length differs from the accumulator's");
  for (std::size_t k = 0; k < values.size(); ++k) {
    sum_[k].add(values[k]);
    sum_sq_[k].add_product(values[k], values[k]);
  }
  ++count_;
}

void MeanAccumulator::merge(const MeanAccumulator& other) {
  GS_CHECK_MSG(other.length() == length(), "merging accumulators of different lengths");
  for (std::size_t k = 0; k < length(); ++k) {
    sum_[k].add(other.sum_[k]);
    sum_sq_[k].add(other.sum_sq_[k]);
  }
  count_ += other.count_;
}

std::vector<double> MeanAccumulator::mean() const {
  std::vector<double> m(length(), std::numeric_limits<double>::quiet_NaN());
  if (count_ == 0) return m;
  for (std::size_t k = 0; k < length(); ++k) m[k] = sum_[k].value() / double(count_);
  return m;
}

std::vector<double> MeanAccumulator::standard_error() const {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::vector<double> se(length(), nan);
  if (count_ < 2) return se;
  const auto m = mean();
  const double M = double(count_);
  for (std::size_t k = 0; k < length(); ++k) {
    if (!std::isfinite(m[k])) continue;
    // sum (x - m)^2 = S2 - 2 m S1 + M m^2, every product added exactly: no cancellation error.
    ExactSum e = sum_sq_[k];
    for (double p : sum_[k].partials()) e.add_product(-2 * m[k], p);
    const double sq = m[k] * m[k];
    const double sq_err = std::fma(m[k], m[k], -sq);
    e.add_product(M, sq);
    e.add_product(M, sq_err);
    const double ss = std::max(0.0, e.value());
    se[k] = std::sqrt(ss / (M * (M - 1)));
  }
  return se;
}

EnsembleAverage::EnsembleAverage(std::vector<std::string> grid) : grid_request_(std::move(grid)) {}

void EnsembleAverage::check_compatible(const Table& table, const std::string& source) const {
  // Either of the two may be the one changed: both are named.
  if (table.names != names_)
    throw UserError(source + ": columns differ from those of " + first_ +
                    " (one of the two is not as written)");
  if (table.rows() != grid_.rows())
    throw UserError(source + ": " + std::to_string(table.rows()) + " rows, " + first_ + " " +
                    std::to_string(grid_.rows()) + " (time grids must be shared)");
  for (std::size_t j = 0; j < grid_.names.size(); ++j) {
    const auto& a = grid_.columns[j];
    const auto& b = table.column(grid_.names[j]);
    if (std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) != 0)
      throw UserError(source + ": column '" + grid_.names[j] + "' differs from that of " + first_ +
                      " (time grids must be shared)");
  }
}

void EnsembleAverage::insert_index(std::uint64_t realisation, const std::string& source) {
  const auto it = std::lower_bound(indices_.begin(), indices_.end(), realisation);
  if (it != indices_.end() && *it == realisation)
    throw UserError(source + ": realisation " + std::to_string(realisation) +
                    " is already in the ensemble");
  indices_.insert(it, realisation);
}

void EnsembleAverage::add(std::uint64_t realisation, const Table& table,
                          const std::string& source) {
  if (indices_.empty()) {
    Table grid;
    std::vector<std::size_t> averaged;
    for (std::size_t j = 0; j < table.names.size(); ++j) {
      const auto& n = table.names[j];
      if (std::find(grid_request_.begin(), grid_request_.end(), n) != grid_request_.end())
        grid.add_column(n, table.columns[j]);
      else
        averaged.push_back(j);
    }
    if (grid.names.empty())
      throw UserError(source + ": no time column (expected one of the grid columns, e.g. 't')");
    names_ = table.names;
    grid_ = std::move(grid);
    averaged_ = std::move(averaged);
    acc_ = MeanAccumulator(table.rows() * averaged_.size());
    first_ = source;
  }
  check_compatible(table, source);
  insert_index(realisation, source);
  std::vector<double> flat(acc_.length());
  const std::size_t w = averaged_.size();
  for (std::size_t k = 0; k < w; ++k) {
    const auto& col = table.columns[averaged_[k]];
    for (std::size_t i = 0; i < col.size(); ++i) flat[i * w + k] = col[i];
  }
  acc_.add(flat);
}

void EnsembleAverage::merge(const EnsembleAverage& other) {
  if (other.indices_.empty()) return;
  if (indices_.empty()) {
    *this = other;
    return;
  }
  bool same = other.names_ == names_ && other.grid_.names == grid_.names &&
              other.grid_.rows() == grid_.rows();
  for (std::size_t j = 0; same && j < grid_.columns.size(); ++j)
    same = std::memcmp(other.grid_.columns[j].data(), grid_.columns[j].data(),
                       grid_.rows() * sizeof(double)) == 0;
  if (!same) throw UserError("merged ensembles have different columns or time grids");
  for (auto idx : other.indices_)
    if (std::binary_search(indices_.begin(), indices_.end(), idx))
      throw UserError("merged ensembles both hold realisation " + std::to_string(idx));
  for (auto idx : other.indices_) insert_index(idx, "merged ensemble");
  acc_.merge(other.acc_);
}

Table EnsembleAverage::result() const {
  GS_CHECK_MSG(!indices_.empty(), "ensemble average of no realisation");
  Table out = grid_;
  const auto m = acc_.mean();
  const auto se = acc_.standard_error();
  const std::size_t w = averaged_.size(), rows = grid_.rows();
  for (std::size_t k = 0; k < w; ++k) {
    std::vector<double> mc(rows), sc(rows);
    for (std::size_t i = 0; i < rows; ++i) {
      mc[i] = m[i * w + k];
      sc[i] = se[i * w + k];
    }
    out.add_column(names_[averaged_[k]], std::move(mc));
    out.add_column(names_[averaged_[k]] + "_sem", std::move(sc));
  }
  return out;
}

void HistogramAverage::add(const Histogram& h, const std::string& source) {
  if (acc_.count() == 0 && edges_.empty()) {
    edges_ = h.edges;
    acc_ = MeanAccumulator(h.values.size());
    first_ = source;
  } else if (h.edges != edges_) {
    throw UserError(source + ": histogram bins differ from those of " + first_ +
                    " (one of the two is not as written)");
  }
  acc_.add(h.values);
  samples_ += h.samples;
  outside_ += h.outside;
}

void HistogramAverage::merge(const HistogramAverage& other) {
  if (other.count() == 0) return;
  if (count() == 0) {
    *this = other;
    return;
  }
  if (other.edges_ != edges_) throw UserError("merged histograms have different bins");
  acc_.merge(other.acc_);
  samples_ += other.samples_;
  outside_ += other.outside_;
}

Histogram HistogramAverage::mean() const {
  Histogram h;
  h.edges = edges_;
  h.values = acc_.mean();
  h.samples = samples_;
  h.outside = outside_;
  return h;
}

void ProfileAverage::add(const RadialProfile& p, const std::string& source) {
  GS_CHECK(p.speed_sum.size() == p.count.size() && p.radial_velocity_sum.size() == p.count.size());
  if (count() == 0 && edges_.empty()) {
    edges_ = p.edges;
    density_ = MeanAccumulator(p.density.size());
    speed_.assign(p.count.size(), ExactSum());
    radial_.assign(p.count.size(), ExactSum());
    count_.assign(p.count.size(), 0);
    first_ = source;
  } else if (p.edges != edges_) {
    throw UserError(source + ": profile shells differ from those of " + first_ +
                    " (give a fixed binning for ensembles)");
  }
  density_.add(p.density);
  for (std::size_t b = 0; b < count_.size(); ++b) {
    speed_[b].add(p.speed_sum[b]);
    radial_[b].add(p.radial_velocity_sum[b]);
    count_[b] += p.count[b];
  }
}

void ProfileAverage::merge(const ProfileAverage& other) {
  if (other.count() == 0) return;
  if (count() == 0) {
    *this = other;
    return;
  }
  if (other.edges_ != edges_) throw UserError("merged profiles have different shells");
  density_.merge(other.density_);
  for (std::size_t b = 0; b < count_.size(); ++b) {
    speed_[b].add(other.speed_[b]);
    radial_[b].add(other.radial_[b]);
    count_[b] += other.count_[b];
  }
}

RadialProfile ProfileAverage::mean() const {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  RadialProfile p;
  p.edges = edges_;
  p.count = count_;
  p.density = density_.mean();
  for (std::size_t b = 0; b < count_.size(); ++b) {
    p.speed_sum.push_back(speed_[b].value());
    p.radial_velocity_sum.push_back(radial_[b].value());
    p.mean_speed.push_back(count_[b] ? p.speed_sum[b] / double(count_[b]) : nan);
    p.mean_radial_velocity.push_back(count_[b] ? p.radial_velocity_sum[b] / double(count_[b])
                                               : nan);
  }
  return p;
}

}  // namespace gs
