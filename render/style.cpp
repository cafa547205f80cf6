#include "render/style.h"

#include "sim/error.h"

namespace gs::render {

Field parse_field(const std::string& name) {
  if (name == "speed") return Field::Speed;
  if (name == "radial-velocity") return Field::RadialVelocity;
  if (name == "first-collision") return Field::FirstCollision;
  throw UserError("unknown colour field '" + name +
                  "' (use speed, radial-velocity or first-collision)");
}

Background parse_background(const std::string& name) {
  if (name == "light") return Background::Light;
  if (name == "dark") return Background::Dark;
  throw UserError("unknown background '" + name + "' (use light or dark)");
}

const char* field_label(Field f) {
  switch (f) {
    case Field::Speed:
      return "speed |v|";
    case Field::RadialVelocity:
      return "radial velocity v_r";
    case Field::FirstCollision:
      return "first collision time";
  }
  return "";
}

}  // namespace gs::render
