// tests/models: a portable normal generator for the mixed-model tests' simulated designs
// (std::normal_distribution differs between standard libraries, so values would too).
#pragma once

#include <cmath>
#include <cstdint>
#include <numbers>

namespace feint::test {

struct Normal {
  std::uint64_t s;
  double uniform() {
    s = s * 6364136223846793005ULL + 1442695040888963407ULL;
    return (static_cast<double>(s >> 11) + 0.5) / 9007199254740992.0;
  }
  double operator()() {
    const double u = uniform(), v = uniform();
    return std::sqrt(-2 * std::log(u)) * std::cos(2 * std::numbers::pi * v);
  }
};

}  // namespace feint::test
