// The yes/no analysis's pieces shared by yes_no.cpp (two conditions) and yes_no_conditions.cpp
// (three or more): see feint/tables/yes_no.hpp (private to the tables module).
#pragma once

#include <cstddef>
#include <map>
#include <string>

#include "feint/io/questionnaire.hpp"
#include "feint/stats/htest.hpp"
#include "feint/stats/paired_proportions.hpp"
#include "feint/tables/yes_no.hpp"

namespace feint::tables::detail {

/// A comparison of two conditions as a tidy row, labelled A>B / A<B when p < alpha (no "≈": no
/// test here gives evidence of no difference).
TidyRow yes_no_comparison_row(const std::string& question, const std::string& a, const std::string& b,
                              stats::TestResult result, double alpha);

/// A comparison row's cells in the tables: the test's name, the estimate (odds ratio or
/// difference), its interval and the statistic ("–" where there is none).
struct ComparisonCells {
  std::string test, estimate = "–", ci = "–", statistic = "–";
};
ComparisonCells comparison_cells(const TidyRow& row);

/// Each participant's row in condition c; InvalidData when they answered twice in it.
std::map<std::string, std::size_t> rows_by_participant(const io::Questionnaire& q, const std::string& c);

/// The table of pairs of question `item`: the participants in both maps with both answers.
stats::PairedYesNoTable paired_table(const io::Questionnaire& q, std::size_t item,
                                     const std::map<std::string, std::size_t>& in_a,
                                     const std::map<std::string, std::size_t>& in_b);

/// The summary of `question` in `group` (analyze_yes_no made one for each).
const YesNoSummary& summary_of(const YesNoAnalysis& a, const std::string& question, const std::string& group);

/// Three or more conditions (no pair named): the omnibus tests, the pairs and their notes.
void compare_across_conditions(YesNoAnalysis& a, const io::Questionnaire& q);

/// The text / markdown / latex tables of the comparison across the conditions.
std::string render_across_conditions(const YesNoAnalysis& a, OutputFormat format);

}  // namespace feint::tables::detail
