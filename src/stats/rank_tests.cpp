// Wilcoxon signed-rank and rank-sum (Mann–Whitney) tests, reproducing R 4.2's wilcox.test.
#include "feint/stats/rank_tests.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>
#include <utility>
#include <vector>

#include <boost/math/distributions/normal.hpp>
#include <fmt/format.h>

namespace feint::stats {
namespace detail {

Ranks average_ranks(std::span<const double> values) {
  const std::size_t n = values.size();
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return values[a] < values[b]; });
  Ranks r;
  r.rank.assign(n, 0.0);
  std::size_t i = 0;
  while (i < n) {
    std::size_t j = i + 1;
    while (j < n && values[order[j]] == values[order[i]]) ++j;
    // Positions i..j-1 (0-based) share the average of ranks i+1..j.
    const double avg = (static_cast<double>(i + 1) + static_cast<double>(j)) / 2.0;
    for (std::size_t k = i; k < j; ++k) r.rank[order[k]] = avg;
    const double t = static_cast<double>(j - i);
    if (j - i > 1) {
      r.ties = true;
      r.tie_sum += t * t * t - t;
    }
    i = j;
  }
  return r;
}

namespace {

// Exact-distribution size limits when the caller forces exact = true for large samples (R would
// compute them, slowly); beyond these the normal approximation runs and the note says so.
constexpr std::size_t max_exact_signrank_n = 500;
constexpr double max_exact_ranksum_work = 5e7;  // ~ (m n)^2 / 4 updates

// P(V = s), s = 0..n(n+1)/2, for n untied non-zero differences. Adding difference k either
// leaves V (negative sign) or adds k (positive sign), each with probability 1/2. For n < 50 every
// value is a dyadic rational with a numerator below 2^49, so the table is exact in double.
std::vector<double> signrank_distribution(std::size_t n) {
  const std::size_t total = n * (n + 1) / 2;
  std::vector<double> p(total + 1, 0.0);
  p[0] = 1.0;
  for (std::size_t k = 1; k <= n; ++k) {
    const std::size_t top = k * (k + 1) / 2;
    for (std::size_t s = top; s >= k; --s) p[s] = 0.5 * (p[s] + p[s - k]);
    for (std::size_t s = 0; s < k; ++s) p[s] *= 0.5;
  }
  return p;
}

// P(W = w), w = 0..m n, for samples of m and n untied values. With i x's and j y's, the largest
// value is an x with probability i/(i+j) (it then beats all j y's: W grows by j) or a y with
// probability j/(i+j). Probabilities, not counts, so nothing overflows; all terms are positive.
std::vector<double> ranksum_distribution(std::size_t m, std::size_t n) {
  // The distribution is symmetric in (m, n): iterate over the larger one.
  const std::size_t a = std::min(m, n);
  const std::size_t b = std::max(m, n);
  const std::size_t width = a * b + 1;
  std::vector<double> g((a + 1) * width, 0.0);
  auto row = [&](std::size_t i) { return g.data() + i * width; };
  for (std::size_t i = 0; i <= a; ++i) row(i)[0] = 1.0;  // no y yet: W = 0
  for (std::size_t j = 1; j <= b; ++j) {
    for (std::size_t i = 1; i <= a; ++i) {
      const double denom = static_cast<double>(i + j);
      const double px = static_cast<double>(i) / denom;
      const double py = static_cast<double>(j) / denom;
      double* cur = row(i);
      const double* prev = row(i - 1);  // already holds (i-1, j)
      const std::size_t top = i * j;
      for (std::size_t w = top; w >= j; --w) cur[w] = py * cur[w] + px * prev[w - j];
      for (std::size_t w = 0; w < j && w <= top; ++w) cur[w] = py * cur[w];
    }
  }
  return {row(a), row(a) + width};
}

// Lower tail P(X <= k) or upper tail P(X > k) of a distribution on 0..size-1 (k integral), each
// summed directly from the smallest terms up.
double tail(const std::vector<double>& p, double k, bool lower_tail) {
  const double last = static_cast<double>(p.size() - 1);
  if (lower_tail) {
    if (k < 0.0) return 0.0;
    if (k >= last) return 1.0;
    const auto upto = static_cast<std::size_t>(k);
    double sum = 0.0;
    for (std::size_t s = 0; s <= upto; ++s) sum += p[s];
    return sum;
  }
  if (k < 0.0) return 1.0;
  if (k >= last) return 0.0;
  const auto from = static_cast<std::size_t>(k) + 1;
  double sum = 0.0;
  for (std::size_t s = p.size(); s-- > from;) sum += p[s];
  return sum;
}

}  // namespace

