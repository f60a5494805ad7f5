// feint/analysis/analyze.hpp - the whole study pipeline: Study -> StudyResults.
//
//   load_study (study.hpp)  ->  analyze  ->  StudyResults (results.hpp, plain data)
//                                              -> feint/plot (figures), feint/publish (files)
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "feint/analysis/results.hpp"
#include "feint/analysis/study.hpp"

namespace feint::analysis {

/// Scores the study's logs, builds Table 1 (and the comparison), the mixed ANOVA, the mixed
/// models, the questionnaire analyses, the figure data and the diagnostics. Parts the design does
/// not allow (one iteration, one condition, no strategy column) are left empty with a note in
/// diagnostics.exclusions; bad data throws InvalidData naming file, row and column.
/// Scoring uses a private temporary folder (removed before returning); the study is never written.
StudyResults analyze(const Study& study, const std::string& tool_version = "unknown");

/// The comparison a study gets when no setting names one: its two conditions, when the study has
/// no settings file and its scores hold exactly two (named) conditions; "adaptive" first when it
/// is one of them (the paper's design: the adaptive condition is the one H1 is about), otherwise
/// in alphabetical order, so that the contrast does not depend on the logs' file names. None when
/// a comparison was set, a settings file was read, or there are not exactly two conditions.
std::optional<std::pair<std::string, std::string>> default_comparison(
    const Study& study, const std::vector<std::string>& conditions);

}  // namespace feint::analysis
