// The Results paragraphs (publish::results_text): exact sentences for each answer, the 250-word
// cap, LaTeX that compiles, and `feint analyze` writing them and opening its report with them.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include "cli/cli_helpers.hpp"
#include "feint/publish/results_text.hpp"

namespace fs = std::filesystem;
using feint::analysis::EffectSize;
using feint::analysis::Finding;
using feint::analysis::Grade;
using feint::analysis::Hypothesis;
using feint::analysis::Strength;
using feint::publish::Answer;
using feint::publish::ResultsFormat;
using feint::publish::results_paragraphs;
using feint::publish::results_text;
using feint::publish::word_count;
using feint::test::read_text;
using feint::test::run_feint;
using feint::test::shell_quote;
using feint::test::TempDir;
using feint::test::write_text;

namespace {

Hypothesis h1(bool confirmatory = true) {
  return {"H1", "People stay deceived longer under adaptive than under random selection.",
          {"error", "confusion"}, "greater", confirmatory, {}};
}

// A Welch t test's finding of `measure`, adaptive - random, with every structured field.
Finding welch(const std::string& measure, double estimate, Strength strength, const std::string& evidence) {
  Finding f;
  f.id = "H1-condition-" + measure;
  f.hypothesis = "H1";
  f.measure = measure;
  f.contrast = "adaptive - random";
  f.direction = estimate > 0 ? "adaptive > random" : "adaptive < random";
  f.means = {0.55 + estimate, 0.55};
  f.estimate = estimate;
  f.ci_low = estimate - 0.05;
  f.ci_high = estimate + 0.05;
  f.effect_size = EffectSize{"d", estimate / 0.12, estimate / 0.12 - 0.41, estimate / 0.12 + 0.41};
  f.p = 0.023;
  f.p_adjusted = 0.046;
  f.bf10 = 3.21;
  f.test = "Welch t test";
  f.statistics = "t(57.50) = 2.31, p = .023, adjusted p = .046, d = 0.50, BF\u2081\u2080 = 3.21";
  f.strength = strength;
  f.evidence = evidence;
  return f;
}

Finding supported_error() {
  return welch("error", 0.06, Strength::evidence_for_difference, "moderate evidence for a difference");
}

Finding inconclusive_confusion() {
  Finding f = welch("confusion", 0.01, Strength::no_evidence_either_way, "no evidence either way");
  f.means = {0.35, 0.34};
  f.ci_low = -0.02;
  f.ci_high = 0.04;
  f.effect_size = EffectSize{"d", 0.08, -0.43, 0.59};
  f.p = 0.41;
  f.p_adjusted.reset();
  f.bf10 = 0.45;  // BF01 = 2.22
  f.statistics = "t(55.12) = 0.83, p = .410, d = 0.08 [-0.43, 0.59], BF\u2080\u2081 = 2.22";
  return f;
}

std::string md_paragraph(const Hypothesis& h, const std::vector<Finding>& fs, std::string_view a = {}) {
  const std::vector<Hypothesis> hs{h};
  const auto ps = results_paragraphs(hs, fs, ResultsFormat::markdown, a);
  return ps.empty() ? std::string() : ps.front();
}

// The paragraph's closing sentence (from the hypothesis's id to the end).
std::string closing(const std::string& paragraph, const std::string& id = "H1") {
  const auto k = paragraph.rfind(" " + id + " was ");
  return k == std::string::npos ? paragraph : paragraph.substr(k + 1);
}

}  // namespace

TEST(ResultsText, SupportedForOneMeasureInconclusiveForTheOther) {
  const std::string p = md_paragraph(h1(), {supported_error(), inconclusive_confusion()});
  EXPECT_EQ(p,
            "**H1** (confirmatory): People stay deceived longer under adaptive than under random selection. "
            "Error: adaptive *M* = 0.61, random *M* = 0.55; difference (adaptive \u2212 random) 0.06, 95% CI "
            "[0.01, 0.11]; *d* = 0.50, 95% CI [0.09, 0.91]; Welch t test, *t*(57.50) = 2.31, *p* = .023, "
            "adjusted *p* = .046, BF\u2081\u2080 = 3.21: moderate evidence for a difference. "
            "Confusion: adaptive *M* = 0.35, random *M* = 0.34; difference (adaptive \u2212 random) 0.01, 95% CI "
            "[\u22120.02, 0.04]; *d* = 0.08, 95% CI [\u22120.43, 0.59]; Welch t test, *t*(55.12) = 0.83, "
            "*p* = .410, BF\u2080\u2081 = 2.22: no evidence either way. "
            "H1 was supported for error but inconclusive for confusion.");
}

