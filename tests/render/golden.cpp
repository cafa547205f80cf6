#include "tests/render/golden.h"

#include <cstdlib>
#include <filesystem>

#include "render/image_compare.h"
#include "render/png.h"

namespace gs::test {

namespace fs = std::filesystem;

std::string check_golden(const render::Image& actual, const std::string& name) {
  const fs::path golden = fs::path(GRAINSHOCK_ASSETS_DIR) / "golden" / (name + ".png");
  if (const char* u = std::getenv("GRAINSHOCK_UPDATE_GOLDEN"); u && std::string(u) == "1") {
    fs::create_directories(golden.parent_path());
    render::write_png(golden.string(), actual, {{"Software", "grainshock golden"}}, 9);
    return "";
  }
  const fs::path out = fs::path(GRAINSHOCK_TEST_OUTPUT_DIR) / "golden";
  fs::create_directories(out);
  const std::string actual_path = (out / (name + ".actual.png")).string();
  if (!fs::exists(golden)) {
    render::write_png(actual_path, actual);
    return "no golden " + golden.string() + " (actual picture written to " + actual_path +
           "; create goldens with env GRAINSHOCK_UPDATE_GOLDEN=1 ctest -R RenderGolden)";
  }
  const render::Image expected = render::read_png(golden.string());
  const render::ImageComparison c = render::compare_images(expected, actual);
  if (c.match()) return "";
  const std::string diff_path = (out / (name + ".diff.png")).string();
  render::write_png(actual_path, actual);
  render::write_png(diff_path, render::diff_image(expected, actual));
  return "picture differs from " + golden.string() + ": " +
         (c.same_size ? "worst differing blob " + std::to_string(c.largest.pixels) + " px, mass " +
                            std::to_string(c.largest.mass) + " at x " +
                            std::to_string(c.largest.x0) + ", y " + std::to_string(c.largest.y0)
                      : std::string("sizes differ")) +
         "; actual: " + actual_path + ", diff: " + diff_path;
}

}  // namespace gs::test
