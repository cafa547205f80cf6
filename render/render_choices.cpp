#include "render/render_choices.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "render/field.h"
#include "render/renderer.h"
#include "render/scene.h"
#include "sim/error.h"

namespace gs::render {

Backend settle_choices(RenderChoices& c) {
  Style& st = c.style;
  View& view = c.view;
  st.colormap = c.colormap;
  // An unknown field is reported once the snapshot is read, with the fields it has.
  for (Field f : all_fields())
    if (c.colour_by == field_name(f)) st.field = f;
  st.background = parse_background(c.background);
  st.scale = parse_scale(c.scale, st.field);
  if (!c.range.empty()) st.range = std::pair{c.range[0], c.range[1]};
  if (!c.percentiles.empty())
    st.percentile_low = c.percentiles[0], st.percentile_high = c.percentiles[1];
  st.colorbar = !c.no_colorbar;
  st.time_label = !c.no_time;
  st.legend = !c.no_legend;
  if (c.framing == "fit")
    view.framing = Framing::Fit;
  else if (c.framing == "box")
    view.framing = Framing::Box;
  else
    throw UsageError("unknown --framing '" + c.framing + "' (use fit or box)");
  if (!c.centre.empty())
    view.centre = Eigen::Vector3d(c.centre[0], c.centre[1], c.centre.size() > 2 ? c.centre[2] : 0);
  if (!(view.zoom > 0)) throw UsageError("--zoom must be positive");
  if (!(view.fov > 0 && view.fov < 180)) throw UsageError("--fov must be between 0 and 180");
  if (c.slab.value_or(0) < 0 || view.distance < 0)
    throw UsageError("--slab and --distance must be >= 0");
  if (c.slab) view.slab = *c.slab;
  if (c.inset && c.no_inset) throw UsageError("--inset and --no-inset exclude each other");
  check_size(view.width, view.height);
  check_style(st);
  return parse_backend(c.backend);
}

double default_slab(const Snapshot& first) {
  return first.info.dim == 3 && default_field(first) == Field::ScaledSpeed ? kKickSlab : 0;
}

void settle_for_snapshots(RenderChoices& c, const std::vector<const Snapshot*>& snaps,
                          const std::string& first_file) {
  Style& st = c.style;
  st.inset = c.inset || (!c.no_inset && snaps.front()->info.seed.has_value());
  // The unbounded medium's box is the engine's addressable region, 4 times the side of the box
  // of its --particles and almost all of it never made: framed whole, the band is a dot.
  if (c.view.framing == Framing::Box)
    for (const Snapshot* s : snaps)
      if (s->info.unbounded)
        throw UserError("--framing box: " + (snaps.size() == 1 ? first_file : "a snapshot") +
                        " is of the unbounded medium, which has no box (its Lattice is only the "
                        "region the engine addresses); use --framing fit");
  if (!c.slab) c.view.slab = default_slab(*snaps.front());
  if (snaps.size() == 1) {
    st.field = choose_field(c.colour_by, *snaps.front(), first_file, &c.note);
    if (st.field == Field::Column) st.column = c.colour_by;
    st.scale = parse_scale(c.scale, st.field);
    check_style(st);
  }
}

std::string cut_note(const Style& style, const Snapshot& s, const Camera& cam) {
  if (s.info.dim != 3 || !(cam.slab > 0 || cam.clip)) return {};
  // The particles the picture shows without the cut: the active ones (all when none is, or with
  // --show-inactive), as the scene draws them.
  const bool all = style.show_inactive || std::none_of(s.active.begin(), s.active.end(),
                                                       [](std::uint8_t a) { return a != 0; });
  std::size_t shown = 0, kept = 0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (!all && !s.active[i]) continue;
    ++shown;
    const double cut = (s.position[i] - cam.cut_origin).dot(cam.forward);
    kept += !(cam.slab > 0 && std::abs(cut) > cam.slab / 2) && !(cam.clip && cut < 0);
  }
  if (kept == shown) return {};
  char slab[64];
  std::snprintf(slab, sizeof slab, "%g", cam.slab);
  return std::string(cam.slab > 0 ? "the slab " + std::string(slab) + " thick" : "the clip") +
         " through the centre kept " + std::to_string(kept) + " of " + std::to_string(shown) +
         " particles" + (cam.slab > 0 ? " (--slab 0 draws all)" : "");
}

}  // namespace gs::render
