#include "sim/escaped.h"

#include <cstdio>

namespace gs {
namespace {

// Length of the UTF-8 sequence at `p` (`n` bytes left) if it is well formed and not a C1
// control character (U+0080..U+009F, which some terminals obey as ESC sequences), else 0.
std::size_t utf8_length(const unsigned char* p, std::size_t n) {
  const unsigned char c = p[0];
  const std::size_t len = c >= 0xF0 && c <= 0xF4 ? 4 : c >= 0xE0 && c < 0xF0 ? 3
                        : c >= 0xC2 && c < 0xE0 ? 2 : 0;
  if (len == 0 || len > n) return 0;
  for (std::size_t k = 1; k < len; ++k)
    if ((p[k] & 0xC0) != 0x80) return 0;
  if (c == 0xC2 && p[1] < 0xA0) return 0;   // C1 controls
  if (c == 0xE0 && p[1] < 0xA0) return 0;   // overlong
  if (c == 0xED && p[1] >= 0xA0) return 0;  // surrogates
  if (c == 0xF0 && p[1] < 0x90) return 0;   // overlong
  if (c == 0xF4 && p[1] >= 0x90) return 0;  // beyond U+10FFFF
  return len;
}

}  // namespace

std::string escaped(std::string_view text, std::size_t max_bytes) {
  const bool cut = text.size() > max_bytes;
  if (cut) text = text.substr(0, max_bytes);
  const auto* p = reinterpret_cast<const unsigned char*>(text.data());
  std::string out;
  out.reserve(text.size());
  for (std::size_t i = 0; i < text.size();) {
    const unsigned char c = p[i];
    if (c >= 0x20 && c < 0x7F) {
      out += static_cast<char>(c);
      ++i;
      continue;
    }
    if (const std::size_t len = c >= 0x80 ? utf8_length(p + i, text.size() - i) : 0) {
      out.append(text.substr(i, len));
      i += len;
      continue;
    }
    char hex[8];
    std::snprintf(hex, sizeof hex, "\\x%02X", static_cast<unsigned>(c));
    out += hex;
    ++i;
  }
  if (cut) out += "...";
  return out;
}

}  // namespace gs
