// feint/stats/p_adjust.hpp - multiple-comparison adjustment, as R's p.adjust().
#pragma once

#include <optional>
#include <span>
#include <string_view>
#include <vector>

namespace feint::stats {

enum class PAdjustMethod { none, bonferroni, holm, hochberg, hommel, BH, BY };

/// R's names: none, bonferroni, holm, hochberg, hommel, BH (also "fdr"), BY. Throws UsageError.
PAdjustMethod parse_p_adjust(std::string_view name);
std::string_view to_string(PAdjustMethod method) noexcept;

/// p.adjust(p, method). Empty entries (tests that could not be computed) stay empty and do not
/// count in the family size, as R's NA handling.
std::vector<std::optional<double>> p_adjust(std::span<const std::optional<double>> p,
                                            PAdjustMethod method);

}  // namespace feint::stats
