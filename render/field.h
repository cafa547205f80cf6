#pragma once
// Per-particle values behind the colours, and the colour range they span.
#include <cstdint>
#include <utility>
#include <vector>

#include "render/style.h"
#include "sim/snapshot.h"

namespace gs::render {

// One value per particle. UserError (naming the missing data) if the snapshot lacks what the
// field needs. Radial velocity is measured from the centre of mass of the active particles.
std::vector<double> field_values(const Snapshot& s, Field f);

// Robust range: the [plo, phi] percentiles of values[i] with mask[i] set (positive ones only
// on a log scale); widened when empty or degenerate so that it is always lo < hi.
std::pair<double, double> auto_range(const std::vector<double>& values,
                                     const std::vector<std::uint8_t>& mask, Scale scale, double plo,
                                     double phi);

// Position of v within [lo, hi] on the scale, in [0, 1] (clamped).
double normalise(double v, std::pair<double, double> range, Scale scale);

}  // namespace gs::render
