// Selection algorithms: invariants, the adaptive update traced by hand, and the run generator.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <map>
#include <set>
#include <vector>

#include "feint/error.hpp"
#include "feint/sim/selection.hpp"

using namespace feint::sim;
using feint::Rng;

namespace {
std::vector<int> states_of(Algorithm a, int n, double lambda, Rng& rng, int k = kStates) {
  Selector sel(a, k, n, lambda);
  sel.reset(rng);
  std::vector<int> out;
  for (int i = 0; i < n; ++i) out.push_back(sel.next(rng));
  return out;
}
}  // namespace

TEST(AdaptiveState, HandComputedTraceWithReset) {
  // K = 4, lambda = 0.5, chosen states 0, 1, 2, 3, 3 (fractions worked out by hand).
  AdaptiveState st(4);
  // 1) S0: c = (1,0,0,0); L = {1,2,3}; p0 = 1/4 - 1/8 = 1/8; others 1/4 + 1/24 = 7/24.
  EXPECT_FALSE(st.observe(0, 0.5));
  EXPECT_DOUBLE_EQ(st.p[0], 1.0 / 8);
  EXPECT_DOUBLE_EQ(st.p[1], 7.0 / 24);
  EXPECT_DOUBLE_EQ(st.p[2], 7.0 / 24);
  EXPECT_DOUBLE_EQ(st.p[3], 7.0 / 24);
  EXPECT_EQ((std::array<int, 4>{st.c[0], st.c[1], st.c[2], st.c[3]}), (std::array<int, 4>{1, 0, 0, 0}));
  // 2) S1: c = (1,1,0,0); L = {2,3} (S0 is not strictly less); moved 7/48, 7/96 each.
  EXPECT_FALSE(st.observe(1, 0.5));
  EXPECT_DOUBLE_EQ(st.p[0], 1.0 / 8);
  EXPECT_DOUBLE_EQ(st.p[1], 7.0 / 48);
  EXPECT_DOUBLE_EQ(st.p[2], 7.0 / 24 + 7.0 / 96);  // 35/96
  EXPECT_DOUBLE_EQ(st.p[3], 35.0 / 96);
  // 3) S2: c = (1,1,1,0); L = {3}; moved 35/192 to S3: p2 = 35/192, p3 = 105/192.
  EXPECT_FALSE(st.observe(2, 0.5));
  EXPECT_DOUBLE_EQ(st.p[2], 35.0 / 192);
  EXPECT_DOUBLE_EQ(st.p[3], 105.0 / 192);
  // 4) S3: c = (1,1,1,1); L empty: p unchanged; every state has occurred: reset to c = (0,0,0,0).
  EXPECT_TRUE(st.observe(3, 0.5));
  EXPECT_DOUBLE_EQ(st.p[3], 105.0 / 192);
  EXPECT_EQ((std::array<int, 4>{st.c[0], st.c[1], st.c[2], st.c[3]}), (std::array<int, 4>{0, 0, 0, 0}));
  // 5) S3 again: c = (0,0,0,1); L = {0,1,2}; moved 105/384, 35/384 to each.
  EXPECT_FALSE(st.observe(3, 0.5));
  EXPECT_DOUBLE_EQ(st.p[3], 105.0 / 384);
  EXPECT_DOUBLE_EQ(st.p[0], 1.0 / 8 + 35.0 / 384);
  EXPECT_DOUBLE_EQ(st.p[1], 7.0 / 48 + 35.0 / 384);
  EXPECT_DOUBLE_EQ(st.p[2], 35.0 / 192 + 35.0 / 384);
  double sum = 0;
  for (int i = 0; i < 4; ++i) sum += st.p[static_cast<std::size_t>(i)];
  EXPECT_DOUBLE_EQ(sum, 1.0);
}

TEST(AdaptiveState, LambdaZeroNeverChangesProbabilities) {
  AdaptiveState st(4);
  for (int s : {0, 0, 1, 3, 2, 2, 0}) st.observe(s, 0.0);
  for (int i = 0; i < 4; ++i) EXPECT_EQ(st.p[static_cast<std::size_t>(i)], 0.25);
}

TEST(AdaptiveState, DrawNeverPicksAZeroProbabilityState) {
  AdaptiveState st(4);
  st.p = {};
  st.p[2] = 1.0;
  Rng rng(3);
  for (int i = 0; i < 1000; ++i) EXPECT_EQ(st.draw(rng), 2);
}

TEST(Selector, FixedBlockEveryBlockIsAPermutation) {
  Rng rng(1);
  for (int run = 0; run < 200; ++run) {
    const auto s = states_of(Algorithm::fixed_block, 20, 0.5, rng);
    for (int b = 0; b < 5; ++b) {
      std::set<int> block(s.begin() + 4 * b, s.begin() + 4 * b + 4);
      EXPECT_EQ(block, (std::set<int>{0, 1, 2, 3}));
    }
  }
}

