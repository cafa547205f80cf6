#pragma once
// The two pieces of JSON the outputs need: numbers (non-finite ones as null, which JSON readers
// accept, unlike the "nan" of format_double) and escaped strings.
#include <cmath>
#include <string>
#include <string_view>

#include "sim/format.h"

namespace gs {

inline std::string json_number(double x) {
  return std::isfinite(x) ? format_double(x) : "null";
}

inline std::string json_string(std::string_view s) {
  std::string o = "\"";
  for (char ch : s) {
    switch (ch) {
      case '"':
        o += "\\\"";
        break;
      case '\\':
        o += "\\\\";
        break;
      case '\n':
        o += "\\n";
        break;
      case '\t':
        o += "\\t";
        break;
      default:
        if (static_cast<unsigned char>(ch) < 0x20) {
          char buf[8];
          std::snprintf(buf, sizeof buf, "\\u%04x", ch);
          o += buf;
        } else {
          o += ch;
        }
    }
  }
  return o + "\"";
}

}  // namespace gs
