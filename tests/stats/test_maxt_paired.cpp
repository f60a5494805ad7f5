// The sign-flip step-down maxT of paired t tests (feint/stats/permutation.hpp,
// maxt_step_down_paired): complete enumeration against R's paired t.test over every sign vector
// (tests/golden/stats/maxt_paired_golden.R), sampled sign vectors against the enumeration, the
// family-wise error rate of a null with dependent iterations, and the rejections.
#include <gtest/gtest.h>

#include <boost/math/distributions/binomial.hpp>
#include <cmath>
#include <map>

#include "feint/error.hpp"
#include "feint/rng.hpp"
#include "feint/stats/permutation.hpp"
#include "feint/stats/ttest.hpp"
#include "accuracy.hpp"
#include "golden_csv.hpp"

namespace {

using feint::stats::Alternative;
using feint::stats::maxt_step_down_paired;
using feint::stats::MaxTOptions;
using feint::stats::MaxTResult;

struct Case {
  std::vector<double> differences;
  std::size_t columns = 0;
  MaxTOptions options;
  std::vector<const feint::test::GoldenRow*> rows;
};

std::map<std::string, Case> golden_cases(const feint::test::GoldenCsv& csv) {
  std::map<std::string, Case> cases;
  for (const auto& row : csv.rows()) {
    Case& c = cases[row.str("case")];
    if (c.rows.empty()) {
      c.differences = row.numbers("differences");
      c.columns = static_cast<std::size_t>(row.number("columns"));
      const std::string a = row.str("alternative");
      c.options.alternative = a == "greater" ? Alternative::greater : a == "less" ? Alternative::less : Alternative::two_sided;
    }
    c.rows.push_back(&row);
  }
  return cases;
}

TEST(MaxTPaired, MatchesCompleteEnumerationWithRsPairedTTest) {
  const feint::test::GoldenCsv csv(feint::test::golden_path("maxt_paired_golden.csv"));
  const auto cases = golden_cases(csv);
  // 7 cases on 6 data sets (paired_greater reuses paired_two_sided's): complete, missing pairs,
  // untestable columns, unbalanced pairs per column, dependent iterations, zero differences and ties.
  ASSERT_EQ(cases.size(), 7u);
  for (const auto& [name, c] : cases) {
    SCOPED_TRACE(name);
    const MaxTResult r = maxt_step_down_paired(c.differences, c.columns, c.options);
    EXPECT_TRUE(r.exact);
    for (const auto* row : c.rows) {
      const auto j = static_cast<std::size_t>(row->number("column"));
      EXPECT_EQ(r.labellings, static_cast<std::uint64_t>(row->number("labellings")));
      const auto t = row->num("t");
      ASSERT_EQ(r.statistic[j].has_value(), t.has_value()) << "column " << j;
      if (!t) {
        EXPECT_FALSE(r.p_adjusted[j]);
        continue;
      }
      feint::test::record("maxT paired: t", *r.statistic[j], *t, name);
      EXPECT_NEAR(*r.statistic[j], *t, 1e-12 * std::fabs(*t)) << "column " << j;
      // Counts over the same sign vectors: the p-values are the same fractions.
      EXPECT_NEAR(*r.p_raw[j], row->number("p_raw"), 1e-15) << "column " << j;
      EXPECT_NEAR(*r.p_adjusted[j], row->number("p_adjusted"), 1e-15) << "column " << j;
    }
  }
}

TEST(MaxTPaired, TheStatisticIsThePairedTOfTheTable) {
  // The differences of one column are the pairs' differences: the same t as stats::t_test_paired.
  const std::vector<double> a = {0.91, 1.40, 0.22, 0.75, 1.90, 0.33}, b = {0.50, 1.10, 0.41, 0.20, 1.05, 0.30};
  std::vector<double> d;
  for (std::size_t i = 0; i < a.size(); ++i) d.push_back(a[i] - b[i]);
  const MaxTResult r = maxt_step_down_paired(d, 1);
  const auto t = feint::stats::t_test_paired(a, b, {});
  ASSERT_TRUE(r.statistic[0]);
  EXPECT_NEAR(*r.statistic[0], *t.statistic, 1e-13 * std::fabs(*t.statistic));
  // One test: 2^6 = 64 sign vectors; the adjusted p is the test's own sign-flip p, and (two-sided)
  // the vector of all flips reaches it as the observed one does: p >= 2/64.
  EXPECT_EQ(r.labellings, 64u);
  EXPECT_EQ(*r.p_adjusted[0], *r.p_raw[0]);
  EXPECT_GE(*r.p_raw[0], 2.0 / 64);
}

TEST(MaxTPaired, SampledSignsAgreeWithEnumerationAndAreReproducible) {
  const feint::test::GoldenCsv csv(feint::test::golden_path("maxt_paired_golden.csv"));
  const auto cases = golden_cases(csv);
  const Case& c = cases.at("paired_less_missing");  // 1024 sign vectors
  MaxTOptions o = c.options;
  o.permutations = 500;
  const MaxTResult a = maxt_step_down_paired(c.differences, c.columns, o);
  EXPECT_FALSE(a.exact);
  EXPECT_EQ(a.labellings, 501u);
  for (const auto* row : c.rows) {
    const auto j = static_cast<std::size_t>(row->number("column"));
    const double p = row->number("p_adjusted");
    EXPECT_NEAR(*a.p_adjusted[j], p, 4 * std::sqrt(p * (1 - p) / 500) + 1.0 / 501) << "column " << j;
  }
  const MaxTResult b = maxt_step_down_paired(c.differences, c.columns, o);
  for (std::size_t j = 0; j < c.columns; ++j) EXPECT_EQ(a.p_adjusted[j], b.p_adjusted[j]);
}

// A standard normal deviate (Box–Muller on the header-only uniforms: the stats tests link no
// other module).
double normal(feint::Rng& rng) {
  const double u = 1.0 - rng.uniform(), v = rng.uniform();
  return std::sqrt(-2.0 * std::log(u)) * std::cos(2.0 * M_PI * v);
}

// Under the null (differences symmetric about 0) with strongly dependent iterations (a participant
// effect on every difference), the family-wise error of the adjusted p-values is at most alpha.
TEST(MaxTPaired, ControlsTheFamilyWiseErrorUnderADependentNull) {
  constexpr int kStudies = 1000, kParticipants = 12, kIterations = 6;
  feint::Rng rng(77);
  int rejected = 0;
  MaxTOptions o;
  o.permutations = 999;
  for (int s = 0; s < kStudies; ++s) {
    std::vector<double> d;
    for (int i = 0; i < kParticipants; ++i) {
      const double person = 1.5 * normal(rng);
      for (int j = 0; j < kIterations; ++j) d.push_back(person + normal(rng));
    }
    o.seed = 1000 + static_cast<std::uint64_t>(s);
    const MaxTResult r = maxt_step_down_paired(d, kIterations, o);
    bool any = false;
    for (const auto& p : r.p_adjusted) any |= p && *p < 0.05;
    rejected += any;
  }
  // P(X >= 70 | n = 1000, p = .05) = 0.003: a true FWER of 5 % passes, a Bonferroni-free
  // per-test 5 % (about 1 - .95^6 ~ 26 % with independent tests) fails.
  EXPECT_LT(rejected, 70);
  EXPECT_GT(rejected, 25);  // not uselessly conservative: P(X <= 25 | .05) = 0.00003
}

TEST(MaxTPaired, RejectsWhatItCannotAdjust) {
  EXPECT_THROW(maxt_step_down_paired(std::vector<double>{1, 2, 3}, 0), feint::UsageError);
  EXPECT_THROW(maxt_step_down_paired(std::vector<double>{1, 2, 3}, 2), feint::UsageError);
  EXPECT_THROW(maxt_step_down_paired(std::vector<double>{}, 1), feint::UsageError);
  MaxTOptions o;
  o.permutations = 0;
  EXPECT_THROW(maxt_step_down_paired(std::vector<double>{1, 2}, 1, o), feint::UsageError);
}

}  // namespace