TEST(ResultsText, ContradictedWhenTheDifferenceGoesTheOtherWay) {
  Finding error = welch("error", -0.06, Strength::evidence_for_difference, "moderate evidence for a difference");
  const std::string p = md_paragraph(h1(false), {error, inconclusive_confusion()});
  EXPECT_EQ(p.rfind("**H1** (exploratory): ", 0), 0u) << p;
  EXPECT_NE(p.find("difference (adaptive \u2212 random) \u22120.06, 95% CI [\u22120.11, \u22120.01]; *d* = \u22120.50"),
            std::string::npos) << p;
  EXPECT_EQ(closing(p), "H1 was contradicted for error (a difference in the other direction) and inconclusive "
                        "for confusion.");
  // The same finding answers a hypothesis of "less" the other way round.
  Hypothesis less = h1();
  less.direction = "less";
  EXPECT_EQ(feint::publish::answer(less, error), Answer::supported);
  // A contrast written B - A is read against A: random - adaptive = -0.06 is adaptive > random.
  Finding flipped = welch("error", -0.06, Strength::evidence_for_difference, "moderate evidence for a difference");
  flipped.contrast = "random - adaptive";
  EXPECT_EQ(feint::publish::answer(h1(), flipped, "adaptive"), Answer::supported);
  EXPECT_EQ(feint::publish::answer(h1(), flipped), Answer::contradicted);  // A unknown: its first side
}

TEST(ResultsText, EvidenceForNoDifferenceIsStatedAsSuch) {
  Finding confusion = inconclusive_confusion();
  confusion.strength = Strength::evidence_for_no_difference;
  confusion.grade = Grade::moderate;
  confusion.bf10 = 0.2;  // BF01 = 5.00
  confusion.evidence = "moderate evidence for no difference";
  const std::string p = md_paragraph(h1(), {supported_error(), confusion});
  EXPECT_NE(p.find("BF\u2080\u2081 = 5.00: moderate evidence for no difference."), std::string::npos) << p;
  EXPECT_EQ(closing(p), "H1 was supported for error but not supported for confusion (evidence for no difference).");
}

TEST(ResultsText, NotComputableAndMissingMeasuresSaySo) {
  Finding confusion;
  confusion.hypothesis = "H1";
  confusion.measure = "confusion";
  confusion.strength = Strength::not_computable;
  confusion.evidence = "not computable";
  confusion.sentence = "Only one condition ('adaptive') is in the data: there is no comparison between "
                       "conditions, so this question cannot be answered.";
  std::string p = md_paragraph(h1(), {supported_error(), confusion});
  EXPECT_NE(p.find(" Confusion: Only one condition ('adaptive') is in the data: there is no comparison between "
                   "conditions, so this question cannot be answered. H1 was"),
            std::string::npos) << p;
  EXPECT_EQ(closing(p), "H1 was supported for error but not testable for confusion.");
  // A declared measure without any finding.
  p = md_paragraph(h1(), {supported_error()});
  EXPECT_NE(p.find(" Confusion: no result was computed. "), std::string::npos) << p;
  EXPECT_EQ(closing(p), "H1 was supported for error but not testable for confusion.");
  // No finding at all (e.g. H2 of a study without a questionnaire): one sentence, no per-measure
  // "no result was computed".
  p = md_paragraph(h1(), {});
  EXPECT_EQ(p.find("no result was computed"), std::string::npos) << p;
  EXPECT_NE(p.find(" H1 could not be tested: the study has no results on error and confusion."), std::string::npos)
      << p;
}

