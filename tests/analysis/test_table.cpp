#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>

#include "analysis/table.h"
#include "sim/error.h"
#include "sim/rng.h"

namespace gs {
namespace {

std::string error_of(auto&& f) {
  try {
    f();
  } catch (const UserError& e) {
    return e.what();
  }
  return "no error";
}

TEST(Table, CsvRoundTripIsExact) {
  Rng rng(3, 0, Stream::Positions);
  Table t;
  std::vector<double> any, physical, special;
  for (int i = 0; i < 2000; ++i) {
    double x;
    do x = std::bit_cast<double>(rng.next());  // every exponent, subnormals included
    while (std::isnan(x));
    any.push_back(x);
    physical.push_back(std::exp(20 * rng.normal()) * (i % 2 ? -1 : 1));
  }
  special = {0.0,
             -0.0,
             1.0,
             12.0,
             0.1,
             1e300,
             5e-324,
             std::numeric_limits<double>::infinity(),
             -std::numeric_limits<double>::infinity(),
             std::numeric_limits<double>::quiet_NaN()};
  special.resize(any.size(), 2.5);
  t.add_column("t", any);
  t.add_column("energy", physical);
  t.add_column("special", special);
  const auto dir = std::filesystem::path(GRAINSHOCK_TEST_OUTPUT_DIR);
  std::filesystem::create_directories(dir);
  write_csv(t, dir / "roundtrip.csv");
  const Table back = read_csv(dir / "roundtrip.csv");
  ASSERT_EQ(back.names, t.names);
  ASSERT_EQ(back.rows(), t.rows());
  for (std::size_t j = 0; j < t.columns.size(); ++j)
    for (std::size_t i = 0; i < t.rows(); ++i) {
      const double a = t.columns[j][i], b = back.columns[j][i];
      if (std::isnan(a))
        EXPECT_TRUE(std::isnan(b));
      else  // bit for bit: -0.0 stays -0.0
        EXPECT_EQ(std::bit_cast<std::uint64_t>(a), std::bit_cast<std::uint64_t>(b))
            << j << " " << i;
    }
  EXPECT_EQ(to_csv(back), to_csv(t));
}

TEST(Table, ParsesForeignCsvAndNamesBadInput) {
  const Table t = parse_csv("t,active , energy\r\n0,1,0.5\r\n\n2, 3 ,1e-3\n", "ts.csv");
  EXPECT_EQ(t.names, (std::vector<std::string>{"t", "active", "energy"}));
  EXPECT_EQ(t.column("active"), (std::vector<double>{1, 3}));
  EXPECT_EQ(t.column("energy")[1], 1e-3);
  EXPECT_NE(error_of([] { parse_csv("t,a\n1,2\n3\n", "x.csv"); }).find("x.csv:3"),
            std::string::npos);
  EXPECT_NE(error_of([] { parse_csv("t,a\n1,zz\n", "x.csv"); }).find("'a'"), std::string::npos);
  EXPECT_NE(error_of([] { parse_csv("t,t\n", "x.csv"); }).find("duplicate"), std::string::npos);
  EXPECT_NE(error_of([] { parse_csv("", "x.csv"); }).find("empty"), std::string::npos);
  EXPECT_NE(error_of([&] { (void)t.column("radius_rms"); }).find("radius_rms"), std::string::npos);
  EXPECT_NE(error_of([] { read_csv("/nonexistent/ts.csv"); }).find("/nonexistent/ts.csv"),
            std::string::npos);
}

}  // namespace
}  // namespace gs
