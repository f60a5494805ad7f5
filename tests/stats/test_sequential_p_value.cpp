// Besag & Clifford's sequential Monte Carlo p-value (stats::SequentialPValue) and the labelling
// visitor that can stop (stats::for_each_labelling_while): worked sequences by hand, and the
// p-value's exactness under the null, P(p <= u) = u at the values it can take, by simulation.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <vector>

#include "feint/error.hpp"
#include "feint/rng.hpp"
#include "feint/stats/permutation.hpp"

using feint::stats::SequentialPValue;

TEST(SequentialPValue, WorkedSequences) {
  // h = 3, at most 10 draws (n = 11). Reaching draws 2, 4 and 5: stopped after l = 5, p = 3 / 5.
  SequentialPValue a(3, 11);
  for (const bool r : {false, true, false, true}) a.add(r);
  EXPECT_FALSE(a.done());
  EXPECT_DOUBLE_EQ(a.p(), 3.0 / 5);  // so far: (g + 1) / (l + 1) = 3 / 5
  a.add(true);
  EXPECT_TRUE(a.stopped_early());
  EXPECT_TRUE(a.done());
  EXPECT_DOUBLE_EQ(a.p(), 3.0 / 5);  // h / l
  EXPECT_EQ(a.labellings(), 6u);
  a.add(true);  // ignored once done
  EXPECT_EQ(a.labellings(), 6u);
  EXPECT_DOUBLE_EQ(a.p(), 3.0 / 5);
  // All 10 draws with 2 reaching: not stopped early, p = (g + 1) / n = 3 / 11.
  SequentialPValue b(3, 11);
  for (int i = 0; i < 10; ++i) b.add(i == 3 || i == 8);
  EXPECT_TRUE(b.done());
  EXPECT_FALSE(b.stopped_early());
  EXPECT_DOUBLE_EQ(b.p(), 3.0 / 11);
  EXPECT_EQ(b.labellings(), 11u);
  // h = 0: never stops early; the fixed-n p-value (g + 1) / n = 8 / 11.
  SequentialPValue c(0, 11);
  for (int i = 0; i < 10; ++i) c.add(i < 7);
  EXPECT_FALSE(c.stopped_early());
  EXPECT_DOUBLE_EQ(c.p(), 8.0 / 11);
  EXPECT_THROW(SequentialPValue(3, 1), feint::UsageError);
}

// Under the null the observed statistic and the sampled ones are i.i.d. (here uniform): the
// sequential p-value is exact, P(p <= u) = u at every value u it can take (Besag & Clifford 1991).
// 200 000 null runs with h = 5, n = 200; each checked rate has a standard error below 0.001 and is
// asked to lie within 4.5 of them. The fixed-n formula (g + 1) / (l + 1) in place of h / l at the
// stop is caught: it gives P(p <= 5 / 20) = 5 / 23 = 0.217 instead of 0.25.
TEST(SequentialPValue, ExactUnderTheNull) {
  const std::uint64_t h = 5, n = 200;
  const int runs = 200000;
  feint::Rng rng(20261127);
  std::vector<double> p(runs);
  for (int k = 0; k < runs; ++k) {
    SequentialPValue s(h, n);
    const double observed = rng.uniform();
    while (!s.done()) s.add(rng.uniform() >= observed);
    p[static_cast<std::size_t>(k)] = s.p();
  }
  // Values it can take: h / l (stopped at draw l), (g + 1) / n (all n - 1 drawn, g < h reaching).
  for (const double u : {5.0 / 5, 5.0 / 6, 5.0 / 10, 5.0 / 20, 5.0 / 50, 5.0 / 100, 5.0 / 199, 5.0 / 200, 3.0 / 200,
                         1.0 / 200}) {
    int below = 0;
    for (const double x : p) below += x <= u * (1 + 1e-12);
    const double rate = static_cast<double>(below) / runs;
    EXPECT_NEAR(rate, u, 4.5 * std::sqrt(u * (1 - u) / runs) + 1e-12) << "u = " << u;
  }
}

TEST(ForEachLabellingWhile, StopsSampledLabellingsButNeverAnEnumeration) {
  const std::vector<std::size_t> five = {0, 1, 2, 3, 4};
  int visits = 0;
  // C(10, 5) = 252 <= 10 000: enumerated whatever the answer.
  EXPECT_TRUE(feint::stats::every_labelling(10, 5, 9999));
  auto l = feint::stats::for_each_labelling_while(10, five, 9999, 1, [&](std::span<const std::size_t>) {
    ++visits;
    return false;
  });
  EXPECT_TRUE(l.exact);
  EXPECT_EQ(l.total, 252u);
  EXPECT_EQ(visits, 252);
  // C(30, 5) > 1000: sampled; the observed labelling first, stopped at the third visit, and the
  // draws are for_each_labelling's.
  EXPECT_FALSE(feint::stats::every_labelling(30, 5, 999));
  std::vector<std::vector<std::size_t>> seen, all;
  l = feint::stats::for_each_labelling_while(30, five, 999, 7, [&](std::span<const std::size_t> g) {
    seen.emplace_back(g.begin(), g.end());
    return seen.size() < 3;
  });
  EXPECT_FALSE(l.exact);
  EXPECT_EQ(l.total, 3u);
  ASSERT_EQ(seen.size(), 3u);
  EXPECT_EQ(seen[0], five);
  feint::stats::for_each_labelling(30, five, 999, 7, [&](std::span<const std::size_t> g) {
    if (all.size() < 3) all.emplace_back(g.begin(), g.end());
  });
  EXPECT_EQ(seen, all);
}
