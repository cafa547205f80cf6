#pragma once
// Per-particle values behind the colours, and the colour range they span.
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "render/style.h"
#include "sim/snapshot.h"

namespace gs::render {

// One value per particle. UserError (naming the missing data) if the snapshot lacks what the
// field needs. Radial velocity is measured from the centre of mass of the active particles.
// The scaled fields divide by v_rms of the active particles (of the moving ones before the
// first collision), which goes to *v_rms when asked for (0 for the other fields). Column takes
// the snapshot's column of that name; None gives 0.5 for every particle.
std::vector<double> field_values(const Snapshot& s, Field f, double* v_rms = nullptr,
                                 const std::string& column = {});
// The same into `v`, whose memory a caller drawing frame after frame keeps.
void field_values(const Snapshot& s, Field f, double* v_rms, const std::string& column,
                  std::vector<double>& v);

// scaled-speed for a gas disturbed at rest (a kick: a file ours marks so, SnapshotInfo::kick,
// or one where some particles have never moved), speed otherwise (a thermal gas, where v_rms is the temperature's and plain speeds read directly);
// without velocities, type where the file names types (OVITO's default), else none.
Field default_field(const Snapshot& s);

// The fields this snapshot can be coloured by (speeds need velocities, first-collision its column).
std::vector<Field> available_fields(const Snapshot& s);
// --color-by NAME for the snapshot read from `file`: "auto" is default_field(), a field's name
// that field, else the name of one of the snapshot's columns (Field::Column: the column is
// NAME; a field's name wins over a column's). UserError naming the file and listing what the
// snapshot can be coloured by (available_fields() and its columns) for an unknown name or one
// the snapshot lacks data for.
// "auto" for a snapshot without velocities is type where it has types, else none; `note` (if
// given) then gets the sentence that says so, for the command's log.
Field choose_field(const std::string& name, const Snapshot& s, const std::string& file,
                   std::string* note = nullptr);

// Robust range: the [plo, phi] percentiles of values[i] with mask[i] set (positive ones only
// on a log scale); widened when empty or degenerate so that it is always lo < hi.
std::pair<double, double> auto_range(const std::vector<double>& values,
                                     const std::vector<std::uint8_t>& mask, Scale scale, double plo,
                                     double phi);

// Position of v within [lo, hi] on the scale, in [0, 1] (clamped).
double normalise(double v, std::pair<double, double> range, Scale scale);

}  // namespace gs::render
