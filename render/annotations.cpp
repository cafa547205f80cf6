#include "render/annotations.h"

#include <algorithm>
#include <cmath>

namespace gs::render {
namespace {

// The box's edges (2D: its rectangle) in a colour halfway from the background to the text,
// painted only on pixels of the bare background, so that the outline passes under every disc
// and never hides or tints a particle.
void outline_box(Image& img, const Scene& sc) {
  const Eigen::AlignedBox3d& b = *sc.box;
  const int corners = sc.dim == 3 ? 8 : 4;
  Rgb8 line;
  for (int k = 0; k < 3; ++k) line[k] = std::uint8_t((sc.palette.background[k] + sc.palette.text[k]) / 2);
  auto corner = [&](int c) {
    return Eigen::Vector3d((c & 1) ? b.max().x() : b.min().x(), (c & 2) ? b.max().y() : b.min().y(),
                           (c & 4) ? b.max().z() : b.min().z());
  };
  for (int a = 0; a < corners; ++a)
    for (int bit = 1; bit < corners; bit <<= 1) {
      if (a & bit) continue;  // each edge once, from its corner with the bit clear
      const auto p = sc.camera.to_pixel(corner(a)), q = sc.camera.to_pixel(corner(a | bit));
      if (!p || !q) continue;
      const double len = (*q - *p).norm();
      const int steps = std::max(1, int(std::ceil(2 * len)));
      for (int s = 0; s <= steps; ++s) {
        const Eigen::Vector2d at = *p + (*q - *p) * (double(s) / steps);
        const int x = int(std::floor(at.x())), y = int(std::floor(at.y()));
        if (x < 0 || y < 0 || x >= img.width || y >= img.height) continue;
        std::uint8_t* px = img.pixel(x, y);
        if (px[0] != sc.palette.background[0] || px[1] != sc.palette.background[1] ||
            px[2] != sc.palette.background[2])
          continue;
        for (int k = 0; k < 3; ++k) px[k] = line[k];
      }
    }
}

}  // namespace

Annotations annotate(Image& img, const Scene& sc, OverlayPainter& painter) {
  Annotations a;
  const Style& st = sc.style;
  const OverlayColours oc{sc.palette.text, sc.palette.background};
  const Colormap cmap = picture_colormap(st);
  if (sc.box) outline_box(img, sc);
  if (st.legend && !sc.legend.empty()) {  // the times of an overlay, or the particle types
    painter.legend(img, sc.legend, oc);
    const int w = painter.legend_width(img.width, img.height, sc.legend);
    a.panels.push_back({img.width - w, 0, img.width,
                        painter.legend_height(img.width, img.height, sc.legend.size())});
  }
  if (!sc.overlay) {
    if (st.colorbar) {
      a.colorbar = painter.colorbar(img, cmap, sc.range, st.scale, sc.bar_label, sc.bar_note, oc);
      a.panels.push_back({a.colorbar.panel_x0, 0, img.width, img.height});
    }
    if (st.time_label && !sc.time_text.empty()) a.panels.push_back(painter.top_left_label(img, sc.time_text, oc));
    if (sc.inset) {
      a.inset = painter.inset(img, *sc.inset, cmap, sc.range, st.scale, oc);
      a.panels.push_back(a.inset);
    }
  }
  // In 3D, the camera's half width is the visible half width at the orbit centre's distance.
  if (st.scale_bar)
    a.panels.push_back(
        painter.scale_bar(img, sc.camera.pixels_per_unit(), oc, a.inset.empty() ? -1 : a.inset.y0));
  return a;
}

}  // namespace gs::render
