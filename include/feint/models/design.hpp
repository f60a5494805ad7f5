// feint/models/design.hpp - a metric of a scores table as a repeated-measures design: one row per
// participant, one column per iteration (the "wide" layout of afex::aov_ez and car::Anova).
//
// The models module reads no file (it links feint_stats, and feint_sim for the power simulation's
// generator), so it takes the long-format observations as plain values; report/ and cli/ turn an
// io::ScoresTable into them.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace feint::models {

/// One value of one metric: a row of a scores table.
struct Observation {
  std::string participant;
  std::string condition;  ///< "" when the table has no condition column
  long long iteration = 0;
  std::optional<double> value;  ///< nullopt = missing (an empty cell)
  std::uint64_t line = 0;       ///< physical line in the file, for error messages
};

/// Participants x iterations, complete cases only (as afex: a participant with a missing value is
/// excluded from the whole analysis of that metric).
struct WideDesign {
  std::string source;  ///< file name, for messages
  std::string metric;
  std::vector<std::string>
      conditions;                     ///< levels in order of first appearance (the between factor)
  std::vector<long long> iterations;  ///< levels, ascending (the within factor)
  std::vector<std::string> participants;  ///< complete participants, sorted by condition, then
                                          ///< order of first appearance
  std::vector<std::size_t> group;         ///< condition index of each participant
  std::vector<double> y;                  ///< participants x iterations, row-major
  std::vector<std::string> excluded;      ///< participants left out for a missing iteration/value
  /// Conditions whose every participant was excluded, dropped from the analysis (only when asked
  /// for with `drop_empty_conditions`; otherwise make_wide_design refuses them).
  std::vector<std::string> dropped_conditions;

  std::size_t n() const noexcept { return participants.size(); }
  std::size_t k() const noexcept { return iterations.size(); }
  double at(std::size_t participant, std::size_t iteration) const {
    return y[participant * k() + iteration];
  }
  /// Participants per condition (complete cases).
  std::vector<std::size_t> group_sizes() const;
};

/// Builds the wide design of `metric` from its observations. Throws InvalidData (exit 65) for
///  - a participant in two conditions (`scores.csv:12: participant 'P03' is in condition 'random'
///    but line 5 put it in 'adaptive'; the ANOVA needs each participant in one condition`),
///  - an iteration with no value of `metric` for anybody,
///  - fewer than two iterations,
///  - no participant left with every iteration,
///  - a metric with no variance (every value equal),
///  - a condition whose every participant is excluded for a missing value, unless
///    `drop_empty_conditions` (then the condition is dropped and named in `dropped_conditions`;
///    with one condition left the analysis is the one-way repeated-measures ANOVA). afex stops
///    there too; silently analysing the other conditions would answer another question.
WideDesign make_wide_design(std::span<const Observation> observations, const std::string& metric,
                            const std::string& source, bool drop_empty_conditions = false);

}  // namespace feint::models
