#include "tests/render/golden.h"

#include <cmath>
#include <cstdlib>
#include <filesystem>

#include "render/png.h"

namespace gs::test {

namespace fs = std::filesystem;

Comparison compare_images(const render::Image& actual, const render::Image& expected) {
  Comparison c;
  c.same_size = actual.width == expected.width && actual.height == expected.height;
  if (!c.same_size) return c;
  c.allowed = static_cast<long>(kDifferingFraction * actual.width * actual.height);
  for (int y = 0; y < actual.height; ++y)
    for (int x = 0; x < actual.width; ++x) {
      const auto* a = actual.pixel(x, y);
      const auto* e = expected.pixel(x, y);
      for (int k = 0; k < 3; ++k)
        if (std::abs(int(a[k]) - int(e[k])) > kChannelTolerance) {
          ++c.differing;
          break;
        }
    }
  return c;
}

render::Image diff_image(const render::Image& actual, const render::Image& expected) {
  render::Image d(actual.width, actual.height);
  for (int y = 0; y < actual.height; ++y)
    for (int x = 0; x < actual.width; ++x) {
      const auto* a = actual.pixel(x, y);
      auto* o = d.pixel(x, y);
      bool differs = true;
      if (x < expected.width && y < expected.height) {
        const auto* e = expected.pixel(x, y);
        differs = false;
        for (int k = 0; k < 3; ++k) differs |= std::abs(int(a[k]) - int(e[k])) > kChannelTolerance;
      }
      const int grey = (a[0] + a[1] + a[2]) / 3;
      o[0] = differs ? 255 : static_cast<std::uint8_t>(192 + grey / 4);
      o[1] = o[2] = differs ? 0 : static_cast<std::uint8_t>(192 + grey / 4);
      o[3] = 255;
    }
  return d;
}

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
  const Comparison c = compare_images(actual, expected);
  if (c.match()) return "";
  const std::string diff_path = (out / (name + ".diff.png")).string();
  render::write_png(actual_path, actual);
  render::write_png(diff_path, diff_image(actual, expected));
  return "picture differs from " + golden.string() + ": " +
         (c.same_size ? std::to_string(c.differing) + " pixels beyond the tolerance, " +
                            std::to_string(c.allowed) + " allowed"
                      : std::string("sizes differ")) +
         "; actual: " + actual_path + ", diff: " + diff_path;
}

}  // namespace gs::test
