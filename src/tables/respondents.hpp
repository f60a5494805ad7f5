// Respondents of a questionnaire by condition, shared by the Likert and the yes/no analyses.
#pragma once

#include <cstddef>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "feint/io/questionnaire.hpp"

namespace feint::tables::detail {

/// The respondents of a condition (everybody without a condition column).
inline std::vector<std::size_t> respondents_in(const io::Questionnaire& q, const std::string& condition) {
  std::vector<std::size_t> out;
  for (std::size_t r = 0; r < q.respondents(); ++r)
    if (!q.has_condition || q.conditions[r] == condition) out.push_back(r);
  return out;
}

/// The first participant of `b` who also answered in `a` (two-sample tests need independent
/// groups), or nullopt.
inline std::optional<std::string> shared_participant(const io::Questionnaire& q, const std::vector<std::size_t>& a,
                                                     const std::vector<std::size_t>& b) {
  std::set<std::string> in_a;
  for (const auto r : a) in_a.insert(q.participants[r]);
  for (const auto r : b)
    if (in_a.count(q.participants[r]) != 0) return q.participants[r];
  return std::nullopt;
}

}  // namespace feint::tables::detail
