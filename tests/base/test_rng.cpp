// The simulator's generator against the published reference outputs, and the bounded/real draws.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>

#include "feint/rng.hpp"

using feint::Rng;
using feint::splitmix64;

TEST(SplitMix64, MatchesReferenceOutputsForSeed1234567) {
  // Vigna's splitmix64.c, seed 1234567 (the widely published test sequence).
  std::uint64_t state = 1234567;
  const std::array<std::uint64_t, 5> expected = {6457827717110365317ULL, 3203168211198807973ULL,
                                                 9817491932198370423ULL, 4593380528125082431ULL,
                                                 16408922859458223821ULL};
  for (auto e : expected) EXPECT_EQ(splitmix64(state), e);
}

TEST(Xoshiro256StarStar, MatchesReferenceOutputsFromState1234) {
  // xoshiro256starstar.c 1.0 with s = {1, 2, 3, 4}.
  Rng rng = Rng::from_state(1, 2, 3, 4);
  const std::array<std::uint64_t, 5> expected = {11520ULL, 0ULL, 1509978240ULL,
                                                 1215971899390074240ULL, 1216172134540287360ULL};
  for (auto e : expected) EXPECT_EQ(rng(), e);
}

TEST(Rng, BoundedIsUnbiasedAndInRange) {
  Rng rng(42);
  std::array<int, 3> count{};
  const int draws = 300000;
  for (int i = 0; i < draws; ++i) {
    const auto v = rng.bounded(3);
    ASSERT_LT(v, 3u);
    ++count[v];
  }
  // chi-square with 2 df; 13.8 is its 0.999 quantile
  double chi2 = 0;
  for (int c : count) chi2 += (c - draws / 3.0) * (c - draws / 3.0) / (draws / 3.0);
  EXPECT_LT(chi2, 13.8);
  for (int i = 0; i < 100; ++i) EXPECT_EQ(rng.bounded(1), 0u);
}

TEST(Rng, UniformIsInUnitIntervalWithMeanOneHalf) {
  Rng rng(7);
  double sum = 0;
  const int draws = 200000;
  for (int i = 0; i < draws; ++i) {
    const double u = rng.uniform();
    ASSERT_GE(u, 0.0);
    ASSERT_LT(u, 1.0);
    sum += u;
  }
  // sd of the mean = sqrt(1/12 / n)
  EXPECT_NEAR(sum / draws, 0.5, 4 * std::sqrt(1.0 / 12 / draws));
}

TEST(Rng, NormalHasMeanZeroAndUnitVariance) {
  Rng rng(11);
  double sum = 0, sum2 = 0;
  const int draws = 200000;
  for (int i = 0; i < draws; ++i) {
    const double z = rng.normal();
    sum += z;
    sum2 += z * z;
  }
  EXPECT_NEAR(sum / draws, 0.0, 4 / std::sqrt(draws));
  EXPECT_NEAR(sum2 / draws, 1.0, 4 * std::sqrt(2.0 / draws));
}

TEST(Rng, StreamsDependOnSeedAndIndexOnly) {
  Rng a = Rng::stream(5, 17), b = Rng::stream(5, 17);
  for (int i = 0; i < 10; ++i) EXPECT_EQ(a(), b());
  Rng c = Rng::stream(5, 18), d = Rng::stream(6, 17), e = Rng::stream(17, 5);
  const auto x = Rng::stream(5, 17)();
  EXPECT_NE(c(), x);
  EXPECT_NE(d(), x);
  EXPECT_NE(e(), x);
}
