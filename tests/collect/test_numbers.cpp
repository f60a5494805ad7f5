// The log rows are written with collect's own number formatting (no temporary strings, and the
// robot's position from its integer count of 0.1 mm): it must give exactly the text of
// io::format_double() and sim::format_metres(), which `feint simulate` and the readers use.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "../../src/collect/durable.hpp"
#include "feint/io/number.hpp"
#include "feint/sim/robot_path.hpp"

namespace feint::collect {
namespace {

std::string metres(double m) {
  std::string s;
  detail::append_metres(s, m);
  return s;
}

std::string number(double v) {
  std::string s;
  detail::append_double(s, v);
  return s;
}

TEST(CollectNumbers, MetresAreWrittenAsFormatMetresWritesThem) {
  for (const double m : {0.0, -0.0, 0.00004, -0.00004, 0.00005, -0.00005, 0.0001, -0.0001, 1.0,
                         -2.0, 4.0, 0.5, 0.1, 0.12, 0.123, 0.1234, 0.12345, 1.99995, -1.99995,
                         12345.6789, -0.0999, 1e20, -3e16, 123456789012.3456})
    EXPECT_EQ(metres(m), sim::format_metres(m)) << m;
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> wide(-50.0, 50.0), narrow(-0.01, 0.01);
  for (int i = 0; i < 200000; ++i) {
    const double m = i % 4 == 0 ? narrow(rng) : wide(rng);
    ASSERT_EQ(metres(m), sim::format_metres(m)) << m;
  }
  // Every multiple of 0.1 mm from -3 m to 3 m, as the robot's path gives them.
  for (int k = -30000; k <= 30000; ++k) ASSERT_EQ(metres(k / 1e4), sim::format_metres(k / 1e4)) << k;
}

TEST(CollectNumbers, NumbersAreWrittenAsFormatDoubleWritesThem) {
  for (const double v : {0.0, -0.0, 0.5, 1.0, 1.0 / 60, 1e-5, 1e-4, 123456789.0, 1e16, 1e17,
                         -2.5e-300, std::numeric_limits<double>::denorm_min(),
                         std::numeric_limits<double>::max(), -std::numeric_limits<double>::max()})
    EXPECT_EQ(number(v), io::format_double(v)) << v;
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(0.0, 30.0);
  for (int i = 0; i < 100000; ++i) {
    const double v = i % 2 ? u(rng) : (i % 1800) / 60.0;
    ASSERT_EQ(number(v), io::format_double(v)) << v;
  }
}

}  // namespace
}  // namespace feint::collect
