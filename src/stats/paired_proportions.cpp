// McNemar's test, exact and chi-square: see feint/stats/paired_proportions.hpp.
#include "feint/stats/paired_proportions.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <boost/math/distributions/binomial.hpp>
#include <boost/math/distributions/chi_squared.hpp>

#include "feint/stats/proportions.hpp"

namespace feint::stats {

namespace {

TestResult paired_base(const PairedYesNoTable& t, const char* test, const char* method) {
  TestResult r;
  r.test = test;
  r.method = method;
  r.n1 = r.n2 = t.pairs();
  if (t.pairs() > 0) {
    const double n = static_cast<double>(t.pairs());
    r.mean1 = static_cast<double>(t.yes_yes + t.yes_no) / n;
    r.mean2 = static_cast<double>(t.yes_yes + t.no_yes) / n;
  }
  return r;
}

double odds(double p) { return p >= 1.0 ? std::numeric_limits<double>::infinity() : p / (1.0 - p); }

}  // namespace

TestResult mcnemar_exact(const PairedYesNoTable& t, const TestOptions& options) {
  const char* method = "Exact binomial test (McNemar, discordant pairs)";
  const std::size_t m = t.yes_no + t.no_yes;
  if (m == 0)
    return TestResult::not_computable("mcnemar_exact", method, "no participant answered differently in the two conditions");
  TestResult r = paired_base(t, "mcnemar_exact", method);
  r.alternative = options.alternative;
  r.conf_level = options.conf_level;
  r.statistic = static_cast<double>(t.yes_no);
  r.statistic_name = "b";
  const boost::math::binomial_distribution<double> law(static_cast<double>(m), 0.5);
  const double b = static_cast<double>(t.yes_no);
  const double lower = boost::math::cdf(law, b);                                    // P(X <= b)
  const double upper = b == 0 ? 1.0 : boost::math::cdf(boost::math::complement(law, b - 1.0));  // P(X >= b)
  switch (options.alternative) {
    case Alternative::less: r.p_value = lower; break;
    case Alternative::greater: r.p_value = upper; break;
    default: r.p_value = std::min(1.0, 2.0 * std::min(lower, upper));
  }
  // binom.test's interval of b / (b + c): two-sided Clopper–Pearson, one-sided with one bound.
  const bool two = options.alternative == Alternative::two_sided;
  const double level = two ? options.conf_level : 2.0 * options.conf_level - 1.0;
  const Proportion p = describe_proportion(t.yes_no, m, level);
  r.estimate = t.no_yes == 0 ? std::numeric_limits<double>::infinity() : b / static_cast<double>(t.no_yes);
  r.conf_low = options.alternative == Alternative::less ? 0.0 : odds(p.exact_low);
  r.conf_high = options.alternative == Alternative::greater ? std::numeric_limits<double>::infinity() : odds(p.exact_high);
  return r;
}

TestResult mcnemar_test(const PairedYesNoTable& t, bool correct) {
  const char* method = correct ? "McNemar's Chi-squared test with continuity correction" : "McNemar's Chi-squared test";
  const double b = static_cast<double>(t.yes_no), c = static_cast<double>(t.no_yes);
  if (b + c == 0)
    return TestResult::not_computable("mcnemar", method, "no participant answered differently in the two conditions (R: NaN)");
  TestResult r = paired_base(t, "mcnemar", method);
  // R corrects only an asymmetric table (b != c): a symmetric one has X^2 = 0.
  const double d = std::abs(b - c) - (correct && b != c ? 1.0 : 0.0);
  const double x2 = d * d / (b + c);
  r.statistic = x2;
  r.statistic_name = "chi-squared";
  r.df = 1.0;
  r.p_value = x2 <= 0.0 ? 1.0 : boost::math::cdf(boost::math::complement(boost::math::chi_squared(1.0), x2));
  r.estimate = *r.mean1 - *r.mean2;
  return r;
}

}  // namespace feint::stats
