// Numbers are read exactly as strtod reads them in the C locale (decimal form only), no more and
// no less: docs/scoring.md "Numbers".
#include <clocale>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <string>

#include <gtest/gtest.h>

#include "feint/io/number.hpp"

using feint::io::parse_double;
using feint::io::parse_integer;

namespace {

// strtod's reading when it consumes the whole text, else nullopt.
std::optional<double> strtod_whole(const std::string& s) {
  char* end = nullptr;
  const double v = std::strtod(s.c_str(), &end);
  if (s.empty() || end != s.c_str() + s.size()) return std::nullopt;
  return v;
}

}  // namespace

TEST(Number, ASignIsReadOnceNeverTwice) {
  for (const char* bad : {"+-2", "-+2", "++2", "--2", "+ 2", "- 2", "+", "-", "+.", "-e1"}) {
    EXPECT_FALSE(parse_double(bad).has_value()) << bad;
    EXPECT_FALSE(parse_integer(bad).has_value()) << bad;
  }
  EXPECT_EQ(parse_double("+2"), 2.0);
  EXPECT_EQ(parse_double("-2"), -2.0);
  EXPECT_EQ(parse_integer("+7"), 7);
  EXPECT_EQ(parse_integer("-7"), -7);
}

TEST(Number, UnderflowReadsAsStrtodDoes) {
  // strtod gives 0 (or a subnormal) with ERANGE; the value is still the correctly rounded one.
  for (const char* tiny : {"9e-325", "-9e-325", "1e-400", "2.5e-324", "4e-320", "1e-310"}) {
    const auto v = parse_double(tiny);
    ASSERT_TRUE(v.has_value()) << tiny;
    const double want = std::strtod(tiny, nullptr);
    EXPECT_EQ(std::memcmp(&*v, &want, sizeof want), 0) << tiny << " read as " << *v;
  }
  EXPECT_EQ(parse_double("9e-325"), 0.0);
  EXPECT_TRUE(std::signbit(*parse_double("-9e-325")));
}

TEST(Number, OverflowInfinityNanAndHexAreInvalid) {
  for (const char* bad : {"1e309", "-1e309", "inf", "INF", "infinity", "-Infinity", "nan",
                          "NAN", "nan(1)", "0x10", "0x1p3", "-0X1.8P1", "1e", "1e+", "1.5.2",
                          "1,5", "1 000", ".", "e5", "1e5x", "\n1", "1\n", "\v1"}) {
    EXPECT_FALSE(parse_double(bad).has_value()) << bad;
  }
}

TEST(Number, AcceptsEveryDecimalFormStrtodAccepts) {
  for (const char* good : {"0", "-0", "0.", ".5", "-.5", "+.5", "1.", "1e5", "1E+05", "1e-05",
                           "00012.5000", "123456789012345678901234567890",
                           "0.1000000000000000055511151231257827021181583404541015625",
                           "1.7976931348623157e308", "4.9e-324", "2.2250738585072011e-308"}) {
    const auto v = parse_double(good);
    ASSERT_TRUE(v.has_value()) << good;
    const double want = *strtod_whole(good);
    EXPECT_EQ(std::memcmp(&*v, &want, sizeof want), 0) << good;
  }
}

TEST(Number, SurroundingSpacesAndTabsAreIgnored) {
  EXPECT_EQ(parse_double("  1.5\t"), 1.5);
  EXPECT_EQ(parse_double("\t-2 "), -2.0);
  EXPECT_FALSE(parse_double("1 .5").has_value());
  EXPECT_EQ(parse_integer(" 12 "), 12);
}

TEST(Number, IntegersAreDecimalWholeNumbers) {
  EXPECT_EQ(parse_integer("007"), 7);
  EXPECT_EQ(parse_integer("-0"), 0);
  for (const char* bad : {"", "1.0", "1e2", "0x10", "9223372036854775808", "12a"}) {
    EXPECT_FALSE(parse_integer(bad).has_value()) << bad;
  }
}