// R rounds a non-integral q differently in the two functions: psignrank uses
// R_forceint(q + 1e-7) (round to nearest), pwilcox floor(q + 1e-7).
double psignrank(double q, std::size_t n, bool lower_tail) {
  return tail(signrank_distribution(n), std::nearbyint(q + 1e-7), lower_tail);
}

double pwilcox(double q, std::size_t m, std::size_t n, bool lower_tail) {
  return tail(ranksum_distribution(m, n), std::floor(q + 1e-7), lower_tail);
}

double quantile7(std::span<const double> sorted, double p) {
  const std::size_t n = sorted.size();
  const double index = static_cast<double>(n - 1) * p;  // 0-based
  const double lo = std::floor(index);
  const auto ilo = static_cast<std::size_t>(lo);
  const double qs = sorted[ilo];
  if (index > lo && ilo + 1 < n && sorted[ilo + 1] != qs) {
    const double h = index - lo;
    return (1.0 - h) * qs + h * sorted[ilo + 1];  // R's arithmetic, term for term
  }
  return qs;
}

}  // namespace detail

namespace {

using detail::average_ranks;

std::vector<double> drop_nan(std::span<const double> x) {
  std::vector<double> out;
  out.reserve(x.size());
  for (double v : x)
    if (!std::isnan(v)) out.push_back(v);
  return out;
}

std::optional<double> finite_or_empty(double v) {
  if (std::isfinite(v)) return v;
  return std::nullopt;
}

struct SampleDescription {
  std::optional<double> mean, sd, median, iqr;
};

// mean (with R's refinement pass), sd (n - 1), median and IQR (type 7) of a NaN-free sample.
SampleDescription describe_sample(std::vector<double> x) {
  SampleDescription d;
  const std::size_t n = x.size();
  if (n == 0) return d;
  const double nd = static_cast<double>(n);
  double sum = 0.0;
  for (double v : x) sum += v;
  double mean = sum / nd;
  if (std::isfinite(mean)) {
    double corr = 0.0;
    for (double v : x) corr += v - mean;
    mean += corr / nd;
  }
  d.mean = finite_or_empty(mean);
  if (n >= 2 && d.mean) {
    double ss = 0.0;
    for (double v : x) ss += (v - mean) * (v - mean);
    d.sd = finite_or_empty(std::sqrt(ss / (nd - 1.0)));
  }
  std::sort(x.begin(), x.end());
  d.median = finite_or_empty(detail::quantile7(x, 0.5));
  d.iqr = finite_or_empty(detail::quantile7(x, 0.75) - detail::quantile7(x, 0.25));
  return d;
}

// R's normal-approximation p-value, z already continuity-corrected and scaled.
double normal_p(double z, Alternative alternative) {
  const boost::math::normal n01;
  const double lower = boost::math::cdf(n01, z);
  const double upper = boost::math::cdf(boost::math::complement(n01, z));
  switch (alternative) {
    case Alternative::less: return lower;
    case Alternative::greater: return upper;
    case Alternative::two_sided: break;
  }
  return 2.0 * std::min(lower, upper);
}

double continuity_correction(double z, Alternative alternative) {
  switch (alternative) {
    case Alternative::greater: return 0.5;
    case Alternative::less: return -0.5;
    case Alternative::two_sided: break;
  }
  return z > 0.0 ? 0.5 : (z < 0.0 ? -0.5 : 0.0);  // sign(z) * 0.5
}

// R's exact p-value from the two tails of a distribution symmetric about `centre`.
template <class Tail>
double exact_p(double stat, double centre, Alternative alternative, Tail tail_of) {
  switch (alternative) {
    case Alternative::greater: return tail_of(stat - 1.0, false);
    case Alternative::less: return tail_of(stat, true);
    case Alternative::two_sided: break;
  }
  const double p = stat > centre ? tail_of(stat - 1.0, false) : tail_of(stat, true);
  return std::min(2.0 * p, 1.0);
}

void append_note(std::string& note, const std::string& text) {
  if (!note.empty()) note += "; ";
  note += text;
}

// The fields every one-sample result carries, whatever the outcome: the call and the sample.
TestResult one_sample_result(const std::string& test, const TestOptions& options, double mu,
                             const std::vector<double>& x) {
  TestResult r;
  r.test = test;
  r.alternative = options.alternative;
  r.conf_level = options.conf_level;
  r.mu = mu;
  r.n1 = x.size();
  const SampleDescription desc = describe_sample(x);
  r.mean1 = desc.mean;
  r.sd1 = desc.sd;
  r.median1 = desc.median;
  r.iqr1 = desc.iqr;
  r.statistic_name = "V";
  return r;
}

// The fields every two-sample result carries, whatever the outcome: the call and both samples.
TestResult two_sample_result(const std::string& test, const TestOptions& options,
                             const std::vector<double>& x, const std::vector<double>& y) {
  TestResult r;
  r.test = test;
  r.alternative = options.alternative;
  r.conf_level = options.conf_level;
  r.mu = 0.0;
  r.n1 = x.size();
  r.n2 = y.size();
  const SampleDescription dx = describe_sample(x);
  const SampleDescription dy = describe_sample(y);
  r.mean1 = dx.mean;
  r.sd1 = dx.sd;
  r.median1 = dx.median;
  r.iqr1 = dx.iqr;
  r.mean2 = dy.mean;
  r.sd2 = dy.sd;
  r.median2 = dy.median;
  r.iqr2 = dy.iqr;
  r.statistic_name = "W";
  return r;
}

// The exact test: p from the statistic's tabulated null distribution, symmetric about `centre`.
void exact_test(TestResult& r, const char* method, const std::vector<double>& dist, double stat,
                double centre, Alternative alternative) {
  r.method = method;
  r.exact = true;
  r.p_value = exact_p(stat, centre, alternative,
                      [&](double q, bool lower) { return detail::tail(dist, q, lower); });
}

// Names the normal-approximation method and returns R's continuity correction for the centred
// statistic z (0 when not asked for).
double normal_method(TestResult& r, const char* method, double z, bool correct,
                     Alternative alternative) {
  r.method = method;
  r.exact = false;
  if (!correct) return 0.0;
  r.method += " with continuity correction";
  return continuity_correction(z, alternative);
}

// x - mu without the zero differences, which the signed-rank test drops (R does too).
std::vector<double> nonzero_differences(const std::vector<double>& x, double mu) {
  std::vector<double> d;
  d.reserve(x.size());
  for (double v : x)
    if (v - mu != 0.0) d.push_back(v - mu);
  return d;
}

// Every difference is zero: V = 0 with no variance. R's normal approximation divides by
// sigma = 0: two-sided (and without the correction) 0/0 = NaN; one-sided with the continuity
// correction +-0.5/0 = +-Inf, which R turns into p = 1. Match R where it gives a number, and say
// what it means.
void no_nonzero_difference(TestResult& r, std::size_t zeros, double mu, bool correct,
                           Alternative alternative) {
  r.method = "Wilcoxon signed rank test";
  r.exact = false;
  r.statistic = 0.0;
  if (correct && alternative != Alternative::two_sided) {
    r.method += " with continuity correction";
    r.p_value = 1.0;
    r.note = fmt::format(
        "all {} differences from mu = {} are zero: V = 0 has no variance; R's wilcox.test also "
        "returns p = 1 here (its continuity correction over zero variance gives z = {}Inf), "
        "which is no evidence either way",
        zeros, mu, alternative == Alternative::less ? "+" : "-");
    return;
  }
  r.computed = false;
  r.note = fmt::format(
      "all {} differences from mu = {} are zero: nothing to rank; R's wilcox.test returns V = 0 "
      "with p-value NaN (p = 1 only for a one-sided test with the continuity correction)",
      zeros, mu);
}

struct SignedRankSum {
  detail::Ranks ranks;  // of |d|
  double v = 0.0;       // sum of the ranks of the positive differences
};

SignedRankSum signed_rank_sum(const std::vector<double>& d) {
  const std::size_t n = d.size();
  std::vector<double> absd(n);
  for (std::size_t i = 0; i < n; ++i) absd[i] = std::fabs(d[i]);
  SignedRankSum s{average_ranks(absd), 0.0};
  for (std::size_t i = 0; i < n; ++i)
    if (d[i] > 0.0) s.v += s.ranks.rank[i];
  return s;
}

struct RankSum {
  detail::Ranks ranks;  // of x then y, pooled
  double w = 0.0;       // Mann-Whitney W: x's rank sum less its minimum nx (nx + 1) / 2
};

RankSum rank_sum(const std::vector<double>& x, const std::vector<double>& y) {
  std::vector<double> pooled(x);
  pooled.insert(pooled.end(), y.begin(), y.end());
  RankSum s{average_ranks(pooled), 0.0};
  const double nx = static_cast<double>(x.size());
  double x_ranks = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) x_ranks += s.ranks.rank[i];
  s.w = x_ranks - nx * (nx + 1.0) / 2.0;
  return s;
}

