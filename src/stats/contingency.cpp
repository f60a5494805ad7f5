// A yes/no answer across three or more conditions: see feint/stats/contingency.hpp.
#include "feint/stats/contingency.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include <boost/math/distributions/chi_squared.hpp>
#include <boost/math/distributions/non_central_chi_squared.hpp>
#include <boost/math/tools/toms748_solve.hpp>
#include <fmt/format.h>

#include "feint/error.hpp"
#include "stats_detail.hpp"

namespace feint::stats {

namespace {

// R's FEXACT (fexact.c, f2xact): "TOL is chosen as the square root of the smallest relative
// spacing", added to the observed table's log probability.
constexpr double kFexactTol = 3.45254e-7;

double log_choose(std::size_t n, std::size_t k) {
  return std::lgamma(static_cast<double>(n) + 1) - std::lgamma(static_cast<double>(k) + 1) -
         std::lgamma(static_cast<double>(n - k) + 1);
}

/// A sum of many positive terms (Neumaier's compensated summation).
struct Sum {
  double s = 0, c = 0;
  void add(double v) {
    const double t = s + v;
    c += std::fabs(s) >= std::fabs(v) ? (s - t) + v : (v - t) + s;
    s = t;
  }
  double value() const { return s + c; }
};

/// The last two rows (a, b) of the enumeration with s yes answers between them: x of them in row
/// a has weight log C(a, x) + log C(b, s - x), unimodal in x, so the tables no more probable than
/// a cut are a left tail and a right tail, whose probabilities are kept as running sums.
struct LastTwoRows {
  std::size_t lo = 0, hi = 0, mode = 0;
  double log_total = 0;    // log C(a + b, s): the sum of the weights
  std::vector<double> lw;  // lw[x - lo]
  std::vector<double> left, right;  // sum of the pmf over [lo, x] and over [x, hi]

  LastTwoRows(std::size_t a, std::size_t b, std::size_t s) {
    lo = s > b ? s - b : 0;
    hi = std::min(a, s);
    log_total = log_choose(a + b, s);
    for (std::size_t x = lo; x <= hi; ++x) lw.push_back(log_choose(a, x) + log_choose(b, s - x));
    mode = lo + static_cast<std::size_t>(std::max_element(lw.begin(), lw.end()) - lw.begin());
    left.resize(lw.size());
    right.resize(lw.size());
    double run = 0;
    for (std::size_t i = 0; i < lw.size(); ++i) left[i] = run += std::exp(lw[i] - log_total);
    run = 0;
    for (std::size_t i = lw.size(); i-- > 0;) right[i] = run += std::exp(lw[i] - log_total);
  }

  /// The probability (given s) of the x whose weight is <= cut.
  double tails(double cut) const {
    const std::size_t m = mode - lo;
    // [0, m]: weights non-decreasing; the first index whose weight exceeds the cut.
    const auto l_end = std::partition_point(lw.begin(), lw.begin() + static_cast<std::ptrdiff_t>(m) + 1,
                                            [&](double w) { return w <= cut; });
    // (m, end): weights non-increasing; the first index at or below the cut.
    const auto r_begin = std::partition_point(lw.begin() + static_cast<std::ptrdiff_t>(m) + 1, lw.end(),
                                              [&](double w) { return w > cut; });
    double p = 0;
    if (l_end != lw.begin()) p += left[static_cast<std::size_t>(l_end - lw.begin()) - 1];
    if (r_begin != lw.end()) p += right[static_cast<std::size_t>(r_begin - lw.begin())];
    return p;
  }
};

/// The enumeration of Fisher's test: rows sorted by size, the two largest last.
struct FisherEnumeration {
  std::vector<std::size_t> n;             // the rows' sizes, ascending
  std::vector<std::size_t> capacity;      // capacity[r] = n[r] + ... + n[C - 1]
  std::vector<std::vector<double>> lc;    // lc[r][x] = log C(n[r], x), outer rows only
  std::vector<LastTwoRows> last;          // by s = the yes answers left for the last two rows
  double cut = 0;                         // the observed table's weight + tolerance
  double log_norm = 0;                    // log C(N, m)
  Sum p;

