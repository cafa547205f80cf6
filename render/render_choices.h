#pragma once
// The choices of `grainshock render` in the words its flags take (colour field, scale, framing,
// range, ...), checked and turned into a Style and a View. The command and the Python module's
// render() both go through here, so the same words draw the same pixels.
#include <optional>
#include <string>
#include <vector>

#include "render/camera.h"
#include "render/gl_context.h"
#include "render/style.h"
#include "render/view.h"
#include "sim/snapshot.h"

namespace gs::render {

struct RenderChoices {
  std::string colormap = "magma", colour_by = "auto", background = "light", scale = "auto";
  std::string framing = "fit", backend = "auto";
  std::vector<double> range, percentiles, centre;  // empty: not given
  bool no_colorbar = false, no_time = false, no_legend = false;
  bool inset = false, no_inset = false;
  // Filled by settle_for_snapshots(): what "auto" chose where the file left it no choice (a file
  // without velocities), for the command to say once; empty otherwise.
  std::string note;
  // Filled by settle_choices() from the words above; the fields without a word (range per frame,
  // show inactive, scale bar, msaa, font, width, height, zoom, the 3D camera) are set directly.
  Style style;
  View view;
  // 3D: the slab's thickness (0: none). Unset, a kick's snapshot gets kKickSlab: its shell is
  // hollow, so drawn whole it shows only its outer skin (the default of `movie` and of a run's
  // pictures too); others' files are drawn whole, as OVITO draws them until a Slice is added.
  std::optional<double> slab;
};

inline constexpr double kKickSlab = 6;
// The slab an unset --slab means for a file whose first frame is `first`: kKickSlab for a 3D
// kick's snapshot, none otherwise (`render` and `movie` alike).
double default_slab(const Snapshot& first);

// Checks every word and number before any file is read or GL context made (UserError naming
// the flag) and fills c.style and c.view from them; returns the GL backend asked for.
Backend settle_choices(RenderChoices& c);

// What depends on the snapshots drawn: the inset is on for a run's own snapshot (it names its
// seed) unless --no-inset, and one snapshot is coloured by the field `colour_by` names ("auto"
// decided by the first snapshot, a name it lacks refused naming `first_file`).
void settle_for_snapshots(RenderChoices& c, const std::vector<const Snapshot*>& snaps,
                          const std::string& first_file);

// 3D with a slab or clip: how many of the particles the picture would show the cut kept, as
// "the slab 6 thick through the centre kept 117 of 300 particles (--slab 0 draws all)"; empty when
// nothing was cut away. `cam` is the camera the picture was drawn with.
std::string cut_note(const Style& style, const Snapshot& s, const Camera& cam);

}  // namespace gs::render
