#pragma once
// A colormap maps t in [0, 1] to a colour. The perceptual ones come from matplotlib's tables,
// so a picture here matches one made in Python with the same name.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace gs::render {

using Rgb8 = std::array<std::uint8_t, 3>;

class Colormap {
 public:
  // viridis, inferno, magma, cividis, turbo or grey; anything else is a UserError listing these.
  static Colormap by_name(const std::string& name);
  static const std::vector<std::string>& names();

  // Linear interpolation between the table's entries; t is clamped to [0, 1], NaN gives 0.
  std::array<float, 3> at(double t) const;
  Rgb8 at8(double t) const;
  const std::string& name() const { return name_; }

 private:
  Colormap(std::string name, const float (*table)[3]) : name_(std::move(name)), table_(table) {}
  std::string name_;
  const float (*table_)[3];  // 256 entries, or nullptr for grey
};

}  // namespace gs::render
