#pragma once
// A decimal number read to the double std::from_chars gives, bit for bit, in a few nanoseconds
// for the tokens snapshot files are made of. from_chars is correctly rounded; so is the fast
// path here, and anything it cannot prove it rounds correctly goes to from_chars.
#include <charconv>
#include <cstdint>
#include <cstring>
#include <limits>
#include <system_error>

namespace gs {

namespace decimal_detail {

// Appends the decimal digits from p on to m (m * 10 + digit each; it wraps past 19 digits,
// which the caller refuses), eight at a time while eight remain: a word's bytes are all digits
// when neither they nor they + 6 leave 0x30..0x39's high nibble, and then three multiplications
// fold them pairwise (10 a + b in bytes, 100 a + b in 16-bit lanes, 10^4 a + b in 32-bit ones).
inline void digits_into(const char*& p, const char* e, std::uint64_t& m) {
  while (e - p >= 8) {
    std::uint64_t w;
    std::memcpy(&w, p, 8);
    if (((w & 0xf0f0f0f0f0f0f0f0u) | ((w + 0x0606060606060606u) & 0xf0f0f0f0f0f0f0f0u) >> 4) !=
        0x3333333333333333u)
      break;
    w -= 0x3030303030303030u;
    w = (w * 10 + (w >> 8)) & 0x00ff00ff00ff00ffu;
    w = (w * 100 + (w >> 16)) & 0x0000ffff0000ffffu;
    w = (w * 10000 + (w >> 32)) & 0xffffffffu;
    m = m * 100000000u + w;
    p += 8;
  }
  while (p != e && static_cast<unsigned>(*p - '0') < 10) m = m * 10 + static_cast<unsigned>(*p++ - '0');
}

// What the fast path leaves: out of line, so that the fast path inlines where tokens are read.
[[gnu::noinline, gnu::cold]] inline bool by_from_chars(const char* b, const char* e, double& v) {
  const auto [p, ec] = std::from_chars(b, e, v);
  return ec == std::errc() && p == e && b != e;
}

}  // namespace decimal_detail

// Reads the whole of [b, e) as std::from_chars(b, e, v) would (general format: no '+', no
// leading space); false where from_chars fails or leaves characters over.
inline bool parse_decimal(const char* b, const char* e, double& v) {
  auto slow = [&] { return decimal_detail::by_from_chars(b, e, v); };
  // The fast path: [-]digits[.digits][(e|E)[+|-]digits], at most 19 digits in all (so the
  // mantissa m is below 10^19 < 2^64) and a power of ten k with |k| <= 27, whose 10^|k| is exact
  // in the 64-bit significand of x87's long double (5^27 < 2^64). Then m * 10^k (or m / 10^-k)
  // is one operation, rounded once to 64 bits; rounding that to a double is the correctly
  // rounded result unless the 64-bit value sits exactly halfway between two doubles (its 11
  // low bits 10000000000), which goes to from_chars. 17-digit shortest round-trip numbers,
  // half of a snapshot's tokens, take this path too.
  const char* p = b;
  const bool negative = p != e && *p == '-';
  p += negative;
  std::uint64_t m = 0;
  int digits = 0, scale = 0;
  const char* const first = p;
  decimal_detail::digits_into(p, e, m);
  digits = static_cast<int>(p - first);
  if (digits == 0) return slow();  // ".5", "inf", "nan", or not a number
  if (p != e && *p == '.') {
    const char* const frac = ++p;
    decimal_detail::digits_into(p, e, m);
    scale = static_cast<int>(p - frac);
    if (scale == 0) return slow();  // "1." (from_chars takes it; rare)
    digits += scale;
  }
  if (digits > 19) return slow();
  int k = -scale;
  if (p != e && (*p == 'e' || *p == 'E')) {
    ++p;
    const bool down = p != e && *p == '-';
    if (p != e && (*p == '-' || *p == '+')) ++p;
    const char* const exp = p;
    int x = 0;
    while (p != e && p - exp < 4 && static_cast<unsigned>(*p - '0') < 10) x = x * 10 + (*p++ - '0');
    if (p == exp) return slow();
    k += down ? -x : x;
  }
  if (p != e || k < -27 || k > 27) return slow();
  if (m <= (std::uint64_t{1} << 53) && k >= -22 && k <= 22) {  // m and 10^|k| exact in a double
    static constexpr double kExact[23] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,
                                          1e8,  1e9,  1e10, 1e11, 1e12, 1e13, 1e14, 1e15,
                                          1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};
    const auto md = static_cast<double>(m);
    const double d = k >= 0 ? md * kExact[k] : md / kExact[-k];
    v = negative ? -d : d;
    return true;
  }
  // The 64-bit significand in the low 8 bytes: x87's 80-bit format (x86-64 Linux).
  static_assert(std::numeric_limits<long double>::digits == 64);
  static constexpr long double kPow10[28] = {
      1e0L,  1e1L,  1e2L,  1e3L,  1e4L,  1e5L,  1e6L,  1e7L,  1e8L,  1e9L,
      1e10L, 1e11L, 1e12L, 1e13L, 1e14L, 1e15L, 1e16L, 1e17L, 1e18L, 1e19L,
      1e20L, 1e21L, 1e22L, 1e23L, 1e24L, 1e25L, 1e26L, 1e27L};
  const auto mm = static_cast<long double>(m);  // exact: m < 2^64
  const long double x = k >= 0 ? mm * kPow10[k] : mm / kPow10[-k];
  std::uint64_t significand;
  std::memcpy(&significand, &x, sizeof significand);
  if (m != 0 && (significand & 0x7ff) == 0x400) return slow();
  const auto d = static_cast<double>(x);
  v = negative ? -d : d;
  return true;
}

}  // namespace gs
