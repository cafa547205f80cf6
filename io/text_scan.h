#pragma once
// Line and token scanning shared by the text snapshot readers (extended XYZ, LAMMPS dumps):
// no copies, no iostreams, numbers through std::from_chars, errors as "file line N: ...".
#include <algorithm>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <exception>
#include <string>
#include <string_view>
#include <thread>

#if defined(__AVX2__)
#include <immintrin.h>
#endif

#include "io/decimal.h"

namespace gs {

inline bool is_space(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\n';
}

// The first space (is_space) in [p, e), or e. Eight bytes at a time: a byte below 0x21 (a space
// or another control character) sets its high bit in (w - 0x21..) & ~w, and the lowest such bit
// is exact (a borrow only runs upwards from a byte that already set one).
inline const char* token_end(const char* p, const char* e) {
  while (e - p >= 8) {
    std::uint64_t w;
    std::memcpy(&w, p, 8);
    const std::uint64_t low = (w - 0x2121212121212121u) & ~w & 0x8080808080808080u;
    if (low == 0) {
      p += 8;
      continue;
    }
    p += std::countr_zero(low) / 8;
    if (is_space(*p)) return p;
    ++p;  // a control character inside the token
  }
  while (p < e && !is_space(*p)) ++p;
  return p;
}

// Past the first n - found newlines from p on, adding those passed to `found`; with fewer before
// e, a place after the last one. A frame's index and the split of its rows skip whole
// frames of short lines: 32 bytes a step, where memchr would be called once a line.
inline const char* past_newlines(const char* p, const char* e, std::size_t n, std::size_t& found) {
#if defined(__AVX2__)
  const __m256i nl = _mm256_set1_epi8('\n');
  while (found < n && e - p >= 32) {
    const __m256i v = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(p));
    auto m = static_cast<std::uint32_t>(_mm256_movemask_epi8(_mm256_cmpeq_epi8(v, nl)));
    const auto c = static_cast<std::size_t>(std::popcount(m));
    if (found + c < n) {
      found += c;
      p += 32;
      continue;
    }
    for (; found + 1 < n; ++found) m &= m - 1;  // the (n - found)th newline is the lowest left
    ++found;
    return p + std::countr_zero(m) + 1;
  }
#endif
  while (found < n && p < e) {
    const void* q = std::memchr(p, '\n', e - p);
    if (!q) break;
    p = static_cast<const char*>(q) + 1;
    ++found;
  }
  return p;
}

inline bool iequals(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    char x = a[i], y = b[i];
    if (x >= 'A' && x <= 'Z') x = static_cast<char>(x - 'A' + 'a');
    if (y >= 'A' && y <= 'Z') y = static_cast<char>(y - 'A' + 'a');
    if (x != y) return false;
  }
  return true;
}

// The next whitespace-separated token of `s` from `i` on; empty at the end.
inline std::string_view next_token(std::string_view s, std::size_t& i) {
  while (i < s.size() && is_space(s[i])) ++i;
  const std::size_t b = i;
  while (i < s.size() && !is_space(s[i])) ++i;
  return s.substr(b, i - b);
}

inline bool is_blank(std::string_view s) {
  for (char c : s)
    if (!is_space(c)) return false;
  return true;
}

