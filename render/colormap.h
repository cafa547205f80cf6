#pragma once
// A colormap maps t in [0, 1] to a colour. The perceptual ones come from matplotlib's tables,
// so a picture here matches one made in Python with the same name.
#include <array>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace gs::render {

using Rgb8 = std::array<std::uint8_t, 3>;

// An sRGB component in [0, 1] as linear light (IEC 61966-2-1): what a colour's luminance and a
// glTF colour (linear by the glTF 2.0 spec, section 3.9.2) take.
double srgb_to_linear(double u);

class Colormap {
 public:
  // viridis, inferno, magma, cividis, turbo or grey; anything else is a UserError listing these.
  static Colormap by_name(const std::string& name);
  static const std::vector<std::string>& names();

  // Linear interpolation between the table's entries; t is clamped to [0, 1], NaN gives 0.
  std::array<float, 3> at(double t) const;
  Rgb8 at8(double t) const;
  const std::string& name() const { return name_; }

  // The part of this map that stands out from `background`: each end is cut back to where its
  // luminance contrast ratio with the background ((L1 + 0.05) / (L2 + 0.05) of WCAG 2.1
  // relative luminances) reaches 1.5:1 (colormap.cpp says why not WCAG's 3:1). Magma's cream
  // end on white (1.1:1) would draw the fastest particles, the inner edge a picture is for, as
  // the least visible; and the antialiased rims of few-pixel discs in a light colour stay near
  // the map while those of dark ones leave it, so light regions weigh more in what the eye
  // (and render/contrast.h's measure) reads as particles. Magma on white keeps [0, 0.88], on the
  // dark background [0.23, 1]. at(0) and at(1) are then the ends of the part kept.
  Colormap against(Rgb8 background) const;
  // Where at(0) and at(1) lie on the full map.
  std::pair<double, double> span() const { return {lo_, hi_}; }

 private:
  Colormap(std::string name, const float (*table)[3]) : name_(std::move(name)), table_(table) {}
  std::array<float, 3> full(double t) const;  // on the whole map
  std::string name_;
  const float (*table_)[3];  // 256 entries, or nullptr for grey
  double lo_ = 0, hi_ = 1;   // the part of the map used
};

}  // namespace gs::render
