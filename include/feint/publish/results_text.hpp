// feint/publish/results_text.hpp - the Results section of a paper, ready to paste: one APA-7
// paragraph per hypothesis, made from the findings (docs/report.md, "Results text").
//
// Each paragraph opens with the hypothesis and whether it is confirmatory or exploratory, gives
// per measure the headline finding's numbers (the means of both sides when known, the difference
// with its interval, the effect size with its interval, the test with its statistic and df, exact
// p, adjusted p, the Bayes factor) and the strength of evidence, and closes with the answer in
// words ("H1 was supported for error but inconclusive for confusion."). At most 250 words.
#pragma once

#include <cstddef>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "feint/analysis/findings.hpp"
#include "feint/analysis/hypotheses.hpp"
#include "feint/analysis/results.hpp"

namespace feint::publish {

enum class ResultsFormat { markdown, latex, html };

/// A paragraph's limit, in words as word_count() counts them.
inline constexpr std::size_t kResultsWordCap = 250;

/// Whitespace-separated tokens: how the 250-word cap is counted.
std::size_t word_count(std::string_view text);

/// The answer for one measure of a hypothesis, from its headline finding.
enum class Answer {
  supported,       ///< evidence for a difference in the declared direction (any, when two-sided)
  contradicted,    ///< evidence for a difference in the other direction
  undirected,      ///< evidence for a difference whose direction the finding does not give
  no_difference,   ///< evidence for no difference
  inconclusive,    ///< no evidence either way
  not_testable,    ///< not computable, or no finding
};

/// The answer that `headline` gives to `hypothesis`. `a` names condition A (the hypotheses'
/// direction is A relative to B): a contrast written "B - A" is read the other way round; empty:
/// each contrast's first side is taken as A.
Answer answer(const analysis::Hypothesis& hypothesis, const analysis::Finding& headline,
              std::string_view a = {});

/// One paragraph per hypothesis, in the hypotheses' order. A finding belongs to the hypothesis
/// its `hypothesis` names and to the measure its `measure` names (findings without a measure are
/// left out). Per measure the headline is the first confirmatory finding, else the first
/// computable comparison of the conditions (not a one-sample test against a reference), else the
/// first computable finding, else the first; the other findings of the hypothesis are counted by
/// strength in one sentence that points to the tables. When the headlines exceed the cap, the last
/// measures' numbers are left to the tables (the answer still names every measure).
std::vector<std::string> results_paragraphs(std::span<const analysis::Hypothesis> hypotheses,
                                            std::span<const analysis::Finding> findings,
                                            ResultsFormat format, std::string_view a = {});

/// The paragraphs as one text: separated by blank lines (Markdown, LaTeX; the LaTeX opens with a
/// comment line and needs no package), or as <p class="results-text"> elements (HTML).
std::string results_text(const std::vector<analysis::Hypothesis>& hypotheses,
                         std::span<const analysis::Finding> findings, ResultsFormat format,
                         std::string_view a = {});

/// The study's paragraphs: its hypotheses and findings, A being the first compared condition; a
/// sentence saying so when the study tests no hypothesis (no two conditions compared). Written by
/// `feint analyze` as OUT/results-text.md and OUT/results-text.tex, and the report opens with it.
std::string study_results_text(const analysis::StudyResults& results, ResultsFormat format);

}  // namespace feint::publish
