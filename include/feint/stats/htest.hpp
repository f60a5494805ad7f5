// feint/stats/htest.hpp - the one result type every hypothesis test returns.
//
// Modelled on R's `htest` (and broom's tidy columns): whatever the test, the same fields, so every
// report writer renders every test. Fields that do not apply to a test are empty (nullopt), never
// 0 or NaN. A test that cannot be computed (n < 2, constant data, an empty group) has
// `computed == false` and says why in `note`; its numeric results are empty.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <utility>

namespace feint::stats {

/// The alternative hypothesis, as R's `alternative =` argument.
enum class Alternative { two_sided, greater, less };

/// "two.sided", "greater", "less" (R's spelling).
std::string_view to_string(Alternative alternative) noexcept;
/// Parses R's spelling (also "two-sided"); throws UsageError otherwise.
Alternative parse_alternative(std::string_view text);

/// Settings shared by every test.
struct TestOptions {
  Alternative alternative = Alternative::two_sided;
  double conf_level = 0.95;  ///< in (0, 1)
};

struct TestResult {
  // What was run.
  std::string test;    ///< one_sample_t, welch_t, student_t, paired_t, tost,
                       ///< wilcoxon_signed_rank, mann_whitney, anova, welch_anova, kruskal_wallis
  std::string method;  ///< R's `method` string, e.g. "Welch Two Sample t-test"
  Alternative alternative = Alternative::two_sided;
  double conf_level = 0.95;
  std::optional<double> mu;  ///< the null value (reference mean, or hypothesised difference)
  std::optional<double> margin;  ///< TOST only: the equivalence margin delta (H1: |true - mu| < delta)

  // The samples (group 1 = x, group 2 = y; one-sample tests fill only group 1).
  std::size_t n1 = 0;
  std::size_t n2 = 0;
  std::optional<double> mean1, mean2, sd1, sd2;
  std::optional<double> median1, median2, iqr1, iqr2;

  // The result.
  std::optional<double> estimate;   ///< mean (one-sample, paired: mean difference) or mean1 - mean2
  std::optional<double> statistic;  ///< t, V, W, F, chi-squared ...
  std::string statistic_name;       ///< "t", "V", "W", "F", "chi-squared"
  std::optional<double> df;         ///< R's `parameter` (numerator df for F tests)
  std::optional<double> df2;        ///< denominator df of F tests
  /// From Boost.Math complements: p = 1e-300 is computed, not rounded to 0 (subnormal values such
  /// as 4e-310 occur, as in R). 0 only when below the smallest subnormal double; report writers
  /// print p < 2.2e-308 as "< 2.2e-308".
  std::optional<double> p_value;
  std::optional<double> p_adjusted; ///< filled by a multiple-comparison step, not by the test
  /// The interval at `conf_level`; a one-sided test has one infinite bound (-inf or +inf), as R.
  std::optional<double> conf_low, conf_high;

  // Effect sizes.
  std::optional<double> cohen_d;        ///< d (one-sample, two-sample pooled) or d_z (paired)
  std::optional<double> hedges_g;       ///< d times the exact gamma-function correction J(df)
  std::optional<double> rank_biserial;  ///< rank tests only
  std::optional<double> r_squared;      ///< ANOVA: R^2 (eta squared) = SS_between / SS_total
  /// Kruskal-Wallis: rank epsilon squared H / (n - 1) (Tomczak & Tomczak 2014; R's
  /// effectsize::rank_epsilon_squared), 0 when the groups' mean ranks are equal.
  std::optional<double> rank_epsilon_squared;
  std::optional<bool> exact;            ///< rank tests: exact distribution (true) or normal approx.
  /// Confidence intervals of the effect sizes at `conf_level` (feint/stats/effect_size.hpp):
  /// d and g from the noncentral t, r from Fisher's z, eta squared from the noncentral F.
  std::optional<double> cohen_d_low, cohen_d_high, hedges_g_low, hedges_g_high;
  std::optional<double> rank_biserial_low, rank_biserial_high;
  std::optional<double> eta_squared_low, eta_squared_high;  ///< CI of r_squared (partial eta^2)

  // Bayes factor (t tests; feint/stats/bayes_factor.hpp): JZS, Cauchy prior scale bf_prior_r,
  // H1 by `alternative` (two-sided: delta != 0; greater: delta > 0; less: delta < 0).
  std::optional<double> log_bf10;    ///< natural log of BF10 (finite where BF10 overflows)
  std::optional<double> bf10, bf01;  ///< exp(log_bf10), exp(-log_bf10)
  std::optional<double> bf_prior_r;

  bool computed = true;
  std::string note;  ///< why it could not be computed, or a warning (ties, zeros, ...)

  /// (conf_low, conf_high); SciPy's `confidence_interval()`.
  std::pair<std::optional<double>, std::optional<double>> confidence_interval() const {
    return {conf_low, conf_high};
  }

  /// A result that could not be computed, with the reason.
  static TestResult not_computable(std::string test, std::string method, std::string reason) {
    TestResult r;
    r.test = std::move(test);
    r.method = std::move(method);
    r.computed = false;
    r.note = std::move(reason);
    return r;
  }
};

}  // namespace feint::stats
