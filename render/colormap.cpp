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
  throw UserError("unknown colormap '" + name + "' (use one of " + list + ")");
}

std::array<float, 3> Colormap::at(double t) const {
  if (!(t > 0)) t = 0;  // also NaN
  if (t > 1) t = 1;
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

Rgb8 Colormap::at8(double t) const {
  const auto c = at(t);
  Rgb8 out;
  for (int k = 0; k < 3; ++k)
    out[k] = static_cast<std::uint8_t>(std::lround(std::clamp(c[k], 0.0f, 1.0f) * 255.0f));
  return out;
}

}  // namespace gs::render
