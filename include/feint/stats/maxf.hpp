// feint/stats/maxf.hpp - the Westfall–Young step-down maxF over a family of omnibus F tests of three or
// more conditions (one test per iteration), by relabelling whole participants.
//
// The maxT of feint/stats/permutation.hpp generalised from two conditions to k: the statistics are
// F (large = extreme, so one-sided), and a relabelling either
//  - between participants: moves participants between the conditions, keeping the conditions'
//    sizes and each participant's values over all iterations together (every distinct assignment
//    of the k labels to the P participants is equally likely under the null); the statistic is
//    Welch's F (R's oneway.test(y ~ g)), a studentised statistic, as the two-condition maxT uses
//    Welch's t;
//  - within participants: permutes each participant's conditions, the same permutation at every
//    iteration (the k! orders of every participant are equally likely under the null); the
//    statistic is the one-way repeated-measures F of the participants with every condition at
//    that iteration (summary(aov(y ~ condition + Error(participant / condition)))).
// With the observed statistics ordered F_(1) >= ... >= F_(m) and u_r^b = max(F_(r)^b, ..., F_(m)^b)
// for every labelling b,
//
//     p~_(r) = #{b : u_r^b >= F_(r)} / B_total,   p_(r) = max(p~_(1), ..., p~_(r)),
//
// B_total counting the observed labelling. Every labelling is enumerated when there are at most
// `permutations + 1` of them (P! / prod n_g! between, (k!)^P within); otherwise the observed one
// and `permutations` drawn uniformly (Fisher–Yates on feint::Rng from `seed`: the same p-values on
// every machine). A test that cannot be computed on the observed data is left out of the family
// (its p empty); on a relabelling it never reaches.
//
// Golden values: tests/golden/table1/table1_conditions_golden.R (complete enumeration in R).
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

#include "feint/stats/permutation.hpp"

namespace feint::stats {

struct MaxFOptions {
  std::uint64_t permutations = 9999;  ///< relabellings drawn when not enumerated exactly
  std::uint64_t seed = 20261126;
};

/// Between participants. `values` is participant-major (values[i * columns + j]: participant i,
/// test j; NaN = missing, left out of that test only); `group[i]` in 0 .. k - 1 is participant i's
/// condition. Per test, Welch's F of the conditions that have values there; not computable (empty)
/// when fewer than two conditions have values, a condition has one value, or a condition's values
/// are constant. The result's `statistic` is F. Throws UsageError for mismatched sizes, a negative
/// label, fewer than two conditions or permutations == 0.
MaxTResult maxf_step_down_between(std::span<const double> values, std::size_t columns,
                                  std::span<const int> group, const MaxFOptions& options = {});

/// Within participants. `values[(i * conditions + c) * columns + j]`: participant i, condition c,
/// test j (NaN = missing). Per test, the repeated-measures F of the participants with a value in
/// every condition there: with each participant's values centred on their own mean (d_ic), and
/// SS_c = n sum_c mean_i(d_ic)^2, SS_e = sum d_ic^2 - SS_c,
///     F = (SS_c / (k - 1)) / (SS_e / ((k - 1)(n - 1))),
/// not computable for n < 2 or SS_e = 0 (up to rounding). Throws UsageError for mismatched sizes,
/// fewer than two conditions, no participant or permutations == 0.
MaxTResult maxf_step_down_within(std::span<const double> values, std::size_t conditions, std::size_t columns,
                                 const MaxFOptions& options = {});

}  // namespace feint::stats