TEST(Selector, FixedBalancedCountsDifferByAtMostOne) {
  Rng rng(2);
  std::array<int, 4> extra_count{};  // which states get the extra occurrences when K does not divide N
  for (int n : {20, 21, 22, 23, 3, 1}) {
    for (int run = 0; run < 300; ++run) {
      const auto s = states_of(Algorithm::fixed_balanced, n, 0.5, rng);
      std::array<int, 4> c{};
      for (int x : s) ++c[static_cast<std::size_t>(x)];
      const auto [lo, hi] = std::minmax_element(c.begin(), c.end());
      EXPECT_LE(*hi - *lo, 1) << "N = " << n;
      EXPECT_EQ(*lo, n / 4);
      if (n == 21) ++extra_count[static_cast<std::size_t>(hi - c.begin())];
    }
  }
  for (int e : extra_count) EXPECT_GT(e, 40);  // the extra occurrence goes to every state
}

TEST(Selector, FixedBalancedOrderIsNotAlwaysTheSame) {
  Rng rng(9);
  std::set<std::vector<int>> seen;
  for (int run = 0; run < 50; ++run) seen.insert(states_of(Algorithm::fixed_balanced, 20, 0.5, rng));
  EXPECT_GT(seen.size(), 45u);
}

TEST(Selector, NextProbabilitiesFollowTheHistory) {
  Rng rng(5);
  Selector block(Algorithm::fixed_block, 4, 20, 0.5);
  block.reset(rng);
  EXPECT_DOUBLE_EQ(block.next_probabilities()[0], 0.25);
  const int first = block.next(rng);
  auto p = block.next_probabilities();
  EXPECT_EQ(p[static_cast<std::size_t>(first)], 0.0);
  for (int i = 0; i < 4; ++i) {
    if (i != first) {
      EXPECT_DOUBLE_EQ(p[static_cast<std::size_t>(i)], 1.0 / 3);
    }
  }
  Selector adaptive(Algorithm::adaptive, 4, 20, 0.5);
  adaptive.reset(rng);
  const int s = adaptive.next(rng);
  EXPECT_DOUBLE_EQ(adaptive.next_probabilities()[static_cast<std::size_t>(s)], 0.125);
}

TEST(Selector, RejectsBadSettings) {
  EXPECT_THROW(Selector(Algorithm::adaptive, 4, 20, 1.5), feint::UsageError);
  EXPECT_THROW(Selector(Algorithm::adaptive, 4, 20, -0.1), feint::UsageError);
  EXPECT_THROW(Selector(Algorithm::random, 4, 0, 0.5), feint::UsageError);
  EXPECT_THROW(Selector(Algorithm::random, 0, 20, 0.5), feint::UsageError);
  EXPECT_THROW(Selector(Algorithm::random, kMaxStates + 1, 20, 0.5), feint::UsageError);
}

TEST(Names, RoundTripAndRejectUnknown) {
  for (auto a : {Algorithm::random, Algorithm::fixed_block, Algorithm::fixed_balanced,
                 Algorithm::adaptive}) {
    EXPECT_EQ(parse_algorithm(to_string(a)), a);
  }
  EXPECT_EQ(parse_algorithm(" Fixed_Block "), Algorithm::fixed_block);
  EXPECT_THROW(parse_algorithm("fixed"), feint::UsageError);
  EXPECT_EQ(parse_target_order("Balanced"), TargetOrder::balanced);
  EXPECT_THROW(parse_target_order("left"), feint::UsageError);
}

TEST(GenerateRun, OptimalIsAlwaysMainAndVersionsFollowTheAlgorithm) {
  RunSettings s;
  s.algorithm = Algorithm::fixed_balanced;
  s.iterations = 20;
  s.targets = TargetOrder::balanced;
  Rng rng(77);
  for (int r = 0; r < 100; ++r) {
    const auto run = generate_run(s, rng);
    ASSERT_EQ(run.size(), 20u);
    std::map<int, std::array<int, 2>> versions;
    int left = 0;
    for (const auto& it : run) {
      if (it.strategy == Strategy::optimal) {
        EXPECT_EQ(it.variant, Variant::main);
      }
      ++versions[static_cast<int>(it.strategy)][static_cast<std::size_t>(it.variant)];
      left += it.target == Target::left ? 1 : 0;
    }
    EXPECT_EQ(left, 10);  // balanced targets
    for (int st = 0; st < 3; ++st) {  // 5 occurrences each: versions split 2/3 or 3/2
      const auto v = versions[st];
      EXPECT_EQ(v[0] + v[1], 5);
      EXPECT_LE(std::abs(v[0] - v[1]), 1);
    }
  }
}

TEST(GenerateRun, RandomTargetsAndVersionsAreFairCoins) {
  RunSettings s;
  s.algorithm = Algorithm::random;
  Rng rng(123);
  int right = 0, v2 = 0, deceptive = 0, total = 0;
  for (int r = 0; r < 2000; ++r) {
    for (const auto& it : generate_run(s, rng)) {
      ++total;
      right += it.target == Target::right ? 1 : 0;
      if (it.strategy != Strategy::optimal) {
        ++deceptive;
        v2 += it.variant == Variant::v2 ? 1 : 0;
      }
    }
  }
  EXPECT_NEAR(static_cast<double>(right) / total, 0.5, 4 * 0.5 / std::sqrt(total));
  EXPECT_NEAR(static_cast<double>(v2) / deceptive, 0.5, 4 * 0.5 / std::sqrt(deceptive));
}
