// feint/stats/ttest.hpp - Student's t tests and TOST equivalence, as R's t.test().
//
// Every function returns a TestResult with statistic, df, p-value (Boost.Math complements, so tiny
// p-values do not underflow), confidence interval, and effect sizes (Cohen's d / d_z and Hedges' g
// with the exact correction J(df) = Gamma(df/2) / (sqrt(df/2) Gamma((df-1)/2)), df = n - 1 or
// n1 + n2 - 2; g is empty for df <= 1, where J is undefined).
//
// NaN values are dropped (paired: incomplete pairs). A test that cannot be computed returns
// computed == false with R's reason in note: "not enough observations ...", "empty group (x)",
// "data are essentially constant" (R's check stderr < 10 eps max|mean|), "infinite values in the
// data". A one-sided test's interval has one infinite bound, as R's. conf_level outside (0, 1)
// throws UsageError. Golden values: tests/golden/stats/ttest_golden.R (310 cases, within 1e-10).
#pragma once

#include <span>

#include "feint/stats/htest.hpp"

namespace feint::stats {

/// t.test(x, mu = mu). d = (mean - mu) / sd.
TestResult t_test_one_sample(std::span<const double> x, double mu, const TestOptions& options = {});

/// t.test(x, y, mu = mu): Welch's test, Welch–Satterthwaite df. d = (mean1 - mean2 - mu) / pooled sd.
TestResult t_test_welch(std::span<const double> x, std::span<const double> y,
                        const TestOptions& options = {}, double mu = 0.0);

/// t.test(x, y, var.equal = TRUE, mu = mu): pooled variance, df = n1 + n2 - 2 (a group of one value
/// is allowed, as R). d = (mean1 - mean2 - mu) / pooled sd.
TestResult t_test_student(std::span<const double> x, std::span<const double> y,
                          const TestOptions& options = {}, double mu = 0.0);

/// t.test(x, y, paired = TRUE, mu = mu): x[i] is paired with y[i] (different lengths throw
/// InvalidData). d_z = (mean(diff) - mu) / sd(diff). mean1/mean2, sd1/sd2 describe x and y.
TestResult t_test_paired(std::span<const double> x, std::span<const double> y,
                         const TestOptions& options = {}, double mu = 0.0);

/// Two one-sided tests (Schuirmann): equivalent when both t.test(x, mu = mu - delta,
/// alternative = "greater") and t.test(x, mu = mu + delta, alternative = "less") reject;
/// p = the larger of the two p-values; statistic/df are those of the one-sided test with that p;
/// the CI is the usual (1 - 2 alpha) interval (0.90 for conf_level 0.95), equivalence being shown
/// when it lies inside (mu - delta, mu + delta). `options.alternative` is ignored.
TestResult tost_one_sample(std::span<const double> x, double mu, double delta,
                           const TestOptions& options = {});

/// TOST for a difference of means (Welch or Student by `var_equal`), margin +-delta around 0.
TestResult tost_two_sample(std::span<const double> x, std::span<const double> y, double delta,
                           bool var_equal, const TestOptions& options = {});

/// TOST for paired samples, margin +-delta around 0.
TestResult tost_paired(std::span<const double> x, std::span<const double> y, double delta,
                       const TestOptions& options = {});

}  // namespace feint::stats