// Whole-token numbers; a leading '+' is accepted (from_chars alone refuses it).
inline bool parse_real(std::string_view t, double& v) {
  if (!t.empty() && t[0] == '+') t.remove_prefix(1);
  return parse_decimal(t.data(), t.data() + t.size(), v);
}
template <class Int>
bool parse_integer(std::string_view t, Int& v) {
  if (!t.empty() && t[0] == '+') t.remove_prefix(1);
  const auto [p, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
  return ec == std::errc() && p == t.data() + t.size() && !t.empty();
}

// Lines of a text, with their numbers (from 1) for messages.
class LineCursor {
 public:
  explicit LineCursor(std::string_view text, std::size_t pos = 0, std::size_t line = 0)
      : text_(text), pos_(pos), line_(line) {}
  bool next(std::string_view& line) {
    if (pos_ >= text_.size()) return false;
    const void* nl = std::memchr(text_.data() + pos_, '\n', text_.size() - pos_);
    const std::size_t end = nl ? static_cast<const char*>(nl) - text_.data() : text_.size();
    line = text_.substr(pos_, end - pos_);
    pos_ = end + 1;
    ++line_;
    return true;
  }
  // Skips up to n lines (the last may lack its newline); returns how many there were.
  std::size_t skip(std::size_t n) {
    if (pos_ >= text_.size()) return 0;
    const char* const e = text_.data() + text_.size();
    std::size_t k = 0;
    const char* p = past_newlines(text_.data() + pos_, e, n, k);
    if (k < n) {  // every newline passed: what follows the last one is a line of its own
      k += e[-1] != '\n';
      p = e;
    }
    pos_ = static_cast<std::size_t>(p - text_.data());
    line_ += k;
    return k;
  }
  std::size_t pos() const { return std::min(pos_, text_.size()); }
  std::size_t line() const { return line_; }  // number of the line last returned
  bool at_end() const { return pos_ >= text_.size(); }

 private:
  std::string_view text_;
  std::size_t pos_, line_;
};

// "snapshot 'path' line N: what", thrown as UserError.
[[noreturn]] void throw_at_line(const std::string& path, std::size_t line, std::string_view what);

// The particle lines of a frame: `rows` lines of exactly `columns` tokens from `body` on, the
// first of them line number `first_line`. Calls token(i, t, tok, line) for column t of row i,
// then row_done(i, line). A missing or extra token is an error naming the line. With `split`,
// a frame of many rows is scanned in two halves on two threads (the callbacks then must touch
// row i's data only); an error in both is reported for the earlier line, as one pass would.
template <class Token, class RowDone>
void scan_rows(std::string_view body, std::size_t rows, std::size_t columns, std::size_t first_line,
               const std::string& path, Token&& token, RowDone&& row_done, bool split = false) {
  const char* const end = body.data() + body.size();
  // Spaces within a line; a token ends at any space (token_end), so the line's end is found by
  // the tokens themselves, with no pass of its own over the line.
  auto blank = [](char c) { return c == ' ' || c == '\t' || c == '\r'; };
  auto scan = [&](std::size_t from, std::size_t to, const char* p) {
    for (std::size_t i = from; i < to; ++i) {
      const std::size_t line = first_line + i;
      const char* q = std::min(p, end);
      std::size_t t = 0;
      for (; t < columns; ++t) {
        while (q < end && blank(*q)) ++q;
        if (q == end || *q == '\n') break;
        const char* const te = token_end(q, end);
        token(i, t, std::string_view(q, te - q), line);
        q = te;
      }
      while (q < end && blank(*q)) ++q;
      if (t < columns || (q != end && *q != '\n')) {
        const void* nl = q < end ? std::memchr(q, '\n', end - q) : nullptr;
        const char* const eol = nl ? static_cast<const char*>(nl) : end;
        std::size_t found = t, j = 0;
        const std::string_view rest(q, eol - q);
        while (!next_token(rest, j).empty()) ++found;
        throw_at_line(
            path, line,
            "expected " + std::to_string(columns) + " columns, found " + std::to_string(found));
      }
      row_done(i, line);
      p = q + 1;
    }
  };
  // Below this a second thread costs more than it saves.
  constexpr std::size_t kSplitRows = 1 << 15;
  if (!split || rows < kSplitRows) return scan(0, rows, body.data());
  const std::size_t mid = rows / 2;
  LineCursor c(body);
  c.skip(mid);
  std::exception_ptr second;
  std::thread other([&] {
    try {
      scan(mid, rows, body.data() + c.pos());
    } catch (...) {
      second = std::current_exception();
    }
  });
  std::exception_ptr first;
  try {
    scan(0, mid, body.data());
  } catch (...) {
    first = std::current_exception();
  }
  other.join();
  if (first) std::rethrow_exception(first);
  if (second) std::rethrow_exception(second);
}
[[noreturn]] void throw_not_finite(const std::string& path, std::size_t line, std::string_view tok,
                                   std::string_view name);
// The finite number `tok` is, or an error at that line naming the column.
inline double finite_at(const std::string& path, std::size_t line, std::string_view tok,
                        std::string_view name) {
  double v = 0;
  if (!parse_real(tok, v) || !std::isfinite(v)) throw_not_finite(path, line, tok, name);
  return v;
}
// "'tok' is not <kind> (<name>)"
std::string not_a(std::string_view tok, std::string_view kind, std::string_view name);

}  // namespace gs
