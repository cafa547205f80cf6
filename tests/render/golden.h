#pragma once
// Golden-image comparison shared by the renderer's tests.
//
// Rule: a pixel differs when any of R, G, B differs by more than 24 (of 255); two images match
// when they have the same size and at most 0.1% of their pixels differ. Why: llvmpipe's output
// moves with Mesa and LLVM versions and with the CPU's vector width (AVX2 vs AVX-512 change
// rounding and which edge pixels a triangle covers), so antialiased rims shift by a fraction of
// a pixel and by a few levels. Those changes touch rim pixels a little; the tolerance absorbs
// them. A real regression changes whole discs: the golden scenes draw discs of at least 5 px
// radius on 256x256 pictures, so one disc moved by its diameter changes >= 2 * 78 pixels and one
// disc recoloured changes ~78 pixels by far more than 24, both above the 65 pixels (0.1%)
// allowed; the comparator's own tests check exactly that.
//
// Regenerate the goldens after an intended change of the pictures:
//   env GRAINSHOCK_UPDATE_GOLDEN=1 ctest --test-dir build -R RenderGolden
// then look at assets/golden/*.png before committing them.
#include <string>

#include "render/image.h"

namespace gs::test {

struct Comparison {
  bool same_size = false;
  long differing = 0;  // pixels beyond the channel tolerance
  long allowed = 0;
  bool match() const { return same_size && differing <= allowed; }
};

inline constexpr int kChannelTolerance = 24;
inline constexpr double kDifferingFraction = 0.001;

Comparison compare_images(const render::Image& actual, const render::Image& expected);

// Differing pixels in red over a faded copy of the actual picture.
render::Image diff_image(const render::Image& actual, const render::Image& expected);

// Compares `actual` with assets/golden/<name>.png. On mismatch writes <name>.actual.png and
// <name>.diff.png under GRAINSHOCK_TEST_OUTPUT_DIR/golden and returns a message naming them;
// returns "" on a match. With GRAINSHOCK_UPDATE_GOLDEN=1 writes the golden instead.
std::string check_golden(const render::Image& actual, const std::string& name);

}  // namespace gs::test