// Every value of x and y is tied, so W has no variance. As in the signed-rank test: R gives NaN,
// except p = 1 one-sided with the correction.
void all_values_tied(TestResult& r, double w, std::size_t m, std::size_t n, bool correct,
                     Alternative alternative) {
  const double nx = static_cast<double>(m);
  const double ny = static_cast<double>(n);
  r.statistic = w;
  if (correct && alternative != Alternative::two_sided) {
    r.p_value = 1.0;
    r.note = fmt::format(
        "all {} values of x and y are tied: W = {} has no variance; R's wilcox.test also "
        "returns p = 1 here (its continuity correction over zero variance gives z = {}Inf), "
        "which is no evidence either way",
        m + n, w, alternative == Alternative::less ? "+" : "-");
    r.rank_biserial = 2.0 * w / (nx * ny) - 1.0;
    return;
  }
  r.computed = false;
  r.note = fmt::format(
      "all {} values of x and y are tied: the rank-sum statistic has no variance; R's "
      "wilcox.test returns W = {} with p-value NaN (p = 1 only for a one-sided test with the "
      "continuity correction)",
      m + n, w);
}

}  // namespace

TestResult wilcoxon_signed_rank(std::span<const double> x_in, double mu, const TestOptions& options,
                                bool correct, std::optional<bool> exact) {
  const std::string test = "wilcoxon_signed_rank";
  if (!std::isfinite(mu))
    return TestResult::not_computable(test, "Wilcoxon signed rank test",
                                      fmt::format("mu = {} is not a finite number (R: \"'mu' must be "
                                                  "a single number\")",
                                                  mu));
  const std::vector<double> x = drop_nan(x_in);
  if (x.empty())
    return TestResult::not_computable(
        test, "Wilcoxon signed rank test",
        "no non-missing observations (R: \"not enough (non-missing) 'x' observations\")");

  const std::vector<double> d = nonzero_differences(x, mu);
  const std::size_t zeros = x.size() - d.size();
  const std::size_t n = d.size();
  TestResult r = one_sample_result(test, options, mu, x);
  if (n == 0) {
    no_nonzero_difference(r, zeros, mu, correct, options.alternative);
    return r;
  }

  const SignedRankSum s = signed_rank_sum(d);
  const double v = s.v;
  const double nd = static_cast<double>(n);
  const double total = nd * (nd + 1.0) / 2.0;
  r.statistic = v;
  r.rank_biserial = (v - (total - v)) / total;

  const bool want_exact = exact.value_or(n < 50);
  const bool too_large = n > detail::max_exact_signrank_n;
  if (want_exact && !s.ranks.ties && zeros == 0 && !too_large) {
    exact_test(r, "Wilcoxon signed rank exact test", detail::signrank_distribution(n), v,
               nd * (nd + 1.0) / 4.0, options.alternative);
  } else {
    const double z = v - nd * (nd + 1.0) / 4.0;
    const double sigma =
        std::sqrt(nd * (nd + 1.0) * (2.0 * nd + 1.0) / 24.0 - s.ranks.tie_sum / 48.0);
    const double correction =
        normal_method(r, "Wilcoxon signed rank test", z, correct, options.alternative);
    r.p_value = normal_p((z - correction) / sigma, options.alternative);
    if (want_exact && s.ranks.ties) append_note(r.note, "cannot compute exact p-value with ties");
    if (want_exact && zeros > 0) append_note(r.note, "cannot compute exact p-value with zeroes");
    if (want_exact && too_large && !s.ranks.ties && zeros == 0)
      append_note(r.note, fmt::format("exact distribution not computed for n = {} > {}; normal "
                                      "approximation used",
                                      n, detail::max_exact_signrank_n));
  }
  if (zeros > 0)
    append_note(r.note, fmt::format("{} of {} differences from mu = {} are zero and were dropped",
                                    zeros, x.size(), mu));
  return r;
}

