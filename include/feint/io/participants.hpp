// feint/io/participants.hpp - the participants of two inputs of one study compared (the pad-trace
// logs and the questionnaire), so that a pipeline can say who is missing where.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace feint::io {

struct ParticipantComparison {
  std::vector<std::string> only_in_logs;           ///< sorted, distinct
  std::vector<std::string> only_in_questionnaire;  ///< sorted, distinct
  std::size_t in_both = 0;
  /// Both inputs name the same participants.
  bool matches() const noexcept { return only_in_logs.empty() && only_in_questionnaire.empty(); }
  /// "" when they match; otherwise one sentence listing the ids missing on either side (at most
  /// 10 of each, then "and N more"), noting ids that differ only in case.
  std::string message() const;
};

/// Compares participant ids exactly (trimmed text, case-sensitive, as every loader keys them);
/// duplicates are ignored.
ParticipantComparison compare_participants(const std::vector<std::string>& log_ids,
                                           const std::vector<std::string>& questionnaire_ids);

}  // namespace feint::io
