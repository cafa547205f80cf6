#include "render/inset.h"

#include <algorithm>

#include "sim/error.h"
#include "sim/observables.h"

namespace gs::render {

InsetData inset_profile(int dim, std::span<const Eigen::Vector3d> positions,
                        std::span<const double> speeds, bool scaled, int bins) {
  InsetData d;
  if (positions.empty()) return d;
  const RadialProfile p = speed_profile(dim, positions, speeds, Binning{.bins = bins});
  d.scaled = scaled;
  for (std::size_t b = 0; b + 1 < p.edges.size(); ++b) {
    d.r.push_back(0.5 * (p.edges[b] + p.edges[b + 1]));
    d.density.push_back(p.density[b]);
    d.speed.push_back(p.mean_speed[b]);
  }
  d.r_max = p.edges.back();
  return d;
}

InsetData inset_profile(const Snapshot& band, double v_rms, int bins) {
  GS_CHECK(std::find(band.active.begin(), band.active.end(), 0) == band.active.end());
  if (band.size() == 0 || !band.has_velocity()) return {};
  std::vector<double> speeds(band.size());
  for (std::size_t i = 0; i < speeds.size(); ++i)
    speeds[i] = v_rms > 0 ? band.velocity[i].norm() / v_rms : band.velocity[i].norm();
  return inset_profile(band.info.dim, band.position, speeds, v_rms > 0, bins);
}

}  // namespace gs::render
