#include "render/style.h"

#include "sim/error.h"

namespace gs::render {

const std::vector<Field>& all_fields() {
  static const std::vector<Field> f = {Field::ScaledSpeed,          Field::Speed,
                                       Field::ScaledRadialVelocity, Field::RadialVelocity,
                                       Field::FirstCollision,       Field::Type,
                                       Field::None};
  return f;
}

const char* field_name(Field f) {
  switch (f) {
    case Field::Speed:
      return "speed";
    case Field::RadialVelocity:
      return "radial-velocity";
    case Field::FirstCollision:
      return "first-collision";
    case Field::ScaledSpeed:
      return "scaled-speed";
    case Field::ScaledRadialVelocity:
      return "scaled-radial-velocity";
    case Field::Column:
      return "column";
    case Field::Type:
      return "type";
    case Field::None:
      return "none";
  }
  return "";
}

Field parse_field(const std::string& name) {
  std::string list;
  for (Field f : all_fields()) {
    if (name == field_name(f)) return f;
    list += (list.empty() ? "" : ", ") + std::string(field_name(f));
  }
  throw UsageError("unknown --color-by '" + name + "' (use " + list + ")");
}

Background parse_background(const std::string& name) {
  if (name == "light") return Background::Light;
  if (name == "dark") return Background::Dark;
  throw UsageError("unknown --background '" + name + "' (use light or dark)");
}

const char* field_label(Field f) {
  switch (f) {
    case Field::Speed:
      return "speed |v|";
    case Field::RadialVelocity:
      return "radial velocity v_r";
    case Field::FirstCollision:
      return "first collision time";
    case Field::ScaledSpeed:
      return "v / v_rms";
    case Field::ScaledRadialVelocity:
      return "v_r / v_rms";
    case Field::Type:
      return "type";
    case Field::Column:
    case Field::None:
      return "";
  }
  return "";
}

bool is_scaled(Field f) {
  return f == Field::ScaledSpeed || f == Field::ScaledRadialVelocity;
}

Scale parse_scale(const std::string& name, Field f) {
  if (name == "lin") return Scale::Linear;
  if (name == "log") return Scale::Log;
  if (name != "auto") throw UsageError("unknown --scale '" + name + "' (use auto, lin or log)");
  return f == Field::Speed || f == Field::FirstCollision ? Scale::Log : Scale::Linear;
}

bool needs_velocity(Field f) {
  return f != Field::FirstCollision && f != Field::Column && f != Field::Type && f != Field::None;
}

// 5-95% spans of the active particles' v / v_rms and v_r / v_rms (r = 0.1):
// - 2D, the Fig. 1 job (N = 2.5e5, n = 0.25) at t_paper = 5000, 10000, 20000, 50000: v / v_rms
//   0.29-0.32 to 1.44-1.47, v_r / v_rms 0.35-0.48 to 1.19-1.24 (r = 0.5 and N = 4e4 at
//   t = 1000-8000 give 0.16-0.30 to 1.53-1.83: a younger band, wider);
// - 3D, N = 2e5 at t = 500, 1000, 3000: v / v_rms 0.14-0.17 to 1.87-1.97, v_r / v_rms -0.09 to
//   -0.02 to 1.53-1.61.
std::optional<std::pair<double, double>> default_range(Field f, int dim) {
  if (f == Field::None) return std::pair{0.0, 1.0};  // field_values() gives 0.5: the map's middle
  if (f == Field::Type) return std::pair{0.0, 1.0};  // the palette, not the map, colours types
  if (f == Field::ScaledSpeed) return dim == 3 ? std::pair{0.15, 1.9} : std::pair{0.3, 1.5};
  if (f == Field::ScaledRadialVelocity)
    return dim == 3 ? std::pair{-0.1, 1.6} : std::pair{0.3, 1.3};
  return std::nullopt;
}

}  // namespace gs::render
