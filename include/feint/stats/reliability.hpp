// feint/stats/reliability.hpp - internal consistency of multi-item scales.
#pragma once

#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace feint::stats {

struct CronbachAlpha {
  std::optional<double> raw_alpha;               ///< psych::alpha()$total$raw_alpha
  std::vector<std::optional<double>> if_dropped;  ///< raw alpha with item j dropped (psych's alpha.drop)
  std::size_t n = 0;                              ///< respondents used (complete cases)
  std::size_t items_used = 0;                     ///< items with non-zero variance (psych deletes the rest)
  std::string note;                               ///< why not computable (k < 2, zero variance, n < 2)
};

/// Cronbach's alpha from item columns of equal length (respondents in the same order; NaN marks a
/// missing answer and the respondent is dropped: complete cases only):
///
///   alpha = k/(k-1) * (1 - sum_j var(item_j) / var(total)) = k/(k-1) * (1 - tr(C) / sum(C))
///
/// with C the k x k sample covariance matrix of the items (Cronbach 1951). Reproduces
/// `psych::alpha(na.omit(items))` (psych 2.2.9): raw_alpha = $total$raw_alpha and if_dropped[j] =
/// $alpha.drop$raw_alpha[j], the alpha of the other k-1 items. As psych does: items without variance
/// are left out (their if_dropped is empty; `note` names them); negatively keyed items are NOT
/// reversed (reverse-code them first); with exactly 2 items psych's alpha.drop is
/// C[1,2]/C[2,2] for dropping item 1 and C[1,2]/C[1,1] for dropping item 2. Note psych's default
/// `use = "pairwise"` differs from complete cases when answers are missing.
///
/// Not computable (raw_alpha empty, `note` says why): fewer than 2 items (with variance), items of
/// different lengths, fewer than 2 complete respondents, or a total score without variance.
CronbachAlpha cronbach_alpha(std::span<const std::vector<double>> items);

}  // namespace feint::stats