TEST(ResultsText, AbsentNumbersAreLeftOutNeverPrintedAsNan) {
  Finding bare;
  bare.hypothesis = "H1";
  bare.measure = "error";
  bare.strength = Strength::no_evidence_either_way;
  bare.evidence = "no evidence either way";
  bare.estimate = std::nan("");
  bare.p = std::nan("");
  bare.effect_size = EffectSize{"d", std::nan(""), std::nullopt, std::nullopt};
  bare.statistics = "t(57.50) = NA, p = NA";
  Finding conf = inconclusive_confusion();
  conf.ci_low = -std::numeric_limits<double>::infinity();  // a one-sided interval, open below as R's
  conf.effect_size.reset();
  conf.bf10.reset();
  conf.bf_note = "no Bayes factor for this test";
  const std::vector<Finding> fs{bare, conf};
  for (const auto format : {ResultsFormat::markdown, ResultsFormat::latex, ResultsFormat::html}) {
    std::string t = results_text({h1()}, fs, format);
    // LaTeX's \infty is the one-sided interval's open end, not a number printed as "inf".
    for (auto k = t.find("\\infty"); k != std::string::npos; k = t.find("\\infty")) t.erase(k, 6);
    for (const char* bad : {"nan", "NA", "inf", "Inf"}) EXPECT_EQ(t.find(bad), std::string::npos) << bad << "\n" << t;
  }
  const std::string p = md_paragraph(h1(), fs);
  EXPECT_NE(p.find(" Error: no evidence either way. Confusion: adaptive *M* = 0.35, random *M* = 0.34; difference "
                   "(adaptive \u2212 random) 0.01, 95% CI (\u2212\u221e, 0.04]; Welch t test, *t*(55.12) = 0.83, *p* = .410, "
                   "no Bayes factor: "
                   "no evidence either way. "),
            std::string::npos) << p;
}

// Per measure the headline is the whole comparison with its means (the mixed model's condition
// effect), not a family's member nor a one-sample test; the rest are counted.
TEST(ResultsText, TheHeadlinePerMeasureAndTheOthersCounted) {
  Finding family = welch("error", 0.09, Strength::evidence_for_difference, "strong evidence for a difference");
  family.member = "test 3";
  family.means.reset();
  Finding interaction;  // an F test: no contrast, no estimate
  interaction.hypothesis = "H1";
  interaction.measure = "error";
  interaction.strength = Strength::no_evidence_either_way;
  Finding reference = welch("error", 0.2, Strength::evidence_for_difference, "strong evidence for a difference");
  reference.contrast = "mean - 0.5";
  Finding headline = supported_error();
  Finding warning;  // no measure: counted among the others, never a headline
  warning.hypothesis = "H1";
  warning.strength = Strength::not_computable;
  const std::string p = md_paragraph(h1(), {family, interaction, reference, headline, warning, inconclusive_confusion()});
  EXPECT_NE(p.find("Error: adaptive *M* = 0.61, random *M* = 0.55; difference (adaptive \u2212 random) 0.06"),
            std::string::npos) << p;
  EXPECT_NE(p.find(" The 4 other findings on H1 (2 with evidence for a difference, 1 with no evidence either way, "
                   "and 1 not computable) are in the tables. H1 was supported"),
            std::string::npos) << p;
  // Alone, the family is the headline, and says which member its numbers are; its statistics
  // (which may be another member's) are left out.
  const std::string q = md_paragraph(h1(), {family, inconclusive_confusion()});
  EXPECT_NE(q.find("Welch t test (test 3, the family's smallest adjusted *p*), *p* = .023, adjusted *p* = .046"),
            std::string::npos) << q;
  EXPECT_EQ(q.find("*t*(57.50)"), std::string::npos) << q;
  // A confirmatory finding is the headline whatever the others.
  family.confirmatory = true;
  const std::string c = md_paragraph(h1(), {headline, family, inconclusive_confusion()});
  EXPECT_NE(c.find("Error: difference (adaptive \u2212 random) 0.09"), std::string::npos) << c;
  EXPECT_NE(c.find("The other finding on H1 (evidence for a difference) is in the tables."), std::string::npos) << c;
}

