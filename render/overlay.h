#pragma once
// Annotations drawn over the rendered scene on the CPU: colour bar, time label, legend of the
// multi-time overlay, scale bar. Sizes follow the picture's smaller side so a thumbnail and a
// 4K frame look alike.
#include <string>
#include <utility>
#include <vector>

#include "render/colormap.h"
#include "render/image.h"
#include "render/inset.h"
#include "render/style.h"
#include "render/text.h"

namespace gs::render {

// Tick values for a colour bar over [lo, hi]: "nice" steps on a linear scale, decades (with 2
// and 5 when the range is short) on a log scale.
std::vector<double> colorbar_ticks(double lo, double hi, Scale scale);
// Shortest of %.3g-style text for a tick value.
std::string tick_text(double v);

struct OverlayColours {
  Rgb8 text;   // text and frames
  Rgb8 panel;  // translucent backing that keeps text legible over particles
};

// A pixel rectangle, inclusive-exclusive.
struct Rect {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  bool empty() const { return x1 <= x0 || y1 <= y0; }
};

// Where the colour bar was drawn, for tests: the gradient's pixel rectangle.
struct BarRect {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;  // inclusive-exclusive, y0 at the top (high end)
  int panel_x0 = 0;                    // left edge of the panel behind bar, ticks and title
};

class OverlayPainter {
 public:
  explicit OverlayPainter(const std::string& font_path) : font_(font_path) {}

  // `note` (may be empty) goes under the bar, e.g. the v_rms of a scaled field.
  BarRect colorbar(Image& img, const Colormap& cmap, std::pair<double, double> range, Scale scale,
                   const std::string& label, const std::string& note, const OverlayColours& c);
  // Pixels the colour bar's panel takes from the right edge, so a fitted scene can keep clear.
  int colorbar_width(int width, int height, std::pair<double, double> range, Scale scale,
                     const std::string& label, const std::string& note);
  // Returns the label's panel.
  Rect top_left_label(Image& img, const std::string& text, const OverlayColours& c);
  Rect top_left_label_panel(int width, int height, const std::string& text);  // where it goes
  // A small plot in the bottom-left corner: density as grey shells (left axis), mean speed as
  // dots in their colormap colour (right axis, the colour bar's mapping) against distance.
  int inset_width(int width, int height);  // pixels from the left edge the inset's panel takes
  Rect inset_panel(int width, int height);  // where it goes
  Rect inset(Image& img, const InsetData& d, const Colormap& cmap, std::pair<double, double> range,
             Scale scale, const OverlayColours& c);
  void legend(Image& img, const std::vector<std::pair<Rgb8, std::string>>& entries,
              const OverlayColours& c);
  int legend_width(int width, int height, const std::vector<std::pair<Rgb8, std::string>>& entries);
  int legend_height(int width, int height, std::size_t entries);
  // A bar of a round length in particle diameters, bottom left, above `below_top` if given.
  Rect scale_bar(Image& img, double pixels_per_unit, const OverlayColours& c, int below_top = -1);
  Rect scale_bar_panel(int width, int height, double pixels_per_unit, int below_top = -1);

 private:
  struct BarLayout {
    int u = 0, tick_len = 0, gap = 0, right = 0, title_base = 0, title_x = 0, panel_x0 = 0;
    int note_base = 0;
    BarRect bar;
    std::vector<double> ticks;
  };
  BarLayout layout(int width, int height, std::pair<double, double> range, Scale scale,
                   const std::string& label, const std::string& note);
  int unit(int width, int height);  // sets and returns the font's pixel size
  Font font_;
};

// Alpha-blends a solid rectangle (clipped to the image).
void fill_rect(Image& img, int x0, int y0, int x1, int y1, Rgb8 colour, float alpha = 1);
// A straight line `width` pixels thick.
void draw_line(Image& img, double x0, double y0, double x1, double y1, Rgb8 colour,
               double width = 1);

}  // namespace gs::render
