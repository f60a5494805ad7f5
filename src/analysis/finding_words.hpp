// finding_words.hpp - small pieces of a finding's wording shared by the findings' sources
// (private to the analysis module).
#pragma once

#include <string>

#include <fmt/format.h>

#include "feint/stats/htest.hpp"

namespace feint::analysis::detail {

// ", one-sided (adaptive > random)" for a one-sided test of A against B; "" for a two-sided one.
inline std::string one_sided_words(stats::Alternative alternative, const std::string& a, const std::string& b) {
  if (alternative == stats::Alternative::two_sided) return {};
  return fmt::format(", one-sided ({} {} {})", a, alternative == stats::Alternative::greater ? ">" : "<", b);
}

inline bool is_t_test(const std::string& test) {
  return test == "one_sample_t" || test == "welch_t" || test == "student_t" || test == "paired_t";
}

}  // namespace feint::analysis::detail
