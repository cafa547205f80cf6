#include "render/inset.h"

#include <algorithm>

#include "sim/observables.h"

namespace gs::render {

InsetData inset_profile(const Snapshot& s, double v_rms, int bins) {
  InsetData d;
  if (std::find(s.active.begin(), s.active.end(), 1) == s.active.end() || !s.has_velocity())
    return d;
  // The profile reads the active particles several times: from their copy, a few per cent of
  // a big snapshot, the big arrays are read once (sim/observables.h).
  const RadialProfile p = radial_profile(active_subset(s), Binning{.bins = bins});
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
