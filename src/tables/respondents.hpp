// Respondents of a questionnaire by condition, shared by the Likert and the yes/no analyses.
#pragma once

#include <cstddef>
#include <optional>
#include <set>
#include <string>
#include <utility>
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

/// A respondent's value of name k: the answer to an item, or a composite's mean of its items
/// (missing when any of them is).
struct Answers {
  const io::Questionnaire& q;
  const std::vector<std::vector<std::size_t>>& members;  ///< items of each composite

  std::optional<double> value(std::size_t k, std::size_t r) const {
    const std::size_t n_items = q.items.size();
    if (k < n_items) {
      const auto& x = q.responses[k][r];
      return x ? std::optional<double>(*x) : std::nullopt;
    }
    double sum = 0.0;
    for (const auto i : members[k - n_items]) {
      const auto& x = q.responses[i][r];
      if (!x) return std::nullopt;
      sum += *x;
    }
    return sum / static_cast<double>(members[k - n_items].size());
  }

  /// The values of name k over the respondents, and how many of them are missing.
  std::pair<std::vector<double>, std::size_t> values_of(
      std::size_t k, const std::vector<std::size_t>& resp) const {
    std::pair<std::vector<double>, std::size_t> out{{}, 0};
    for (const auto r : resp) {
      if (const auto v = value(k, r)) {
        out.first.push_back(*v);
      } else {
        ++out.second;
      }
    }
    return out;
  }
};

}  // namespace feint::tables::detail
