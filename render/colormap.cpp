#include "render/colormap.h"

#include <algorithm>
#include <cmath>

#include "render/colormap_data.h"
#include "sim/error.h"

namespace gs::render {

const std::vector<std::string>& Colormap::names() {
  static const std::vector<std::string> n = {"viridis", "inferno", "magma",
                                             "cividis", "turbo",   "grey"};
  return n;
}

Colormap Colormap::by_name(const std::string& name) {
  if (name == "viridis") return {name, kViridisData};
  if (name == "inferno") return {name, kInfernoData};
  if (name == "magma") return {name, kMagmaData};
  if (name == "cividis") return {name, kCividisData};
  if (name == "turbo") return {name, kTurboData};
  if (name == "grey" || name == "gray") return {"grey", nullptr};
  std::string list;
  for (const auto& n : names()) list += (list.empty() ? "" : ", ") + n;
  throw UsageError("unknown --colormap '" + name + "' (use one of " + list + ")");
}

std::array<float, 3> Colormap::at(double t) const {
  if (!(t > 0)) t = 0;  // also NaN
  if (t > 1) t = 1;
  return full(lo_ + t * (hi_ - lo_));
}

std::array<float, 3> Colormap::full(double t) const {
  if (!table_) {
    const auto g = static_cast<float>(t);
    return {g, g, g};
  }
  const double x = t * 255;
  const int i = std::min(254, static_cast<int>(x));
  const auto f = static_cast<float>(x - i);
  std::array<float, 3> c;
  for (int k = 0; k < 3; ++k) c[k] = table_[i][k] + f * (table_[i + 1][k] - table_[i][k]);
  return c;
}

double srgb_to_linear(double u) {
  return u <= 0.04045 ? u / 12.92 : std::pow((u + 0.055) / 1.055, 2.4);
}

namespace {

// Relative luminance of an sRGB colour (WCAG 2.1).
double luminance(double r, double g, double b) {
  return 0.2126 * srgb_to_linear(r) + 0.7152 * srgb_to_linear(g) + 0.0722 * srgb_to_linear(b);
}

}  // namespace

// The least luminance contrast ratio with the background a colour of the map keeps. WCAG's 3:1
// for graphics leaves magma on white only up to L* 62, too little lightness for a 4:2:0 movie,
// whose colour detail rides on luminance: on the Fig. 1 job (render/contrast.h's edge contrast,
// median over 24 sectors) the whole map gives stills 0.22/0.21/0.22/0.11 at t_paper 5000..50000 and
// movie frames >= 0.14; 3:1 gives stills >= 0.14 but movie frames down to 0.10; 1.5:1 (magma
// up to L* 85) stills >= 0.15 and movie frames >= 0.11.
constexpr double kMinContrast = 1.5;

Colormap Colormap::against(Rgb8 background) const {
  const double bg = luminance(background[0] / 255.0, background[1] / 255.0, background[2] / 255.0);
  auto stands_out = [&](double t) {
    const auto c = full(t);
    const double y = luminance(c[0], c[1], c[2]);
    return (std::max(y, bg) + 0.05) / (std::min(y, bg) + 0.05) >= kMinContrast;
  };
  // Steps of 1/1020 (a quarter of a table entry) from each end; never more than the map holds,
  // and a map with nothing that stands out is left whole rather than emptied.
  constexpr int kSteps = 1020;
  int lo = 0, hi = kSteps;
  while (lo < hi && !stands_out(double(lo) / kSteps)) ++lo;
  while (hi > lo && !stands_out(double(hi) / kSteps)) --hi;
  Colormap c = *this;
  if (hi > lo) c.lo_ = double(lo) / kSteps, c.hi_ = double(hi) / kSteps;
  return c;
}

Rgb8 Colormap::at8(double t) const {
  const auto c = at(t);
  Rgb8 out;
  // lround's rounding (half away from zero) without its call, which a scene of 2.5e5 particles
  // made once a channel: x - floor(x) is exact for 0 <= x <= 255.
  for (int k = 0; k < 3; ++k) {
    const float x = std::clamp(c[k], 0.0f, 1.0f) * 255.0f;
    const int i = static_cast<int>(x);
    out[k] = static_cast<std::uint8_t>(x - static_cast<float>(i) >= 0.5f ? i + 1 : i);
  }
  return out;
}

}  // namespace gs::render
