#include "io/text_scan.h"

#include "sim/error.h"
#include "sim/escaped.h"

namespace gs {

void throw_at_line(const std::string& path, std::size_t line, std::string_view what) {
  std::string m = "snapshot '";
  m.append(path).append("' line ").append(std::to_string(line)).append(": ").append(what);
  throw UserError(m);
}

void throw_not_finite(const std::string& path, std::size_t line, std::string_view tok,
                      std::string_view name) {
  throw_at_line(path, line, not_a(tok, "a finite number", name));
}

// Appending instead of chaining operator+ avoids GCC 12's false -Wrestrict on short literals.
std::string not_a(std::string_view tok, std::string_view kind, std::string_view name) {
  std::string m = "'";
  // A hostile token must neither flood nor drive the terminal.
  m.append(escaped(tok, 40)).append("' is not ").append(kind).append(" (").append(name).append(")");
  return m;
}

}  // namespace gs
