// feint/analysis/findings.hpp - what the study shows, in sentences (issue 15). This is the slot
// that StudyResults carries; the findings engine (helper branch issue15-stats) fills and extends it.
#pragma once

#include <string>
#include <vector>

namespace feint::analysis {

/// One answered question of the study: a sentence with its numbers, the strength of evidence,
/// and where in the report it comes from.
struct Finding {
  std::string id;        ///< stable key, e.g. "H1-persistence"
  std::string question;  ///< the hypothesis in words
  std::string sentence;  ///< the answer, APA numbers included
  std::string evidence;  ///< "evidence for", "no evidence either way", "evidence for no difference"
  std::string source;    ///< anchor of the table or figure it comes from, e.g. "table1"
};

}  // namespace feint::analysis
