// JZS Bayes factors against the exact integrals of tests/golden/bayes/make_bf_golden.R.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "feint/error.hpp"
#include "feint/stats/bayes_factor.hpp"
#include "feint/stats/ttest.hpp"
#include "golden_csv.hpp"
#include "accuracy.hpp"

using namespace feint::stats;

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

double eff_n(const feint::test::GoldenRow& row) {
  const double a = row.number("n1"), b = row.number("n2");
  return row.str("kind") == "one_sample" ? a : a * b / (a + b);
}
double eff_df(const feint::test::GoldenRow& row) {
  const double a = row.number("n1"), b = row.number("n2");
  return row.str("kind") == "one_sample" ? a - 1 : a + b - 2;
}

}  // namespace

TEST(BayesFactorGolden, ExactIntegralToOneInATrillion) {
  const feint::test::GoldenCsv golden(FEINT_SOURCE_DIR "/tests/golden/bayes/bf_golden.csv");
  const auto& rows = golden.rows();
  ASSERT_GE(rows.size(), 150u);
  std::size_t large_t = 0, n2 = 0, n500 = 0, one_sided = 0, interval = 0;
  double worst = 0;
  for (const auto& row : rows) {
    const double t = row.number("t"), r = row.number("r");
    const double lo = row.number("lo"), hi = row.number("hi");
    const std::string what = row.str("kind") + " t=" + row.str("t") + " n1=" + row.str("n1") +
                             " n2=" + row.str("n2") + " [" + row.str("lo") + "," + row.str("hi") + "]";
    const double got = jzs_log_bf(t, eff_n(row), eff_df(row), r, lo, hi);
    const double want = row.number("log_bf");
    // relative error of BF = |exp(got - want) - 1| ~ |got - want|. The golden is R's integrate at
    // rel.tol 1e-12; measured: 2.3e-13 (the BF), 1.4e-10 (its complement, a difference of two
    // integrals when the interval holds most of the mass).
    EXPECT_LT(std::fabs(std::expm1(got - want)), 1e-12) << what << " got " << got << " want " << want;
    worst = std::max(worst, std::fabs(std::expm1(got - want)));
    feint::test::record("Bayes factor log BF (exact integral)", got, want, what);
    if (auto c = row.num("log_bf_complement")) {
      const double gc = jzs_log_bf_complement(t, eff_n(row), eff_df(row), r, lo, hi);
      feint::test::record("Bayes factor complement log BF (exact integral)", gc, *c, what);
      EXPECT_LT(std::fabs(std::expm1(gc - *c)), 3e-10) << what << " (complement)";
    }
    large_t += std::fabs(t) > 20;
    n2 += row.number("n1") == 2;
    n500 += row.number("n1") >= 250;
    one_sided += (lo == 0 || hi == 0);
    interval += std::isfinite(lo) && std::isfinite(hi);
  }
  EXPECT_GT(large_t, 20u);
  EXPECT_GT(n2, 10u);
  EXPECT_GT(n500, 10u);
  EXPECT_GT(one_sided, 30u);
  EXPECT_GT(interval, 10u);
  std::printf("JZS Bayes factors: %zu golden cases, max relative error of BF %.2e\n", rows.size(), worst);
}

TEST(BayesFactor, WholeLineIsTheWeightedSumOfTheTwoHalves) {
  // BF_full = P(delta > 0) BF_+ + P(delta < 0) BF_- with P = 1/2 each (the prior is symmetric).
  for (double t : {-3.0, 0.2, 2.5, 9.0}) {
    const double full = jzs_log_bf(t, 20, 19);
    const double up = jzs_log_bf(t, 20, 19, kJzsMediumScale, 0, kInf);
    const double down = jzs_log_bf(t, 20, 19, kJzsMediumScale, -kInf, 0);
    EXPECT_NEAR(std::exp(full), 0.5 * std::exp(up) + 0.5 * std::exp(down), 1e-9 * std::exp(full));
  }
}

TEST(BayesFactor, FromTTestResultsAndAlternatives) {
  const std::vector<double> x{5.1, 4.8, 6.0, 5.5, 5.9, 6.3, 5.2, 4.9};
  const std::vector<double> y{4.1, 4.5, 4.0, 5.2, 4.4, 3.9, 4.8};
  TestResult one = t_test_one_sample(x, 5.0);
  add_bayes_factor(one);
  ASSERT_TRUE(one.bf10);
  EXPECT_NEAR(*one.log_bf10, jzs_log_bf(*one.statistic, 8, 7), 1e-12);
  EXPECT_NEAR(*one.bf01 * *one.bf10, 1.0, 1e-12);
  // Welch's test gets the pooled-t (ttestBF) Bayes factor.
  TestResult welch = t_test_welch(x, y);
  TestResult student = t_test_student(x, y);
  add_bayes_factor(welch);
  add_bayes_factor(student);
  ASSERT_TRUE(welch.bf10 && student.bf10);
  EXPECT_NEAR(*welch.log_bf10, *student.log_bf10, 1e-12);
  EXPECT_NEAR(*student.log_bf10, jzs_log_bf(*student.statistic, 8.0 * 7 / 15, 13), 1e-10);
  // one-sided: greater restricts delta > 0 and is larger than two-sided for a positive t
  TestResult greater = t_test_student(x, y, {Alternative::greater, 0.95});
  add_bayes_factor(greater);
  EXPECT_GT(*greater.log_bf10, *student.log_bf10);
  EXPECT_NEAR(*greater.log_bf10, jzs_log_bf(*student.statistic, 8.0 * 7 / 15, 13, kJzsMediumScale, 0, kInf), 1e-10);
  // not computed: no Bayes factor
  TestResult bad = t_test_one_sample(std::vector<double>{1.0}, 0.0);
  add_bayes_factor(bad);
  EXPECT_FALSE(bad.bf10);
}

