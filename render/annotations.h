#pragma once
// The overlays of a scene painted on its drawn picture, on the CPU, so text, colour bar and inset
// come out identical on every driver.
#include <vector>

#include "render/image.h"
#include "render/overlay.h"
#include "render/scene.h"

namespace gs::render {

struct Annotations {
  BarRect colorbar;          // empty if none was drawn
  Rect inset;                // empty if none was drawn
  std::vector<Rect> panels;  // every overlay's panel, colour bar and inset included
};

Annotations annotate(Image& img, const Scene& scene, OverlayPainter& painter);

}  // namespace gs::render
