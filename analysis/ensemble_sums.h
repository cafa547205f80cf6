#pragma once
// The running sums of an ensemble: every realisation's time series and snapshot observables
// added into exact accumulators (analysis/ensemble.h), so that the result does not depend on
// which thread or which cluster job ran which realisation, nor on the order of merging.
//
// The curves the local slopes and fits bootstrap over (kCurveColumns) are also kept per
// realisation, keyed by index: ~6 x (samples on the grid) doubles each, a few kB.
#include <array>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "analysis/ensemble.h"
#include "analysis/realisation.h"

namespace gs {

// The time-series columns kept per realisation for bootstrapping local slopes and fits, in the
// order of EnsembleSums::Curves.
inline constexpr std::array<const char*, 10> kCurveColumns = {
    "active",          "energy",       "radius_rms",   "speed_rms",
    "collisions",      "front_radius", "radial_momentum", "kicked_displacement",
    "kicked_speed",    "kicked_collisions"};
// The per-snapshot scalars averaged over realisations (names of snapshot_scalars.csv).
inline constexpr std::array<const char*, 17> kSnapshotScalars = {
    "packing_typical",      "packing_upper",      "packing_mean",       "inner_correlation",
    "inner_outer_ratio",    "inner_speed",        "outer_speed",        "R_outside_fraction",
    "v_outside_fraction",   "front_radius",       "shell_peak_density", "packing_densest_cell",
    "packing_local_median", "packing_local_upper", "packing_cell5",     "packing_cell20",
    "packing_voronoi_median"};

class EnsembleSums {
 public:
  using Curves = std::array<std::vector<double>, kCurveColumns.size()>;
  struct SnapshotSums {
    double t = 0;
    HistogramAverage radius, speed, packing;
    ProfileAverage profile;
    MeanAccumulator scalars{kSnapshotScalars.size()};
    // The kinetic pressure profile (SnapshotMeasures::pressure) of the realisations that have
    // one (folders written before it was measured have none); length 0 until the first.
    MeanAccumulator pressure;
  };

  explicit EnsembleSums(const EnsembleSpec& spec);
  // UserError (naming `source`) if the realisation is held already or does not fit the spec.
  void add(const Realisation& r, const std::string& source);
  // UserError if the specs differ (spec_identity) or both hold a realisation.
  void merge(const EnsembleSums& other);

  const EnsembleSpec& spec() const { return spec_; }
  std::uint64_t count() const { return series_.realisations(); }
  const std::vector<std::uint64_t>& indices() const { return series_.indices(); }
  // Grid columns t, t_paper, then c and c_sem per column. Needs count() >= 1.
  Table timeseries() const { return series_.result(); }
  const std::vector<SnapshotSums>& snapshots() const { return snaps_; }
  const std::map<std::uint64_t, Curves>& curves() const { return curves_; }

 private:
  EnsembleSpec spec_;
  EnsembleAverage series_;
  std::vector<SnapshotSums> snaps_;
  std::map<std::uint64_t, Curves> curves_;
};

}  // namespace gs
