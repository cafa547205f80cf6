#pragma once
// One frame of an HTML page (jobs/view_page.h): the particles `render` would draw for a snapshot,
// in the compact form a browser uploads as one buffer. Built from the same Scene as the PNG
// (render/scene.h), so a particle has the same colour on the page as in the picture.
#include <cstdint>
#include <string>
#include <vector>

#include "render/colormap.h"
#include "render/style.h"
#include "sim/snapshot.h"

namespace gs::render {

struct PageFrame {
  int dim = 2;
  std::size_t count = 0;  // particles drawn
  std::string label;      // "t = ...   t_paper = ..." or "step N", as the PNG's
  std::string source;     // the file (and frame) it was read from
  double t = 0, t_paper = 0;
  bool has_time = true, has_t_paper = false;
  std::int64_t step = -1;
  // Positions are stored as 16-bit fractions of [lo, hi] per axis (relative to `origin`, the
  // camera's centre, which is added back only for the hover panel); the largest error is
  // (hi - lo) / 2 / 65535 per axis, `error_diameters` of the largest diameter.
  double origin[3] = {0, 0, 0}, lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
  double error_diameters = 0;
  // What `render` frames (relative to origin): the active particles' centres, or all when none
  // are active, with the largest radius; 3D: the bounding sphere's radius about the origin.
  double fit_lo[3] = {0, 0, 0}, fit_hi[3] = {0, 0, 0}, r_max = 0, sphere = 0;
  bool uniform_radius = true;
  std::pair<double, double> range{0, 1};
  std::string bar_label, bar_note;
  bool colorbar = true;              // false for one colour (--color-by none)
  std::vector<std::string> columns;  // per-particle values shown on hover (speed first if any)
  std::vector<bool> column_exact;    // a column of whole numbers, stored as float32
  // Little-endian sections, each padded to 4 bytes: uint16 positions (x, y[, z] per particle),
  // uint8 colour (0..254: the colormap at k / 254; 255: the inactive grey), uint32 particle
  // index in the file, uint16 radius / r_max (only when radii differ), per column binary16 (half
  // float, 3 significant digits) or, for whole numbers, float32 (exact).
  std::string bytes;
};

// The colour of value k of PageFrame's colour byte: the colormap as pictures use it (against
// the background) at k / 254, and the palette's inactive grey at 255. 256 RGB triples.
std::vector<std::uint8_t> page_lut(const Style& style);

// `style` as settled for this snapshot (settle_for_snapshots); its colour bar, inset and
// occlusion culling are ignored (the page draws its own bar and all the particles).
PageFrame make_page_frame(const Snapshot& s, const Style& style);

}  // namespace gs::render