// An F test with no estimate and no direction cannot support a directed hypothesis.
TEST(ResultsText, AnFTestWithoutADirectionIsUndecided) {
  Finding f;
  f.hypothesis = "H1";
  f.measure = "error";
  f.strength = Strength::evidence_for_difference;
  f.evidence = "evidence for a difference";
  f.test = "F test (mixed model)";
  f.p = 0.0004;
  f.p_adjusted = 0.0012;
  f.statistics = "F(1, 58) = 14.20, p < .001, \u03b7G\u00b2 = .06";
  f.effect_size = EffectSize{"eta2_p", 0.197, 0.05, 0.36};
  f.bf_note = "no Bayes factor for this test";
  const std::string p = md_paragraph(h1(), {f, inconclusive_confusion()});
  EXPECT_NE(p.find("Error: partial *\u03b7*\u00b2 = .20, 95% CI [.05, .36]; F test (mixed model), *F*(1, 58) = "
                   "14.20, *p* < .001, adjusted *p* = .001, no Bayes factor: evidence for a difference."),
            std::string::npos) << p;
  EXPECT_EQ(closing(p), "H1 was undecided for error (a difference whose direction the test does not give) and "
                        "inconclusive for confusion.");
  Hypothesis two_sided = h1();
  two_sided.direction = "two-sided";
  EXPECT_EQ(feint::publish::answer(two_sided, f), Answer::supported);
}

// effectsize's intervals of proportions of variance are one-sided (upper bound 1): the text says
// so, as the findings' sentences do, and keeps a two-sided one as it is.
TEST(ResultsText, AOneSidedIntervalOfAProportionOfVarianceSaysOneSided) {
  Finding f;
  f.hypothesis = "H1";
  f.measure = "error";
  f.strength = Strength::no_evidence_either_way;
  f.evidence = "no evidence either way";
  f.test = "F test (mixed model)";
  f.p = 0.09;
  f.statistics = "F(2, 660) = 2.42, p = .090";
  f.effect_size = EffectSize{"eta2_p", 0.0073, 0.0, 1.0};
  const std::string p = md_paragraph(h1(), {f, inconclusive_confusion()});
  EXPECT_NE(p.find("Error: partial *\u03b7*\u00b2 = .01, one-sided 95% CI [.00, 1.00]; F test"), std::string::npos)
      << p;
  f.effect_size = EffectSize{"omega2", 0.15, 0.02, 1.0};
  EXPECT_NE(md_paragraph(h1(), {f, inconclusive_confusion()}).find("= .15, one-sided 95% CI [.02, 1.00]"),
            std::string::npos);
  f.effect_size = EffectSize{"d", 0.3, -0.2, 1.0};  // a d whose upper bound happens to be 1: two-sided
  EXPECT_NE(md_paragraph(h1(), {f, inconclusive_confusion()}).find("*d* = 0.30, 95% CI [\u22120.20, 1.00]"),
            std::string::npos);
}

// A study of three conditions run for one pair (compare = "adaptive,random"): the hypothesis is
// about that pair, so its headline is that pair's comparison, not the F across the three conditions
// (which ranks first otherwise) nor another pair's contrast listed before it.
TEST(ResultsText, AHypothesisAboutAPairOfThreeConditionsSpeaksThroughThatPair) {
  Finding across = welch("error", 0.0, Strength::no_evidence_either_way, "no evidence either way");
  across.id = "H1-model-condition-error";
  across.contrast.clear();
  across.direction.clear();
  across.means.reset();
  across.estimate.reset();
  across.omnibus = true;
  across.test = "F test (mixed model)";
  across.effect_size.reset();
  across.statistics = "F(2, 660) = 2.42, p = .090";
  Finding other = welch("error", 0.09, Strength::evidence_for_difference, "strong evidence for a difference");
  other.id = "H1-model-pair-error-adaptive-fixed-block";
  other.contrast = "adaptive - fixed-block";
  Finding pair = welch("error", 0.02, Strength::no_evidence_either_way, "no evidence either way");
  pair.id = "H1-model-pair-error-adaptive-random";
  Hypothesis h = h1(false);
  const std::string before = md_paragraph(h, {across, other, pair});
  EXPECT_NE(before.find("Error: F test (mixed model)"), std::string::npos) << before;  // no pair named
  h.pair = {"adaptive", "random"};
  const std::string p = md_paragraph(h, {across, other, pair});
  EXPECT_NE(p.find("Error: adaptive *M* = 0.57, random *M* = 0.55; difference (adaptive \u2212 random) 0.02"),
            std::string::npos)
      << p;
  EXPECT_EQ(p.find("fixed-block"), std::string::npos) << p;
  EXPECT_EQ(closing(p), "H1 was inconclusive for error and not testable for confusion.");
  // The pair's sides in the other order, and an exposure contrast of the pair, answer it too.
  pair.contrast = "random - adaptive";
  EXPECT_NE(md_paragraph(h, {across, other, pair}).find("Error: random *M* = "), std::string::npos);
  pair.contrast = "adaptive slope - random slope";
  EXPECT_NE(md_paragraph(h, {across, other, pair}).find("Error: adaptive slope *M* = "), std::string::npos);
}

