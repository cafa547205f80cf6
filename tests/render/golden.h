#pragma once
// Golden-image tests of the renderer: pictures compared with assets/golden/*.png by the rule of
// render/image_compare.h, the same code as `grainshock compare`.
//
// Regenerate the goldens after an intended change of the pictures:
//   env GRAINSHOCK_UPDATE_GOLDEN=1 ctest --test-dir build -R RenderGolden
// then look at assets/golden/*.png before committing them.
#include <string>

#include "render/image.h"

namespace gs::test {

// Compares `actual` with assets/golden/<name>.png. On mismatch writes <name>.actual.png and
// <name>.diff.png under GRAINSHOCK_TEST_OUTPUT_DIR/golden and returns a message naming them;
// returns "" on a match. With GRAINSHOCK_UPDATE_GOLDEN=1 writes the golden instead.
std::string check_golden(const render::Image& actual, const std::string& name);

}  // namespace gs::test
