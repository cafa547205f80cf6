#include "analysis/ensemble_sums.h"

#include <cmath>

#include "sim/error.h"
#include "sim/format.h"

namespace gs {

EnsembleSums::EnsembleSums(const EnsembleSpec& spec) : spec_(spec) {
  for (double t : spec_.snapshot_times) {
    snaps_.emplace_back();
    snaps_.back().t = t;
  }
}

void EnsembleSums::add(const Realisation& r, const std::string& source) {
  if (r.snapshots.size() != snaps_.size())
    throw UserError(source + ": " + std::to_string(r.snapshots.size()) +
                    " snapshot times, the ensemble " + std::to_string(snaps_.size()));
  for (std::size_t k = 0; k < snaps_.size(); ++k)
    if (r.snapshots[k].t != snaps_[k].t)
      throw UserError(source + ": snapshot time " + format_number(r.snapshots[k].t) +
                      " is not the ensemble's " + format_number(snaps_[k].t));
  // Against the spec's own grid first, not only the first realisation read: one edited by hand
  // is then named itself, not the next one compared with it.
  const std::vector<double> grid = sample_times(spec_);
  if (r.timeseries.has("t")) {
    const std::vector<double>& t = r.timeseries.column("t");
    if (t.size() != grid.size())
      throw UserError(source + ": " + std::to_string(t.size()) + " rows, the ensemble's time grid " +
                      std::to_string(grid.size()));
    for (std::size_t k = 0; k < t.size(); ++k)
      if (t[k] != grid[k])
        throw UserError(source + ": row " + std::to_string(k + 1) + " has t = " +
                        format_number(t[k]) + ", the ensemble's time grid " +
                        format_number(grid[k]));
  }
  Curves c;
  for (std::size_t q = 0; q < kCurveColumns.size(); ++q)
    c[q] = r.timeseries.column(kCurveColumns[q]);
  series_.add(r.index, r.timeseries, source);  // checks index, columns and grid
  curves_.emplace(r.index, std::move(c));
  for (std::size_t k = 0; k < snaps_.size(); ++k) {
    const auto& m = r.snapshots[k];
    auto& s = snaps_[k];
    s.radius.add(m.radius, source);
    s.speed.add(m.speed, source);
    s.packing.add(m.packing, source);
    s.profile.add(m.profile, source);
    auto frac = [](const Histogram& h) {
      return h.samples ? double(h.outside) / double(h.samples) : 0.0;
    };
    const std::array<double, kSnapshotScalars.size()> v = {m.band.typical,
                                                           m.band.upper,
                                                           m.band.mean,
                                                           m.inner.correlation,
                                                           m.inner.ratio,
                                                           m.inner.inner_speed,
                                                           m.inner.outer_speed,
                                                           frac(m.radius),
                                                           frac(m.speed),
                                                           m.measures.front.radius,
                                                           m.measures.front.peak_density,
                                                           m.measures.densest_cell,
                                                           m.measures.local_median,
                                                           m.measures.local_upper,
                                                           m.measures.cell_small,
                                                           m.measures.cell_large,
                                                           m.measures.voronoi_median};
    s.scalars.add(v);
    if (!m.pressure.empty()) {
      if (s.pressure.count() == 0) s.pressure = MeanAccumulator(m.pressure.size());
      if (m.pressure.size() != s.pressure.length())
        throw UserError(source + ": " + std::to_string(m.pressure.size()) +
                        " pressure shells, the ensemble " + std::to_string(s.pressure.length()));
      s.pressure.add(m.pressure);
    }
  }
}

void EnsembleSums::merge(const EnsembleSums& other) {
  if (spec_identity(other.spec_) != spec_identity(spec_))
    throw UserError("the ensembles to merge were made with different physics or sampling");
  if (other.count() == 0) return;
  series_.merge(other.series_);  // UserError if a realisation is in both
  for (const auto& [k, c] : other.curves_) curves_.emplace(k, c);
  for (std::size_t k = 0; k < snaps_.size(); ++k) {
    auto& s = snaps_[k];
    const auto& o = other.snaps_[k];
    s.radius.merge(o.radius);
    s.speed.merge(o.speed);
    s.packing.merge(o.packing);
    s.profile.merge(o.profile);
    s.scalars.merge(o.scalars);
    if (o.pressure.count() == 0) continue;
    if (s.pressure.count() == 0)
      s.pressure = o.pressure;
    else if (s.pressure.length() == o.pressure.length())
      s.pressure.merge(o.pressure);
    else
      throw UserError("the ensembles to merge have pressure profiles of different shells");
  }
}

}  // namespace gs
