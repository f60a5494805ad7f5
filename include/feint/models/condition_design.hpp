// feint/models/condition_design.hpp - how a study's conditions relate to its participants, declared
// or read off the data, and checked against the data (docs/analysis.md "Designs").
//
//   between: each participant saw one condition (the seed paper's design: independent groups,
//            two-sample tests, condition between participants in the ANOVA and the models);
//   within:  each participant saw every condition (in counterbalanced blocks: paired tests,
//            condition within participants, relabelling that swaps conditions within a person).
//
// A design is declared in feint.toml (`design = "within"`) or with `--design`; without one it is
// read off the data when the data leave no doubt (nobody in two conditions: between; everybody in
// every condition: within) and otherwise refused: a study where some people saw two conditions
// and others one is either a within study with dropouts or a between study with a reused id, and
// only the lab knows which.
#pragma once

#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "feint/models/design.hpp"

namespace feint::models {

enum class ConditionDesign { between, within };

/// "between" or "within" (any case; surrounding blanks ignored); "" = not declared (nullopt).
/// Throws UsageError naming --design otherwise.
std::optional<ConditionDesign> parse_condition_design(std::string_view text);
std::string_view to_string(ConditionDesign design) noexcept;

/// The design of a study's trials: declared or read off the data, with what the data made of it.
struct DesignCheck {
  ConditionDesign design = ConditionDesign::between;
  bool declared = false;  ///< false: read off the data
  /// How the design was decided, for the report's Design section ("conditions within participants
  /// (read off the data: each of the 24 participants saw both conditions)").
  std::string note;
  /// Within: the participants who did not see every condition, each with the conditions they saw
  /// ("P07 (adaptive only)"); paired tests leave them out, the mixed model keeps their trials.
  std::vector<std::string> incomplete;
  /// Conditions with one participant only (a between design cannot estimate their variance).
  std::vector<std::string> single_participant_conditions;
  /// Warnings for the accounting, one sentence each (empty when the data fit the design).
  std::vector<std::string> warnings;
};

/// Decides and checks the design of `observations` (rows of a scores table; `source` names it in
/// messages, with each row's line). Rows with an empty condition are ignored (a study without
/// conditions has no condition design; the result is then `between`, not declared, no note).
/// Throws InvalidData, naming the participant, both lines and what to set, when
///  - the design is declared `between` and a participant has trials in two conditions;
///  - it is declared `within` and no participant saw two conditions;
///  - it is not declared and some participants saw several conditions while others saw one.
DesignCheck check_condition_design(std::span<const Observation> observations,
                                   std::optional<ConditionDesign> declared, const std::string& source);

}  // namespace feint::models