// H2 is two-sided and answered per questionnaire item (the findings' measures, not "questionnaire").
TEST(ResultsText, ATwoSidedHypothesisPerItemAndTheWordCap) {
  const Hypothesis h2{"H2", "The questionnaire answers differ between adaptive and random.", {"questionnaire"},
                      "two-sided", false, {}};
  std::vector<Finding> fs;
  const std::vector<std::string> items = {"trust", "entertainment", "deception", "intelligence", "likeability",
                                          "safety", "competence", "warmth", "discomfort", "animacy"};
  for (std::size_t i = 0; i < items.size(); ++i) {
    Finding f = i == 0 ? welch(items[i], -0.8, Strength::evidence_for_difference, "strong evidence for a difference")
                       : inconclusive_confusion();
    f.hypothesis = "H2";
    f.measure = items[i];
    f.effect_size = EffectSize{"r_rb", -0.34, -0.55, -0.09};
    f.test = "Mann-Whitney test";
    f.statistics = "W = 310.5, p = .023, r = -.34";
    fs.push_back(f);
  }
  const std::string few = md_paragraph(h2, {fs[0], fs[1]});
  EXPECT_NE(few.find("Trust: adaptive *M* = \u22120.25, random *M* = 0.55; difference (adaptive \u2212 random) "
                     "\u22120.80, 95% CI [\u22120.85, \u22120.75]; rank-biserial *r* = \u2212.34, 95% CI [\u2212.55, "
                     "\u2212.09]; Mann-Whitney test, *W* = 310.5, *p* = .023, adjusted *p* = .046, BF\u2081\u2080 = "
                     "3.21: strong evidence for a difference."),
            std::string::npos) << few;
  EXPECT_EQ(closing(few, "H2"), "H2 was supported for trust but inconclusive for entertainment.");
  // Ten items do not fit in 250 words: the last items' numbers are left to the tables, and the
  // answer still names every item.
  for (const auto format : {ResultsFormat::markdown, ResultsFormat::latex, ResultsFormat::html}) {
    const auto ps = results_paragraphs(std::vector<Hypothesis>{h2}, fs, format);
    ASSERT_EQ(ps.size(), 1u);
    EXPECT_LE(word_count(ps[0]), 250u) << ps[0];
    EXPECT_GT(word_count(ps[0]), 150u) << ps[0];
  }
  const std::string p = md_paragraph(h2, fs);
  EXPECT_NE(p.find(" The results on "), std::string::npos) << p;
  EXPECT_NE(p.find(", and animacy are in the tables. H2 was supported for trust but inconclusive for entertainment, "
                   "deception, intelligence, likeability, safety, competence, warmth, discomfort, and animacy."),
            std::string::npos) << p;
  // A statement alone beyond the cap is cut short, so that the answer stays in.
  Hypothesis wordy = h2;
  for (int i = 0; i < 300; ++i) wordy.statement += " word";
  const std::string w = md_paragraph(wordy, fs);
  EXPECT_LE(word_count(w), 250u);
  EXPECT_NE(w.find("word ... "), std::string::npos) << w;
  EXPECT_NE(w.find("H2 was supported for trust"), std::string::npos) << w;
}

