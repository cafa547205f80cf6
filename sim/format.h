#pragma once
// Shortest text that reads back to the same double, for CSV, TOML and JSON outputs.
#include <charconv>
#include <cmath>
#include <string>

namespace gs {

inline std::string format_double(double x) {
  if (!std::isfinite(x)) return std::isnan(x) ? "nan" : (x > 0 ? "inf" : "-inf");
  char buf[32];
  auto [end, ec] = std::to_chars(buf, buf + sizeof buf, x);
  std::string s(buf, end);
  // Keep a float a float in TOML and JSON readers ("2" would read back as an integer).
  if (s.find_first_of(".e") == std::string::npos) s += ".0";
  return s;
}

}  // namespace gs

namespace gs {

// Shortest round-trip text without the float marker: 12 for 12.0, for CSV columns.
inline std::string format_number(double x) {
  if (!std::isfinite(x)) return std::isnan(x) ? "nan" : (x > 0 ? "inf" : "-inf");
  char buf[32];
  auto [end, ec] = std::to_chars(buf, buf + sizeof buf, x);
  return std::string(buf, end);
}

}  // namespace gs