TestResult mann_whitney(std::span<const double> x_in, std::span<const double> y_in,
                        const TestOptions& options, bool correct, std::optional<bool> exact) {
  const std::string test = "mann_whitney";
  const std::vector<double> x = drop_nan(x_in);
  const std::vector<double> y = drop_nan(y_in);
  if (x.empty())
    return TestResult::not_computable(
        test, "Wilcoxon rank sum test",
        "no non-missing observations in x (R: \"not enough (non-missing) 'x' observations\")");
  if (y.empty())
    return TestResult::not_computable(test, "Wilcoxon rank sum test",
                                      "no non-missing observations in y (R: \"not enough 'y' "
                                      "observations\")");

  TestResult r = two_sample_result(test, options, x, y);
  const RankSum s = rank_sum(x, y);
  const double w = s.w;
  const double nx = static_cast<double>(x.size());
  const double ny = static_cast<double>(y.size());

  const bool want_exact = exact.value_or(x.size() < 50 && y.size() < 50);
  const double work = nx * ny * nx * ny / 4.0;
  const bool too_large = (x.size() >= 50 || y.size() >= 50) && work > detail::max_exact_ranksum_work;
  if (want_exact && !s.ranks.ties && !too_large) {
    exact_test(r, "Wilcoxon rank sum exact test", detail::ranksum_distribution(x.size(), y.size()),
               w, nx * ny / 2.0, options.alternative);
  } else {
    const double z = w - nx * ny / 2.0;
    const double sigma = std::sqrt(
        (nx * ny / 12.0) * ((nx + ny + 1.0) - s.ranks.tie_sum / ((nx + ny) * (nx + ny - 1.0))));
    const double correction =
        normal_method(r, "Wilcoxon rank sum test", z, correct, options.alternative);
    if (!(sigma > 0.0)) {
      all_values_tied(r, w, x.size(), y.size(), correct, options.alternative);
      return r;
    }
    r.p_value = normal_p((z - correction) / sigma, options.alternative);
    if (want_exact && s.ranks.ties) append_note(r.note, "cannot compute exact p-value with ties");
    if (want_exact && too_large && !s.ranks.ties)
      append_note(r.note, fmt::format("exact distribution not computed for n1 = {}, n2 = {}; normal "
                                      "approximation used",
                                      x.size(), y.size()));
  }
  r.statistic = w;
  r.rank_biserial = 2.0 * w / (nx * ny) - 1.0;
  return r;
}

}  // namespace feint::stats