TEST(ResultsText, WordCountCountsWhitespaceSeparatedTokens) {
  EXPECT_EQ(word_count(""), 0u);
  EXPECT_EQ(word_count("  a  b\tc\nd "), 4u);
  EXPECT_EQ(word_count("*t*(57.50) = 2.31,"), 3u);
}

TEST(ResultsText, HtmlAndLatexRenderTheSameWords) {
  const std::vector<Finding> fs{supported_error(), inconclusive_confusion()};
  const std::string html = results_text({h1()}, fs, ResultsFormat::html);
  EXPECT_EQ(html.rfind("<p class=\"results-text\" id=\"results-H1\"><strong>H1</strong> (confirmatory): ", 0), 0u)
      << html;
  // No-break spaces keep "p = .023" and an interval on one line of a phone's screen.
  EXPECT_NE(html.find("<i>t</i>(57.50)\u00a0=\u00a02.31, <i>p</i>\u00a0=\u00a0.023, adjusted <i>p</i>\u00a0=\u00a0.046, "
                      "BF<sub>10</sub>\u00a0=\u00a03.21"),
            std::string::npos) << html;
  EXPECT_NE(html.find("95%\u00a0CI\u00a0[0.01,\u00a00.11]"), std::string::npos) << html;
  EXPECT_NE(html.find("<strong>H1 was supported for error but inconclusive for confusion.</strong></p>\n"),
            std::string::npos) << html;
  const std::string tex = results_text({h1()}, fs, ResultsFormat::latex);
  EXPECT_NE(tex.find("H1 (confirmatory): People stay"), std::string::npos) << tex;
  EXPECT_NE(tex.find("Error: adaptive $M = 0.61$, random $M = 0.55$; difference (adaptive $-$ random) $0.06$, "
                     "95\\% CI $[0.01, 0.11]$; $d = 0.50$, 95\\% CI $[0.09, 0.91]$; Welch t test, $t(57.50) = 2.31$, "
                     "$p = .023$, adjusted $p = .046$, $\\mathrm{BF}_{10} = 3.21$: moderate evidence for a difference."),
            std::string::npos) << tex;
  EXPECT_NE(tex.find("$[-0.02, 0.04]$"), std::string::npos) << tex;
  EXPECT_NE(tex.find("$\\mathrm{BF}_{01} = 2.22$"), std::string::npos) << tex;
}

namespace {

bool have_pdflatex() { return std::system("command -v pdflatex >/dev/null 2>&1") == 0; }

}  // namespace

// Everything the LaTeX can hold (every effect size, chi-squared, a Bayes factor in scientific
// notation, TeX's special characters in the names) compiles in a paper without a package.
TEST(ResultsText, LatexCompilesInAPaper) {
  if (!have_pdflatex()) GTEST_SKIP() << "pdflatex not installed: LaTeX compile check of the Results text skipped";
  // Two hypotheses of three measures each, so that every effect size is shown within the cap.
  Hypothesis h = h1();
  h.statement = "Under 50% & more_of #1 {braces} ~ \"quoted\" ^ \\ < > \u2248 \u00b1 it differs.";
  h.measures.clear();
  Hypothesis g = h;
  g.id = "H2";
  g.direction = "two-sided";
  std::vector<Finding> fs;
  for (const char* es : {"d", "d_z", "g", "r_rb", "eta2_p", "eta2_G"}) {
    Finding f = supported_error();
    f.hypothesis = fs.size() < 3 ? "H1" : "H2";
    f.measure = std::string("m_") + es + " & 100%";
    f.contrast = "cond_A #1 - cond_B {2}";
    f.effect_size = EffectSize{es, 0.3, 0.1, 0.5};
    fs.push_back(f);
  }
  fs[0].statistics = "\u03c7\u00b2(2) = 5.21, p = .023";
  fs[0].bf10 = 1e-6;
  fs[1].statistics = "TOST: t(29) = -2.10, p = .023";
  fs[1].bf10 = 2.3e5;
  const std::string tex = results_text({h, g}, fs, ResultsFormat::latex);
  TempDir dir;
  write_text(dir / "results.tex", tex);
  write_text(dir / "paper.tex", "\\documentclass{article}\n\\usepackage[T1]{fontenc}\n\\begin{document}\n"
                                "\\section{Results}\n\\input{results.tex}\n\\end{document}\n");
  const int rc = std::system(("cd " + shell_quote(dir.path().string()) +
                              " && pdflatex -interaction=nonstopmode -halt-on-error paper.tex > out.txt 2>&1")
                                 .c_str());
  EXPECT_EQ(rc, 0) << tex << "\n" << read_text(dir / "out.txt");
  EXPECT_NE(tex.find("$\\chi^2(2) = 5.21$"), std::string::npos) << tex;
  EXPECT_NE(tex.find("$\\mathrm{BF}_{10} = 2.3 \\times 10^{5}$"), std::string::npos) << tex;
  EXPECT_NE(tex.find("$\\mathrm{BF}_{01} = 1.0 \\times 10^{6}$"), std::string::npos) << tex;
  EXPECT_NE(tex.find("TOST: $t(29) = -2.10$"), std::string::npos) << tex;
  for (const char* es : {"$d = 0.30$", "$d_z = 0.30$", "$g = 0.30$", "rank-biserial $r = .30$",
                         "partial $\\eta^2 = .30$", "generalized $\\eta^2 = .30$"})
    EXPECT_NE(tex.find(es), std::string::npos) << es << "\n" << tex;
}

