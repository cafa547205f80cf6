#pragma once
// How particles are coloured and what is drawn over them. Plain options; defaults follow the
// paper's Fig. 1 (active particles only, light background) with colour by speed added.
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace gs::render {

// Per-particle quantity mapped through the colormap. The scaled ones divide by v_rms(t) of the
// active particles, the paper's scaling variable v t^(1-alpha) up to a constant (Figs. 4b, 5b):
// their distribution hardly moves with time, so one fixed range means one scaled speed in
// every frame of a movie. Column is a numeric per-particle column of the file (Style::column
// names it: LAMMPS c_pe, GSD charge, ...); Type colours by particle type (Snapshot::type) from a
// categorical palette with a legend of the type names; None draws every particle in one colour.
enum class Field {
  Speed,
  RadialVelocity,
  FirstCollision,
  ScaledSpeed,
  ScaledRadialVelocity,
  Column,
  Type,
  None
};
enum class Scale { Linear, Log };
enum class Background { Light, Dark };

// The most samples per pixel --msaa takes (check_style).
inline constexpr int kMaxMsaa = 64;

struct Style {
  // Magma on white, without its cream end (Colormap::against): black to light orange all
  // stand out from the background, and its colours differ in lightness, which a movie's 4:2:0
  // chroma subsampling keeps, where viridis's greens and yellows differ more in hue.
  std::string colormap = "magma";
  Field field = Field::Speed;
  std::string column;  // the Snapshot::columns name when field is Column
  Scale scale = Scale::Linear;
  // Fixed colour range; when absent, the field's default_range() for the scaled fields, else
  // robust percentiles of the shown particles' values, so one outlier (the kicked particle
  // early on) does not wash out the picture.
  std::optional<std::pair<double, double>> range;
  bool range_per_frame = false;  // percentiles even for a field with a default range
  double percentile_low = 1, percentile_high = 99;
  bool show_inactive = false;  // inactive particles in a faint neutral colour
  Background background = Background::Light;
  bool colorbar = true;
  std::string bar_label;  // the colour bar's title with its unit; empty: field_label's
  bool time_label = true;
  bool scale_bar = false;     // a length in particle diameters (3D: at the centre's distance)
  bool legend = true;         // multi-snapshot overlay: one colour per time
  bool inset = false;         // density and mean scaled speed against distance, bottom left
  // The periodic box's edges, in a faint line where no particle is drawn (a movie of a box
  // that moves, whose frames each show their own box in a camera that frames them all).
  bool box_outline = false;
  int msaa = 4;               // samples per pixel for 3D spheres (2D discs antialias in the shader)
  double splat_below_px = 2;  // 2D discs of smaller radius (pixels) are drawn on the CPU
  bool occlusion_cull = true;  // 3D: skip spheres hidden behind nearer ones (exact)
  std::string font = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";
};

// Parses the command-line words; UserError naming the word (and listing the fields) otherwise.
Field parse_field(const std::string& name);
Background parse_background(const std::string& name);  // light | dark
const char* field_name(Field f);                       // the command-line word
const char* field_label(Field f);                      // the colour bar's title
// Every field but Column (a name of the file's), in the order the help lists them.
const std::vector<Field>& all_fields();
bool is_scaled(Field f);
// --scale auto|lin|log: auto is log for plain speed and first-collision times (they span
// decades in a band), linear for the scaled and signed fields.
Scale parse_scale(const std::string& name, Field f);
bool needs_velocity(Field f);

// The fixed range of a scaled field: about the 5-95% span of the collapsed distribution, which
// is nearly the same at every time (see style.cpp for where the numbers come from).
std::optional<std::pair<double, double>> default_range(Field f, int dim);

}  // namespace gs::render
