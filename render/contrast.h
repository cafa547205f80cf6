#pragma once
// How well a picture shows the fast inner edge of the band (the measure the default colours were
// chosen by): take the coloured particle pixels, their centroid and 24 angular sectors around it;
// in each sector compare the points in the inner quarter of the sector's radial spread with those
// in its outer quarter. The inner quarter's mean colormap position (0..1) minus the outer
// quarter's, median over the sectors, is positive when the inner edge is drawn in higher colours.
#include <vector>

#include "render/colormap.h"
#include "render/image.h"
#include "render/overlay.h"

namespace gs::render {

struct ShadedPoint {
  double x = 0, y = 0;  // pixels (or any planar coordinates)
  double t = 0;         // colormap position, 0..1
};

// NaN when fewer than half of the sectors hold points in both quarters.
double edge_contrast(const std::vector<ShadedPoint>& points, int sectors = 24);

// The pixels of `img` whose colour lies within `tolerance` (RGB distance, 0..255 per channel)
// of the colormap, outside the `exclude` rectangles (the overlays' panels), each with the
// position of its nearest colormap colour. The tolerance absorbs a movie's compression; rims
// blended with the background fall outside it.
std::vector<ShadedPoint> shaded_pixels(const Image& img, const Colormap& cmap,
                                       const std::vector<Rect>& exclude, double tolerance = 40);

}  // namespace gs::render
