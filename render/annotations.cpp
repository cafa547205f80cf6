#include "render/annotations.h"

namespace gs::render {

Annotations annotate(Image& img, const Scene& sc, OverlayPainter& painter) {
  Annotations a;
  const Style& st = sc.style;
  const OverlayColours oc{sc.palette.text, sc.palette.background};
  const Colormap cmap = picture_colormap(st);
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
