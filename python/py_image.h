#pragma once
// The picture type the render and movie bindings share: an RGBA image and the PNG text chunks
// that say what it shows (time, d, N, r, ... as `grainshock render` writes them).
#include "render/image.h"
#include "render/png.h"

namespace gs::py {

struct PyImage {
  render::Image image;
  render::PngText text;
};

}  // namespace gs::py
