#pragma once
// How particles are coloured and what is drawn over them. Plain options; defaults follow the
// paper's Fig. 1 (active particles only, light background) with colour by speed added.
#include <optional>
#include <string>
#include <utility>

namespace gs::render {

// Per-particle quantity mapped through the colormap.
enum class Field { Speed, RadialVelocity, FirstCollision };
enum class Scale { Linear, Log };
enum class Background { Light, Dark };

struct Style {
  std::string colormap = "viridis";
  Field field = Field::Speed;
  Scale scale = Scale::Linear;
  // Fixed colour range; when absent, robust percentiles of the shown particles' values, so one
  // outlier (the kicked particle early on) does not wash out the picture.
  std::optional<std::pair<double, double>> range;
  double percentile_low = 1, percentile_high = 99;
  bool show_inactive = false;  // inactive particles in a faint neutral colour
  Background background = Background::Light;
  bool colorbar = true;
  bool time_label = true;
  bool scale_bar = false;     // a length in particle diameters (3D: at the centre's distance)
  bool legend = true;         // multi-snapshot overlay: one colour per time
  int msaa = 4;               // samples per pixel for 3D spheres (2D discs antialias in the shader)
  double splat_below_px = 2;  // 2D discs of smaller radius (pixels) are drawn on the CPU
  bool occlusion_cull = true;  // 3D: skip spheres hidden behind nearer ones (exact)
  std::string font = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";
};

// Parses the command-line words; UserError naming the word otherwise.
Field parse_field(const std::string& name);            // speed | radial-velocity | first-collision
Background parse_background(const std::string& name);  // light | dark
const char* field_label(Field f);

}  // namespace gs::render