  void walk(std::size_t r, std::size_t s, double weight) {
    if (r + 2 == n.size()) {
      const LastTwoRows& t = last[s];
      p.add(std::exp(weight + t.log_total - log_norm) * t.tails(cut - weight));
      return;
    }
    const std::size_t rest = capacity[r + 1];
    for (std::size_t x = s > rest ? s - rest : 0; x <= std::min(n[r], s); ++x) walk(r + 1, s - x, weight + lc[r][x]);
  }
};

/// How many splits of m yes answers the outer rows (all but the last two) allow: a count by sums.
double outer_splits(const std::vector<std::size_t>& n, std::size_t m) {
  const std::size_t outer = n.size() - 2;
  const std::size_t last_two = n[outer] + n[outer + 1];
  std::vector<double> ways(m + 1, 0.0);
  ways[0] = 1;
  for (std::size_t r = 0; r < outer; ++r) {
    std::vector<double> next(m + 1, 0.0);
    for (std::size_t s = 0; s <= m; ++s)
      if (ways[s] > 0)
        for (std::size_t x = 0; x <= n[r] && s + x <= m; ++x) next[s + x] += ways[s];
    ways = std::move(next);
  }
  double total = 0;
  for (std::size_t s = 0; s <= m; ++s)
    if (m - s <= last_two) total += ways[s];
  return total;
}

/// The rows with answers.
std::vector<YesCount> answered(std::span<const YesCount> table) {
  std::vector<YesCount> rows;
  for (const auto& r : table) {
    if (r.yes > r.n) throw UsageError(fmt::format("a yes count exceeds its answers ({} of {})", r.yes, r.n));
    if (r.n > 0) rows.push_back(r);
  }
  return rows;
}

}  // namespace

TestResult fisher_exact_conditions(std::span<const YesCount> table, std::uint64_t max_tables) {
  const char* method = "Fisher's Exact Test for Count Data";
  std::vector<YesCount> rows = answered(table);
  if (rows.size() < 2)
    return TestResult::not_computable("fisher_exact_conditions", method, "fewer than two conditions have answers");
  std::sort(rows.begin(), rows.end(), [](const YesCount& x, const YesCount& y) { return x.n < y.n; });
  FisherEnumeration e;
  std::size_t big_n = 0, m = 0;
  double observed = 0;
  for (const auto& r : rows) {
    e.n.push_back(r.n);
    big_n += r.n;
    m += r.yes;
    observed += log_choose(r.n, r.yes);
  }
  const double splits = outer_splits(e.n, m);
  if (splits > static_cast<double>(max_tables))
    return TestResult::not_computable(
        "fisher_exact_conditions", method,
        fmt::format("not computed exactly: the margins of these {} answers in {} conditions allow about {:.2g} splits "
                    "of the yes answers to enumerate, more than feint's limit of {}; read the chi-square test",
                    big_n, rows.size(), splits, max_tables));
  e.capacity.assign(e.n.size() + 1, 0);
  for (std::size_t r = e.n.size(); r-- > 0;) e.capacity[r] = e.capacity[r + 1] + e.n[r];
  for (std::size_t r = 0; r + 2 < e.n.size(); ++r) {
    e.lc.emplace_back();
    for (std::size_t x = 0; x <= e.n[r]; ++x) e.lc.back().push_back(log_choose(e.n[r], x));
  }
  const std::size_t a = e.n[e.n.size() - 2], b = e.n.back();
  for (std::size_t s = 0; s <= std::min(m, a + b); ++s) e.last.emplace_back(a, b, s);
  e.cut = observed + kFexactTol;
  e.log_norm = log_choose(big_n, m);
  e.walk(0, m, 0.0);
  TestResult r;
  r.test = "fisher_exact_conditions";
  r.method = method;
  r.n1 = big_n;
  r.p_value = std::min(1.0, e.p.value());
  return r;
}

TestResult chisq_independence(std::span<const YesCount> table, double conf_level) {
  detail::check_conf_level(conf_level);
  const char* method = "Pearson's Chi-squared test";
  const std::vector<YesCount> rows = answered(table);
  if (rows.size() < 2)
    return TestResult::not_computable("chisq_test", method, "fewer than two conditions have answers");
  double big_n = 0, yes = 0;
  for (const auto& r : rows) {
    big_n += static_cast<double>(r.n);
    yes += static_cast<double>(r.yes);
  }
  if (yes == 0 || yes == big_n)
    return TestResult::not_computable("chisq_test", method,
                                      yes == 0 ? "every answer is no (R: NaN)" : "every answer is yes (R: NaN)");
  double x2 = 0;
  bool small = false;
  for (const auto& r : rows) {
    const double n = static_cast<double>(r.n), o_yes = static_cast<double>(r.yes);
    const double e_yes = n * yes / big_n, e_no = n * (big_n - yes) / big_n;
    x2 += (o_yes - e_yes) * (o_yes - e_yes) / e_yes + ((n - o_yes) - e_no) * ((n - o_yes) - e_no) / e_no;
    small = small || e_yes < 5 || e_no < 5;
  }
  TestResult r;
  r.test = "chisq_test";
  r.method = method;
  r.conf_level = conf_level;
  r.n1 = static_cast<std::size_t>(big_n);
  r.statistic = x2;
  r.statistic_name = "chi-squared";
  r.df = static_cast<double>(rows.size() - 1);
  r.p_value = boost::math::cdf(boost::math::complement(boost::math::chi_squared(*r.df), x2));
  const CramersV v = cramers_v(x2, r.n1, rows.size(), 2, true, conf_level);
  r.estimate = v.estimate;
  r.conf_low = v.low;
  r.conf_high = v.high;
  if (small) r.note = "Chi-squared approximation may be incorrect (an expected count is below 5)";
  return r;
}

namespace {

/// The ncp of the noncentral chi-square at which pchisq(x2, df, ncp) = p (decreasing in ncp),
/// or 0 when pchisq(x2, df) <= p already (effectsize's rule).
double ncp_at(double x2, double df, double p) {
  const double at_zero = boost::math::cdf(boost::math::chi_squared(df), x2);
  if (at_zero <= p) return 0;
  auto g = [&](double ncp) { return boost::math::cdf(boost::math::non_central_chi_squared(df, ncp), x2) - p; };
  double hi = std::max(1.0, x2);
  for (int k = 0; g(hi) > 0 && k < 200; ++k) hi *= 2;
  std::uintmax_t iters = 300;
  const auto root = boost::math::tools::toms748_solve(g, 0.0, hi, boost::math::tools::eps_tolerance<double>(52), iters);
  return 0.5 * (root.first + root.second);
}

}  // namespace

CramersV cramers_v(double chi_squared, std::size_t n, std::size_t rows, std::size_t columns, bool adjust,
                   double conf_level, Alternative alternative) {
  detail::check_conf_level(conf_level);
  if (!(chi_squared >= 0) || n < 2 || rows < 2 || columns < 2)
    throw InvalidData(fmt::format("Cramér's V: X2 = {}, n = {}, a {} x {} table", chi_squared, n, rows, columns));
  if (alternative == Alternative::less) throw UsageError("Cramér's V: alternative 'less' is not meaningful (V >= 0)");
  const double nd = static_cast<double>(n), r = static_cast<double>(rows), c = static_cast<double>(columns);
  const double df = (r - 1) * (c - 1);
  // Bias correction (effectsize's .adjust_phi and the reduced dimensions of chisq_to_cramers_v).
  const double k = adjust ? r - (r - 1) * (r - 1) / (nd - 1) : r;
  const double l = adjust ? c - (c - 1) * (c - 1) / (nd - 1) : c;
  const double div = std::sqrt(std::min(k, l) - 1);
  auto v_of = [&](double x2) {  // phi^2 = X^2 / N, bias-corrected, over the reduced dimension
    const double phi2 = x2 / nd;
    return std::sqrt(adjust ? std::max(0.0, phi2 - df / (nd - 1)) : phi2) / div;
  };
  CramersV v;
  v.adjusted = adjust;
  v.conf_level = conf_level;
  v.estimate = v_of(chi_squared);
  const double level = alternative == Alternative::two_sided ? conf_level : 2 * conf_level - 1;
  const double a = (1 - level) / 2;
  v.low = v_of(ncp_at(chi_squared, df, 1 - a));
  v.high = alternative == Alternative::greater ? 1.0 : std::min(1.0, v_of(ncp_at(chi_squared, df, a)));
  return v;
}

TestResult cochran_q(std::span<const std::vector<int>> answers) {
  const char* method = "Cochran's Q test";
  if (answers.size() < 2) return TestResult::not_computable("cochran_q", method, "fewer than two participants");
  const std::size_t c = answers.front().size();
  if (c < 2) return TestResult::not_computable("cochran_q", method, "fewer than two conditions");
  std::vector<std::int64_t> g(c, 0);
  std::int64_t total = 0, sum_l2 = 0;
  for (const auto& row : answers) {
    if (row.size() != c) throw InvalidData(fmt::format("Cochran's Q: a participant with {} answers, not {}", row.size(), c));
    std::int64_t l = 0;
    for (std::size_t j = 0; j < c; ++j) {
      if (row[j] != 0 && row[j] != 1) throw InvalidData(fmt::format("Cochran's Q: answer {} is not 0 or 1", row[j]));
      g[j] += row[j];
      l += row[j];
    }
    total += l;
    sum_l2 += l * l;
  }
  const auto cc = static_cast<std::int64_t>(c);
  std::int64_t sum_g2 = 0;
  for (const auto v : g) sum_g2 += v * v;
  const std::int64_t numerator = (cc - 1) * (cc * sum_g2 - total * total);
  const std::int64_t denominator = cc * total - sum_l2;
  if (denominator == 0)
    return TestResult::not_computable("cochran_q", method,
                                      "every participant gave the same answer in every condition");
  TestResult r;
  r.test = "cochran_q";
  r.method = method;
  r.n1 = answers.size();
  r.statistic = static_cast<double>(numerator) / static_cast<double>(denominator);
  r.statistic_name = "Q";
  r.df = static_cast<double>(c - 1);
  r.p_value = boost::math::cdf(boost::math::complement(boost::math::chi_squared(*r.df), *r.statistic));
  return r;
}

}  // namespace feint::stats
