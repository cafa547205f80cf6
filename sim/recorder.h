#pragma once
// Turns the state of a running simulation into rows of timeseries.csv. The columns are the
// design's contract: t, t_paper, active, energy, radius_rms, speed_rms, anisotropy (A of the
// active particles), collisions, events, overlaps, momentum (px, py, pz as d allows) and, for
// thermal starts, the pressure from the collision virial and the collision rate per particle, both
// averaged over the interval since the previous row.
#include <string>
#include <vector>

#include "sim/config.h"
#include "sim/engine.h"
#include "sim/state_stream.h"

namespace gs {

class Recorder {
 public:
  explicit Recorder(const PhysicsConfig& c);
  const std::vector<std::string>& columns() const { return columns_; }
  // The row of the simulation's state now, from its sample() (also handed back in `sample`, so
  // that a caller wanting more of it need not compute it again).
  std::vector<double> row(const Simulation& sim, Sample* sample = nullptr);
  // What the next row depends on beside the simulation: the previous row's time and sums.
  void save(StateWriter& out) const;
  void load(StateReader& in);

 private:
  PhysicsConfig config_;
  std::vector<std::string> columns_;
  double last_t_ = 0, last_virial_ = 0;
  std::int64_t last_collisions_ = 0;
};

// Sample times on a logarithmic grid anchored at t = 1 (per_decade points per decade, from t_min
// up to t_max, t_max included), so that runs of different lengths share their grid points.
std::vector<double> log_times(double t_min, double t_max, int per_decade);

// Every `dt` up to t_max, t_max included.
std::vector<double> linear_times(double dt, double t_max);

// The sorted union of time lists, with times closer than a relative 1e-12 merged.
std::vector<double> merge_times(std::vector<double> a, const std::vector<double>& b);

}  // namespace gs
