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

}  // namespace feint::analysis
