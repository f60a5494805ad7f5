// feint/stats/permutation.hpp - the Westfall–Young step-down maxT permutation adjustment.
//
// A family of two-sample t tests on the same participants (the per-iteration contrasts of a
// metric between two conditions: one test per iteration) is adjusted by permuting whole
// participants between the conditions, keeping each participant's values over all iterations
// together: the step-down maxT of Westfall & Young (1993), as Ge, Dudoit & Speed (2003) give it. With the
// observed statistics ordered s_(1) >= ... >= s_(m) and, for every relabelling b, the successive
// maxima u_k^b = max(s_(k)^b, ..., s_(m)^b):
//
//     p~_(k) = #{b : u_k^b >= s_(k)} / B_total,   p_(k) = max(p~_(1), ..., p~_(k)),
//
// where s = |t| (two-sided), t (greater) or -t (less), and B_total counts the observed labelling.
// This controls the family-wise error rate exactly (up to the Monte Carlo error of sampled
// relabellings) whenever the participants are exchangeable between the conditions under the null,
// whatever the tests' dependence and whatever the metric's distribution: unlike Holm on t-test
// p-values, it never asks the t distribution for its far tail.
//
// Exact enumeration of every labelling with the observed group sizes when there are at most
// `permutations + 1` of them; otherwise `permutations` relabellings drawn uniformly (Fisher–Yates
// on feint::Rng, seeded: the same data and seed give the same p-values on every machine), with
// p = (1 + #{b : ...}) / (permutations + 1), never 0 and valid as it stands (Phipson & Smyth 2010).
//
// Golden values: tests/golden/stats/maxt_golden.R (complete enumeration in R).
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <vector>

#include "feint/stats/htest.hpp"

namespace feint::stats {

struct MaxTOptions {
  Alternative alternative = Alternative::two_sided;
  bool var_equal = false;  ///< Student's pooled t instead of Welch's
  std::uint64_t permutations = 9999;  ///< relabellings drawn when not enumerated exactly
  std::uint64_t seed = 20261126;
};

struct MaxTResult {
  /// Per column (test): the observed t (Welch or Student, group 1 minus group 2); empty when the
  /// test cannot be computed (fewer than 2 values in a group for Welch, constant data), as R.
  std::vector<std::optional<double>> statistic;
  std::vector<std::optional<double>> p_raw;       ///< the column's own permutation p-value
  std::vector<std::optional<double>> p_adjusted;  ///< step-down maxT adjusted
  std::uint64_t labellings = 0;  ///< relabellings counted, the observed one included
  bool exact = false;            ///< every labelling enumerated
};

/// How a relabelling test visited the labellings.
struct Labellings {
  std::uint64_t total = 0;  ///< labellings visited, the observed one included
  bool exact = false;       ///< every labelling enumerated
};

/// Visits the labellings of `participants` participants with |members| of them in group 1, as the
/// relabelling tests count them: every labelling (lexicographic, the observed one among them) when
/// there are at most `permutations + 1`; otherwise the observed labelling (`members`) first, then
/// `permutations` uniform draws (Fisher–Yates on feint::Rng from `seed`, the same on every
/// machine). `visit` gets the group-1 participants' indices. A test's p-value is then
/// #{labellings at least as extreme as the observed} / total, never 0 (Phipson & Smyth 2010).
/// Throws UsageError when a group would be empty or permutations == 0.
Labellings for_each_labelling(std::size_t participants, std::span<const std::size_t> members,
                              std::uint64_t permutations, std::uint64_t seed,
                              const std::function<void(std::span<const std::size_t>)>& visit);

/// True when for_each_labelling enumerates every labelling of `participants` with `members` of them
/// in group 1 (there are at most `permutations + 1`), false when it samples them.
bool every_labelling(std::size_t participants, std::size_t members, std::uint64_t permutations);

/// As for_each_labelling, but `visit` answers whether to go on: false stops the sampled labellings
/// (a sequential p-value). Enumeration ignores the answer: its order is not random, so stopping it
/// early would bias the p-value.
Labellings for_each_labelling_while(std::size_t participants, std::span<const std::size_t> members,
                                    std::uint64_t permutations, std::uint64_t seed,
                                    const std::function<bool(std::span<const std::size_t>)>& visit);

/// Besag & Clifford's (1991) sequential Monte Carlo p-value of one test over sampled labellings:
/// sample until h of them reach the observed statistic, or until n - 1 have been sampled. With g
/// of the l sampled labellings reaching it,
///
///     p = h / l            when the h-th reaching labelling is the l-th sampled (stopped early)
///     p = (g + 1) / n      when n - 1 were sampled with g < h reaching it (as the fixed-n p)
///
/// Under the null (the observed labelling exchangeable with the sampled ones) P(p <= u) = u at
/// every value u the sampler can give, and <= u elsewhere: the p-value is exact, not only
/// approximate (Besag & Clifford 1991, Biometrika 78, 301-304; ties counted as reaching make it
/// conservative). A p-value far above alpha stops after about h / p labellings; one below h / n is
/// the fixed-n p-value itself, from the same labellings. h = 0: never stop early (the fixed-n p).
class SequentialPValue {
 public:
  /// `h` reaching labellings to stop at (0 = never), `n` = the most labellings counted, the
  /// observed one included (n - 1 sampled). Throws UsageError when n < 2.
  SequentialPValue(std::uint64_t h, std::uint64_t n);
  /// Counts the next sampled labelling; ignored once done().
  void add(bool reaches);
  bool stopped_early() const { return h_ > 0 && reached_ == h_; }
  bool done() const { return stopped_early() || sampled_ + 1 >= n_; }
  /// h / l when stopped early, else (g + 1) / (l + 1): (g + 1) / n once all n - 1 are sampled.
  double p() const;
  /// Labellings counted, the observed one included.
  std::uint64_t labellings() const { return sampled_ + 1; }

 private:
  std::uint64_t h_, n_, sampled_ = 0, reached_ = 0;
};

/// The maxT adjustment of `columns` two-sample t tests. `values` is participant-major
/// (values[i * columns + j]: participant i, test j; NaN = missing, left out of that test only);
/// `group[i]` is 1 (group 1, x) or 0 (group 2, y). Throws UsageError for mismatched sizes, labels
/// other than 0/1, an empty group or permutations == 0.
MaxTResult maxt_step_down(std::span<const double> values, std::size_t columns, std::span<const int> group,
                          const MaxTOptions& options = {});

/// The maxT adjustment of `columns` paired t tests (the per-iteration contrasts of a metric between
/// two conditions that every participant saw). `differences` is participant-major
/// (differences[i * columns + j]: participant i's condition-A minus condition-B value at test j;
/// NaN = no pair there, left out of that test only). Under the null each participant's two
/// conditions are exchangeable, so a relabelling swaps the conditions within participants: it flips
/// the signs of all of a participant's differences together (keeping the dependence between the
/// iterations), and the step-down maxT above runs over the 2^P sign vectors: every one when
/// 2^P <= permutations + 1 (the observed one among them), otherwise the observed one and
/// `permutations` uniform draws (feint::Rng from `seed`). The statistic is R's paired
/// t.test's: mean / (sd / sqrt(n)) of the column's differences, not computable for n < 2 or
/// constant differences. Throws UsageError for mismatched sizes, no participant or
/// permutations == 0. (`var_equal` is ignored.)
MaxTResult maxt_step_down_paired(std::span<const double> differences, std::size_t columns,
                                 const MaxTOptions& options = {});

}  // namespace feint::stats