// feint analyze writes both files, and report.html and report.md open with the paragraphs.
TEST(ResultsText, AnalyzeWritesThemAndTheReportOpensWithThem) {
  TempDir dir;
  const fs::path out = dir.path() / "out";
  const auto r = run_feint("analyze " + shell_quote(std::string(FEINT_SOURCE_DIR) + "/data/demo") + " -o " +
                           shell_quote(out.string()) + " --no-figures");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string md = read_text(out / "results-text.md");
  const std::string tex = read_text(out / "results-text.tex");
  ASSERT_FALSE(md.empty()) << "results-text.md not written";
  ASSERT_FALSE(tex.empty()) << "results-text.tex not written";
  // One paragraph per hypothesis (H1, H2), each with its answer, within the cap.
  const auto h2 = md.find("\n\n**H2** (");
  ASSERT_EQ(md.rfind("**H1** (", 0), 0u) << md;
  ASSERT_NE(h2, std::string::npos) << md;
  for (const std::string& p : {md.substr(0, h2), md.substr(h2 + 2)}) {
    EXPECT_LE(word_count(p), 250u) << p;
    EXPECT_NE(p.find(p.substr(2, 2) + " was "), std::string::npos) << p;
  }
  EXPECT_EQ(tex.rfind("% The Results paragraphs of feint analyze", 0), 0u) << tex;
  EXPECT_NE(tex.find("\nH1 ("), std::string::npos) << tex;
  for (const std::string* t : {&md, &tex}) EXPECT_EQ(t->find("nan"), std::string::npos) << *t;
  // report.html: the first section after the contents is Results, which opens with H1's paragraph;
  // the findings follow folded.
  const std::string html = read_text(out / "report.html");
  const auto nav_end = html.find("</nav>\n");
  ASSERT_NE(nav_end, std::string::npos);
  const std::string opening = "<section id=\"results\">\n<h2>Results</h2>\n<p class=\"results-text\" id=\"results-H1\">";
  EXPECT_EQ(html.substr(nav_end + 7, opening.size()), opening);
  const auto details = html.find("<details id=\"findings\">");
  ASSERT_NE(details, std::string::npos);
  EXPECT_LT(html.find("id=\"results-H2\""), details);
  EXPECT_LT(details, html.find("<ul class=\"findings\">"));
  EXPECT_LT(html.find("</details>"), html.find("<section id=\"design\">"));
  // report.md: Results first, its paragraphs as in results-text.md, then the findings in detail.
  const std::string report = read_text(out / "report.md");
  const auto results = report.find("\n## Results\n\n");
  ASSERT_NE(results, std::string::npos);
  EXPECT_EQ(report.find("\n## "), results);
  EXPECT_EQ(report.substr(results + 13, md.size()), md);
  EXPECT_LT(report.find("### Findings in detail"), report.find("## Design"));
}
