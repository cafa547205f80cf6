#pragma once
// What a picture shows, decided on the CPU without GL: the camera framing the snapshots, the
// particles that survive culling with their colours, and the data of the overlays. The Renderer
// draws a Scene; annotate() paints its overlays on the drawn image. Tests and measures (the edge
// contrast) read a Scene directly.
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "render/camera.h"
#include "render/colormap.h"
#include "render/inset.h"
#include "render/style.h"
#include "render/view.h"
#include "sim/snapshot.h"

namespace gs::render {

class OverlayPainter;

struct Palette {
  Rgb8 background, text, inactive;
};
Palette palette(Background b);
// The style's colormap as pictures use it: the part that stands out from the background
// (Colormap::against). Scenes, their overlays and measures of a picture take this one.
Colormap picture_colormap(const Style& style);

// One particle as drawn: centre relative to the camera origin (kept in double until then, so
// unwrapped coordinates far from 0 keep their precision on the GPU), radius, colour.
struct Sprite {
  float x, y, z, r;
  std::uint8_t rgba[4];
};
static_assert(sizeof(Sprite) == 20);

struct Scene {
  int dim = 2;
  Style style;
  Camera camera;
  Palette palette{};
  // Drawing order: 2D inactive particles first, so active discs lie on top; 3D nearest first
  // when occlusion culling is on.
  std::vector<Sprite> sprites;
  // Per sprite: its position on the colormap (0..1), NaN when not coloured by the field
  // (inactive particles, the multi-time overlay).
  std::vector<float> shade;
  double r_max = 0;                       // largest radius of the snapshots
  bool overlay = false;                   // several snapshots, one colour per time
  std::pair<double, double> range{0, 1};  // colour range used (single snapshot)
  double v_rms = 0;                       // scaled fields: the scale, shown beside the colour bar
  std::string bar_label;                  // colour bar title
  std::string bar_note;                   // under the colour bar ("v_rms = 0.0123"), may be empty
  std::string time_text;                  // top-left label
  std::vector<std::pair<Rgb8, std::string>> legend;  // overlay: colour and time
  std::optional<InsetData> inset;
  std::optional<Eigen::AlignedBox3d> box;  // the box outline to draw (Style::box_outline)
};

// Memory a scene's building fills and gives back, kept by a caller that builds one scene after
// another (the Renderer): a frame of 2.5e5 discs on fresh pages spent a sixth of its CPU time in
// page faults. The sprites and shades of a scene done with go back in `sprites` and `shade`.
struct SceneScratch {
  struct Piece {  // what a thread makes of its piece of the particles
    // Drawn below (inactive), and the rest: room for the whole piece, the first counts filled.
    std::vector<Sprite> under_sprites, sprites;
    std::vector<float> under_shade, shade;
    std::size_t under_count = 0, count = 0;
    std::vector<Eigen::Vector3d> band_x;
    std::vector<double> band_v;
  };
  std::vector<Piece> pieces;
  std::vector<double> values;  // the field's
  std::vector<Sprite> sprites;
  std::vector<float> shade;
};

// UserError for an unknown colormap, MIN >= MAX, a field the snapshot lacks or snapshots of
// different dimensions. The painter measures the overlays a fitted scene keeps clear of.
Scene build_scene(const std::vector<const Snapshot*>& snaps, const Style& style, const View& view,
                  OverlayPainter& painter, SceneScratch* scratch = nullptr);

// The colour of each snapshot in the multi-time overlay, and of each particle type (Okabe-Ito,
// safe for colour blindness; it repeats after 7).
Rgb8 overlay_colour(std::size_t index);
// Throws UsageError, naming the flag, unless the style's words and ranges make sense.
void check_style(const Style& style);

}  // namespace gs::render
