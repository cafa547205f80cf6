// The outputs' JSON (analysis/json.h): what the library writes reads back to the same values,
// strings that need escaping included, and the cases JSON cannot hold are written as documented.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "analysis/json.h"

namespace gs {
namespace {

TEST(Json, NumbersAndStringsReadBackTheSame) {
  Json j;
  j["third"] = 1.0 / 3.0;  // needs all 17 digits
  j["tiny"] = 5e-324;      // the smallest subnormal
  j["whole"] = 2.0;        // stays a float ("2.0"), not an integer
  j["count"] = std::uint64_t{18446744073709551615u};
  j["name"] = "say \"when\"\\ a\nb\tc \x01 \xc3\xa9";  // quote, backslash, controls, UTF-8
  const std::string text = json_text(j);
  EXPECT_EQ(text.back(), '\n');
  EXPECT_NE(text.find("\"whole\": 2.0"), std::string::npos) << text;
  const Json back = Json::parse(text);
  EXPECT_EQ(back, j) << text;
  EXPECT_EQ(back["third"].get<double>(), 1.0 / 3.0);  // to the bit
  EXPECT_EQ(back["name"].get<std::string>(), j["name"].get<std::string>());
}

TEST(Json, NonFiniteNumbersAreNullAndBadUtf8IsReplaced) {
  Json j;
  j["nan"] = std::numeric_limits<double>::quiet_NaN();
  j["inf"] = -std::numeric_limits<double>::infinity();
  j["file"] = std::string("run\xff.xyz");  // a file name need not be UTF-8
  const Json back = Json::parse(json_text(j));
  EXPECT_TRUE(back["nan"].is_null());
  EXPECT_TRUE(back["inf"].is_null());
  EXPECT_EQ(back["file"].get<std::string>(), "run\xef\xbf\xbd.xyz");  // U+FFFD
}

}  // namespace
}  // namespace gs
