#include "render/inset.h"

#include <algorithm>

#include "sim/error.h"
#include "sim/observables.h"

namespace gs::render {

InsetData inset_profile(const Snapshot& band, double v_rms, int bins) {
  InsetData d;
  GS_CHECK(std::find(band.active.begin(), band.active.end(), 0) == band.active.end());
  if (band.size() == 0 || !band.has_velocity()) return d;
  const RadialProfile p = radial_profile(band, Binning{.bins = bins});
  d.scaled = v_rms > 0;
  const double k = d.scaled ? 1 / v_rms : 1;
  for (std::size_t b = 0; b + 1 < p.edges.size(); ++b) {
    d.r.push_back(0.5 * (p.edges[b] + p.edges[b + 1]));
    d.density.push_back(p.density[b]);
    d.speed.push_back(p.mean_speed[b] * k);
  }
  d.r_max = p.edges.back();
  return d;
}

}  // namespace gs::render
