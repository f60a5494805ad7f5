// feint/stats/rank_tests.hpp - Wilcoxon signed-rank and Mann–Whitney U, as R's wilcox.test().
#pragma once

#include <optional>
#include <span>

#include "feint/stats/htest.hpp"

namespace feint::stats {

/// wilcox.test(x, mu = mu, correct = correct, exact = exact): zeros (x == mu) dropped; exact when
/// n < 50 and no ties or zeros (unless `exact` forces a choice), otherwise the normal approximation
/// with tie correction and (if `correct`) continuity correction. statistic V; rank-biserial
/// correlation r = (V - (S - V)) / S with S = n(n+1)/2. `exact` in the result says which ran.
TestResult wilcoxon_signed_rank(std::span<const double> x, double mu, const TestOptions& options = {},
                                bool correct = true, std::optional<bool> exact = std::nullopt);

/// wilcox.test(x, y, correct = correct, exact = exact): statistic W (= U of x); exact when both
/// n < 50 and no ties. rank-biserial r = 2 W / (n1 n2) - 1.
TestResult mann_whitney(std::span<const double> x, std::span<const double> y,
                        const TestOptions& options = {}, bool correct = true,
                        std::optional<bool> exact = std::nullopt);

}  // namespace feint::stats
