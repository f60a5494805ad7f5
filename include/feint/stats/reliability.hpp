// feint/stats/reliability.hpp - internal consistency of multi-item scales.
#pragma once

#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace feint::stats {

/// How Cronbach's alpha treats missing answers (NaN).
enum class AlphaMissing {
  /// psych::alpha's default (`use = "pairwise"`): each covariance C[a,b] from the respondents who
  /// answered both a and b (R's cov(x, use = "pairwise.complete.obs")).
  pairwise,
  /// Only respondents who answered every item (psych::alpha(na.omit(x))).
  complete_cases,
};

/// "pairwise" / "complete" (also "complete-cases"); throws UsageError otherwise.
AlphaMissing parse_alpha_missing(std::string_view text);
std::string_view to_string(AlphaMissing method) noexcept;

struct CronbachAlpha {
  std::optional<double> raw_alpha;               ///< psych::alpha()$total$raw_alpha
  std::vector<std::optional<double>> if_dropped;  ///< raw alpha with item j dropped (psych's alpha.drop)
  std::size_t n = 0;  ///< respondents used: complete cases, or (pairwise) who answered any item
  AlphaMissing missing = AlphaMissing::pairwise;  ///< which treatment of missing answers ran
  std::size_t items_used = 0;                     ///< items with non-zero variance (psych deletes the rest)
  std::string note;                               ///< why not computable (k < 2, zero variance, n < 2)
};

/// Cronbach's alpha from item columns of equal length (respondents in the same order; NaN marks a
/// missing answer, treated as `missing` says: by default psych::alpha's pairwise covariances):
///
///   alpha = k/(k-1) * (1 - sum_j var(item_j) / var(total)) = k/(k-1) * (1 - tr(C) / sum(C))
///
/// with C the k x k sample covariance matrix of the items (Cronbach 1951). Reproduces
/// `psych::alpha(items)` (pairwise, psych 2.2.9's default) and `psych::alpha(na.omit(items))`
/// (complete_cases): raw_alpha = $total$raw_alpha and if_dropped[j] =
/// $alpha.drop$raw_alpha[j], the alpha of the other k-1 items. As psych does: items without variance
/// are left out (their if_dropped is empty; `note` names them); negatively keyed items are NOT
/// reversed (reverse-code them first); with exactly 2 items psych's alpha.drop is
/// C[1,2]/C[2,2] for dropping item 1 and C[1,2]/C[1,1] for dropping item 2. With pairwise
/// covariances, alpha if dropped uses the same C without the item (as psych does).
///
/// Not computable (raw_alpha empty, `note` says why): fewer than 2 items (with variance), items of
/// different lengths, fewer than 2 complete respondents (pairwise: two items answered together by
/// fewer than 2 respondents), or a total score without variance.
CronbachAlpha cronbach_alpha(std::span<const std::vector<double>> items,
                             AlphaMissing missing = AlphaMissing::pairwise);

}  // namespace feint::stats