TEST(BayesFactor, RejectsBadArguments) {
  EXPECT_THROW(jzs_log_bf(1, 10, 9, 0), feint::UsageError);
  EXPECT_THROW(jzs_log_bf(1, 10, 9, -1), feint::UsageError);
  EXPECT_THROW(jzs_log_bf(1, 0, 9), feint::UsageError);
  EXPECT_THROW(jzs_log_bf(std::nan(""), 10, 9), feint::InvalidData);
  EXPECT_THROW(jzs_log_bf(1, 10, 9, 0.7, 1, 1), feint::UsageError);
  EXPECT_THROW(jzs_bf_one_sample(1, 1), feint::UsageError);
  EXPECT_THROW(jzs_bf_interval_null(1, 10, 9, 0), feint::UsageError);
}

TEST(BayesFactor, NullEvidenceGrowsWithNAndLargeTIsFinite) {
  // t = 0: BF01 grows like sqrt(N) (Rouder et al. 2009, fig. 2).
  double prev = 0;
  for (std::size_t n : {10u, 40u, 160u, 640u, 2560u}) {
    const double bf01 = jzs_bf_one_sample(0.0, n).bf01();
    EXPECT_GT(bf01, prev);
    prev = bf01;
  }
  EXPECT_GT(prev, 30.0);
  // t = 40, n = 500: BF10 ~ e^350 is finite in logs (p(t | 0) ~ (1 + t^2/nu)^(-250) ~ e^-359)
  const BayesFactor big = jzs_bf_one_sample(40, 500);
  EXPECT_TRUE(std::isfinite(big.log_bf10));
  EXPECT_GT(big.log_bf10, 300);
  EXPECT_LT(big.log_bf10, 360);
  // an interval null [-0.1, 0.1] at t = 0, n = 500: evidence for the interval (BF10 < 1/3)
  EXPECT_LT(jzs_bf_interval_null(0, 500, 499, 0.1).bf10(), 1.0 / 3);
}


// One-sided Bayes factors at any t and n (docs/bayes-factors.md). They are computed as Rouder's g
// integral times a skew-t factor; three independent checks:
//  1. where the direct integral over the noncentral t likelihood is tractable (an interval
//     [0, 1e12] goes through it; the prior mass beyond 1e12 is 5e-13), the two agree to 1e-8;
//  2. the halves add up to the whole line, BF_full = (BF_+ + BF_-) / 2, at |t| up to 1e4 and n up
//     to 1e5, and the side the data point to carries the evidence;
//  3. far in the tail the side against the data tends to 2 Cauchy(0; r) / sqrt(n nu): the likelihood
//     ratio falls like exp(sqrt(n nu) delta) below delta = 0.
// A metric far from its reference (t ~ 500 at n = 30) once made the one-sided integral run for
// minutes: such a test then hangs, and ctest's timeout fails it.
TEST(BayesFactor, OneSidedAgreesWithTheDirectIntegralAndHoldsAtExtremeTAndN) {
  constexpr double kFar = 1e12;
  for (double n : {3.0, 30.0, 1000.0}) {
    for (double t : {-37.0, -2.0, 0.5, 4.0, 50.0}) {
      const double up = jzs_log_bf(t, n, n - 1, kJzsMediumScale, 0, kInf);
      const double down = jzs_log_bf(t, n, n - 1, kJzsMediumScale, -kInf, 0);
      EXPECT_LT(std::fabs(std::expm1(up - jzs_log_bf(t, n, n - 1, kJzsMediumScale, 0, kFar))), 1e-8)
          << "t=" << t << " n=" << n;
      EXPECT_LT(std::fabs(std::expm1(down - jzs_log_bf(t, n, n - 1, kJzsMediumScale, -kFar, 0))), 1e-8)
          << "t=" << t << " n=" << n;
    }
  }
  for (double n : {3.0, 30.0, 1000.0, 1e5}) {
    for (double t : {-1e4, -500.0, -37.0, 4.0, 50.0, 500.0, 5000.0, 1e4}) {
      const double nu = n - 1;
      const double full = jzs_log_bf(t, n, nu);
      const double up = jzs_log_bf(t, n, nu, kJzsMediumScale, 0, kInf);
      const double down = jzs_log_bf(t, n, nu, kJzsMediumScale, -kInf, 0);
      ASSERT_TRUE(std::isfinite(full) && std::isfinite(up) && std::isfinite(down))
          << "t=" << t << " n=" << n;
      const double hi = std::max(up, down);
      const double halves = hi + std::log(0.5 * std::exp(up - hi) + 0.5 * std::exp(down - hi));
      EXPECT_LT(std::fabs(std::expm1(halves - full)), 1e-9)
          << "t=" << t << " n=" << n << ": log BF full " << full << ", halves " << halves;
      EXPECT_GT(t > 0 ? up : down, t > 0 ? down : up) << "t=" << t << " n=" << n;
      if (n >= 1000 && std::fabs(t) >= 5000) {
        const double against = t > 0 ? down : up;
        const double tail = std::log(2 / (M_PI * kJzsMediumScale) / std::sqrt(n * nu));
        EXPECT_NEAR(against, tail, 0.01) << "t=" << t << " n=" << n;
      }
    }
  }
}
