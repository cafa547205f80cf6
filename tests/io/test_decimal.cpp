// io/decimal.h reads every token to the bits std::from_chars gives (or fails where it fails).
#include <gtest/gtest.h>

#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <random>
#include <string>

#include "io/decimal.h"
#include "io/text_scan.h"

namespace gs {
namespace {

// Fails the test naming the token where parse_decimal and from_chars disagree.
void same_as_from_chars(const std::string& s) {
  double fast = 12345, ref = 12345;
  const bool ok = parse_decimal(s.data(), s.data() + s.size(), fast);
  const auto [p, ec] = std::from_chars(s.data(), s.data() + s.size(), ref);
  const bool ref_ok = ec == std::errc() && p == s.data() + s.size() && !s.empty();
  ASSERT_EQ(ok, ref_ok) << "'" << s << "'";
  if (ok) {
    ASSERT_EQ(std::memcmp(&fast, &ref, sizeof fast), 0) << "'" << s << "'";
  }
}

TEST(Decimal, EdgeCasesAsFromChars) {
  for (const char* s :
       {"0", "-0", "0.0", "-0.0", "-0e5", "1", "-1", "1.", "1.5", ".5", "-.5", "+1", "1e5", "1E5",
        "1e+5", "1e-5", "1e", "1e+", "-", "", "inf", "nan", "-inf", "1e400", "1e-400", "0e999",
        "4.9406564584124654e-324", "2.2250738585072014e-308", "1.7976931348623157e308",
        "9007199254740993", "9007199254740992.5", "18446744073709551615", "9999999999999999999",
        "123456789012345678901", "0.1", "0.2", "0.3", "1e22", "1e23", "1e27", "1e28", "1e-27",
        "1e-28", "00000000000000000001", "0x1p3", "1 ", " 1", "1e0005", "1e00005", "1..2",
        "1.2.3", "12a", "12345678a", "1234567\x0b", "-+1", "--1", "1e--5", "0.30000000000000004",
        "5e-1", "2.5e-1", "0.49999999999999994", "8.98846567431158e307"})
    same_as_from_chars(s);
}

// Shortest round-trip, %.17g, fixed and scientific forms, random mantissas with exponents
// and exact halfway points between doubles: the forms files hold, and the hard cases for a
// fast path.
TEST(Decimal, RandomTokensAsFromChars) {
  std::mt19937_64 rng(32);
  char buf[64];
  auto shortest = [&](double d) {
    const auto r = std::to_chars(buf, buf + sizeof buf, d);
    return std::string(buf, r.ptr);
  };
  std::uniform_real_distribution<double> u(-1100, 1100);
  for (int i = 0; i < 300000; ++i) {
    std::uint64_t bits = rng();
    double any;
    std::memcpy(&any, &bits, sizeof any);
    if (std::isfinite(any)) same_as_from_chars(shortest(any));
    const double d = u(rng);
    same_as_from_chars(shortest(d));
    same_as_from_chars(shortest(d * 1e-3));
    std::snprintf(buf, sizeof buf, "%.17g", d * std::pow(10.0, int(rng() % 40) - 20));
    same_as_from_chars(buf);
    std::snprintf(buf, sizeof buf, "%.*g", int(rng() % 20) + 1, d);
    same_as_from_chars(buf);
    std::snprintf(buf, sizeof buf, "%.*e", int(rng() % 20), d);
    same_as_from_chars(buf);
    std::snprintf(buf, sizeof buf, "%.*f", int(rng() % 20), d / 1000);
    same_as_from_chars(buf);
    std::snprintf(buf, sizeof buf, "%llue%d",
                  static_cast<unsigned long long>(rng() % 10000000000000000000u),
                  int(rng() % 60) - 40);
    same_as_from_chars(buf);
    // m + 1/2 for a 53-bit m: exactly halfway between two doubles, written out in full.
    const std::uint64_t m = (rng() >> 11) | (std::uint64_t{1} << 52);
    std::snprintf(buf, sizeof buf, "%llu.5", static_cast<unsigned long long>(m));
    same_as_from_chars(buf);
    std::snprintf(buf, sizeof buf, "%llue-1", static_cast<unsigned long long>((2 * m + 1) * 5));
    same_as_from_chars(buf);
  }
}

// What the readers call: '+' allowed, finite only.
TEST(Decimal, ParseRealKeepsItsRules) {
  double v = 0;
  EXPECT_TRUE(parse_real("+2.5", v));
  EXPECT_EQ(v, 2.5);
  EXPECT_TRUE(parse_real("-0", v));
  EXPECT_TRUE(std::signbit(v));
  EXPECT_FALSE(parse_real("+", v));
  EXPECT_FALSE(parse_real("2.5x", v));
  EXPECT_THROW(finite_at("f", 3, "inf", "pos"), std::exception);
  EXPECT_EQ(finite_at("f", 3, "1e-3", "pos"), 1e-3);
}

TEST(Decimal, TokenEndFindsTheFirstSpace) {
  const std::string s = "123456789\x0b" "0123 x\ty";
  EXPECT_EQ(token_end(s.data(), s.data() + s.size()) - s.data(), 14);
  const std::string t = "12345678901234567890";
  EXPECT_EQ(token_end(t.data(), t.data() + t.size()) - t.data(), 20);
  const std::string r = "1.5\r\n";
  EXPECT_EQ(token_end(r.data(), r.data() + r.size()) - r.data(), 3);
}

}  // namespace
}  // namespace gs
