// Yes/no questions across three or more conditions: per question the omnibus test (Fisher's exact
// test of the C x 2 table with Pearson's chi-square and Cramér's V beside it; within participants
// Cochran's Q), then every pair as two conditions are compared, Holm-adjusted over the pairs and
// protected by the omnibus test. See feint/tables/yes_no.hpp and docs/yes-no.md.
#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "feint/error.hpp"
#include "feint/io/number.hpp"
#include "feint/stats/contingency.hpp"
#include "feint/stats/p_adjust.hpp"
#include "feint/stats/proportions.hpp"
#include "yes_no_detail.hpp"

namespace feint::tables::detail {

namespace {

std::string joined(const std::vector<std::string>& v) { return fmt::format("{}", fmt::join(v, ", ")); }

std::size_t pair_count(const YesNoAnalysis& a) { return a.compared.size() * (a.compared.size() - 1) / 2; }

TidyRow omnibus_row(const YesNoAnalysis& a, const std::string& question, stats::TestResult r) {
  TidyRow row;
  row.metric = question;
  row.group1 = joined(a.compared);
  if (!r.computed) row.label = std::string(kNotComputable);
  else row.label = *r.p_value < a.settings.alpha ? "differ" : std::string(kNotSignificant);
  row.result = std::move(r);
  return row;
}

/// The test that protects question k's pairs: between participants Fisher's exact test, or the
/// chi-square test where Fisher's tables were too many to enumerate; within, Cochran's Q.
const TidyRow& protecting_test(const YesNoAnalysis& a, std::size_t k) {
  if (a.settings.paired) return a.omnibus[k];
  const TidyRow& fisher = a.omnibus[2 * k];
  return fisher.result.computed ? fisher : a.omnibus[2 * k + 1];
}

/// Holm over the pairs of each question, per test (rows: question, pair, primary then beside), then
/// the labels: a difference only where the adjusted p and the question's omnibus test both show it.
void adjust_and_protect(YesNoAnalysis& a) {
  const std::size_t pairs = pair_count(a);
  for (std::size_t k = 0; k < a.questions.size(); ++k) {
    const TidyRow& omnibus = protecting_test(a, k);
    const bool omnibus_shows =
        omnibus.result.computed && omnibus.result.p_value && *omnibus.result.p_value < a.settings.alpha;
    for (std::size_t test = 0; test < 2; ++test) {
      std::vector<std::optional<double>> p;
      for (std::size_t j = 0; j < pairs; ++j) {
        const auto& r = a.rows[(k * pairs + j) * 2 + test].result;
        p.push_back(r.computed ? r.p_value : std::nullopt);
      }
      const auto adjusted = stats::p_adjust(p, stats::PAdjustMethod::holm);
      for (std::size_t j = 0; j < pairs; ++j) {
        TidyRow& row = a.rows[(k * pairs + j) * 2 + test];
        row.result.p_adjusted = adjusted[j];
        const bool claims = row.label == "A>B" || row.label == "A<B";
        if (claims && (!omnibus_shows || !adjusted[j] || *adjusted[j] >= a.settings.alpha))
          row.label = std::string(kNotSignificant);
      }
    }
  }
}

/// Why the conditions cannot be compared between participants, or "" when they can: a participant
/// who answered in two conditions (the tests compare independent groups).
std::string shared_participant_reason(const io::Questionnaire& q) {
  std::map<std::string, std::string> condition_of;
  for (std::size_t r = 0; r < q.respondents(); ++r) {
    const auto [it, fresh] = condition_of.emplace(q.participants[r], q.conditions[r]);
    if (!fresh && it->second != q.conditions[r])
      return fmt::format("participant {} answered in both conditions {} and {}; Fisher's exact test compares "
                         "independent groups (give each participant one condition, or analyse the study within "
                         "participants)",
                         q.participants[r], it->second, q.conditions[r]);
  }
  return {};
}

void compare_between(YesNoAnalysis& a) {
  const auto& s = a.settings;
  for (const auto& question : a.questions) {
    std::vector<stats::YesCount> counts;
    std::vector<std::string> unanswered;
    for (const auto& c : a.compared) {
      const auto& p = summary_of(a, question, c).proportion;
      counts.push_back({p.x, p.n});
      if (p.n == 0) unanswered.push_back(c);
    }
    a.omnibus.push_back(omnibus_row(a, question, stats::fisher_exact_conditions(counts)));
    a.omnibus.push_back(omnibus_row(a, question, stats::chisq_independence(counts, s.test.conf_level)));
    if (!unanswered.empty())
      a.notes.push_back(fmt::format("{}: no answer in {}; left out of the omnibus tests.", question, joined(unanswered)));
    for (std::size_t i = 0; i < counts.size(); ++i)
      for (std::size_t j = i + 1; j < counts.size(); ++j) {
        const stats::YesNoTable t{counts[i].yes, counts[i].n, counts[j].yes, counts[j].n};
        a.rows.push_back(yes_no_comparison_row(question, a.compared[i], a.compared[j], stats::fisher_exact(t, s.test),
                                               s.alpha));
        a.rows.push_back(yes_no_comparison_row(question, a.compared[i], a.compared[j], stats::prop_test(t, s.test),
                                               s.alpha));
      }
  }
  a.notes.push_back(fmt::format(
      "{} conditions ({}), between participants. Per question, Fisher's exact test of the {} x 2 table of conditions "
      "by answer (primary; R's fisher.test(table): the probability of every table with the observed margins no more "
      "probable than the one observed) and beside it Pearson's chi-square test of independence (R's "
      "chisq.test(table, correct = FALSE)) with the bias-corrected Cramér's V and its one-sided {:g}% interval "
      "(effectsize::cramers_v); then each pair of conditions as two are compared: Fisher's exact test (primary) "
      "with the odds ratio of yes, and the chi-square test of two proportions (Yates-corrected) with their "
      "difference, p Holm-adjusted over the {} pairs of the question.",
      a.compared.size(), joined(a.compared), a.compared.size(), 100 * s.test.conf_level, pair_count(a)));
}

void compare_within(YesNoAnalysis& a, const io::Questionnaire& q) {
  std::vector<std::map<std::string, std::size_t>> in;
  for (const auto& c : a.compared) in.push_back(rows_by_participant(q, c));  // throws for a repeated answer
  std::vector<std::string> everywhere, left_out;
  std::set<std::string> seen;
  for (std::size_t r = 0; r < q.respondents(); ++r) {
    const std::string& p = q.participants[r];
    if (!seen.insert(p).second) continue;
    const bool all = std::all_of(in.begin(), in.end(), [&](const auto& m) { return m.count(p) != 0; });
    (all ? everywhere : left_out).push_back(p);
  }
  for (std::size_t k = 0; k < a.questions.size(); ++k) {
    std::vector<std::vector<int>> blocks;
    for (const auto& p : everywhere) {
      std::vector<int> answers;
      for (const auto& m : in)
        if (const auto& v = q.responses[k][m.at(p)]) answers.push_back(*v == 1 ? 1 : 0);
      if (answers.size() == in.size()) blocks.push_back(std::move(answers));
    }
    a.omnibus.push_back(omnibus_row(a, a.questions[k], stats::cochran_q(blocks)));
    for (std::size_t i = 0; i < in.size(); ++i)
      for (std::size_t j = i + 1; j < in.size(); ++j) {
        const stats::PairedYesNoTable t = paired_table(q, k, in[i], in[j]);
        a.rows.push_back(yes_no_comparison_row(a.questions[k], a.compared[i], a.compared[j],
                                               stats::mcnemar_exact(t, a.settings.test), a.settings.alpha));
        a.rows.push_back(yes_no_comparison_row(a.questions[k], a.compared[i], a.compared[j], stats::mcnemar_test(t),
                                               a.settings.alpha));
      }
  }
  a.notes.push_back(fmt::format(
      "{} conditions ({}), within participants (each participant answered after each condition). Per question, "
      "Cochran's Q test on the participants who answered it in every condition (Q = (C - 1)(C sum G_j^2 - N^2) / "
      "(C N - sum L_i^2), chi-square with C - 1 df; R's friedman.test on the 0/1 answers gives the same Q); then "
      "each pair of conditions compared paired: McNemar's exact test (primary; R's binom.test on the discordant "
      "pairs) with the conditional odds ratio b/c, and R's mcnemar.test beside it, p Holm-adjusted over the {} "
      "pairs of the question.",
      a.compared.size(), joined(a.compared), pair_count(a)));
  if (!left_out.empty()) {
    const std::vector<std::string> shown(left_out.begin(),
                                         left_out.begin() + std::min<std::ptrdiff_t>(10, std::ssize(left_out)));
    a.notes.push_back(fmt::format("Left out of Cochran's Q: {} participant{} did not answer in every condition ({}{}); "
                                  "each pair uses who answered in both of its conditions.",
                                  left_out.size(), left_out.size() == 1 ? "" : "s", joined(shown),
                                  left_out.size() > shown.size() ? ", ..." : ""));
  }
}

}  // namespace

void compare_across_conditions(YesNoAnalysis& a, const io::Questionnaire& q) {
  if (!q.has_condition) return;
  const std::vector<std::string> conditions = a.groups;
  std::string why = a.settings.paired ? std::string() : shared_participant_reason(q);
  a.compared = conditions;
  if (why.empty()) {
    try {
      if (a.settings.paired) compare_within(a, q);
      else compare_between(a);
    } catch (const InvalidData& e) {
      why = e.what();
    }
  }
  if (!why.empty()) {  // described only: the study's analysis goes on
    a.compared.clear();
    a.omnibus.clear();
    a.rows.clear();
    a.notes.resize(1);
    a.notes.push_back(fmt::format("The {} conditions are not compared: {}.", conditions.size(), why));
    return;
  }
  adjust_and_protect(a);
  a.notes.push_back(fmt::format(
      "Protected: a pair is labelled as differing only when its question's {} is significant at alpha = {} and the "
      "pair's Holm-adjusted p is below alpha. No test here gives evidence of no difference (no \u2248).",
      a.settings.paired ? "Cochran's Q test" : "Fisher's exact test (the chi-square test where it is not computed)",
      io::format_double(a.settings.alpha)));
}

namespace {

std::string percent_of(const YesNoAnalysis& a, const std::string& question, const std::string& c) {
  const auto& p = summary_of(a, question, c).proportion;
  return p.n == 0 ? "–" : fmt::format("{:.0f}%", 100 * p.estimate);
}

std::string fixed(std::optional<double> v, int decimals) {
  return v && std::isfinite(*v) ? fmt::format("{:.{}f}", *v, decimals) : "–";
}

TextTable omnibus_table(const YesNoAnalysis& a) {
  TextTable t;
  const bool paired = a.settings.paired;
  t.caption = paired ? fmt::format("Yes/no questions across the {} conditions within participants: Cochran's Q test "
                                   "per question",
                                   a.compared.size())
                     : fmt::format("Yes/no questions across the {} conditions: Fisher's exact test of the {} x 2 table "
                                   "per question",
                                   a.compared.size(), a.compared.size());
  t.header = {"Question"};
  for (const auto& c : a.compared) t.header.push_back("% yes " + c);
  const std::vector<const char*> tail =
      paired ? std::vector<const char*>{"n", "Q", "df", "p", "inference"}
             : std::vector<const char*>{"n", "Fisher p", "X2", "df", "p", "V", "V CI", "inference"};
  for (const char* h : tail) t.header.emplace_back(h);
  t.right_align.assign(t.header.size(), true);
  t.right_align.front() = false;
  t.right_align.back() = false;
  for (std::size_t k = 0; k < a.questions.size(); ++k) {
    std::vector<std::string> cells{a.questions[k]};
    for (const auto& c : a.compared) cells.push_back(percent_of(a, a.questions[k], c));
    const TidyRow& first = paired ? a.omnibus[k] : a.omnibus[2 * k];
    const auto& r = first.result;
    cells.push_back(std::to_string(r.computed ? r.n1 : 0));
    if (paired) {
      cells.insert(cells.end(), {fixed(r.statistic, 2), fixed(r.df, 0), r.computed ? format_p(r.p_value) : "–"});
    } else {
      const auto& x = a.omnibus[2 * k + 1].result;
      cells.insert(cells.end(), {r.computed ? format_p(r.p_value) : "–", fixed(x.statistic, 2), fixed(x.df, 0),
                                 x.computed ? format_p(x.p_value) : "–", fixed(x.estimate, 2),
                                 x.computed ? fmt::format("[{:.2f}, {:.2f}]", *x.conf_low, *x.conf_high) : "–"});
    }
    cells.push_back(protecting_test(a, k).label);
    t.rows.push_back({std::move(cells), false});
  }
  return t;
}

TextTable pairs_table(const YesNoAnalysis& a) {
  TextTable t;
  t.caption = fmt::format("Yes/no questions: each pair of conditions{} (Holm over the pairs of a question, protected "
                          "by its omnibus test)",
                          a.settings.paired ? " within participants" : "");
  t.header = {"Question", "A", "B", "Test", "Estimate", "CI", "Statistic", "p", "p Holm", "Inference"};
  t.right_align = {false, false, false, false, true, true, true, true, true, false};
  for (const auto& row : a.rows) {
    const auto c = comparison_cells(row);
    const auto& r = row.result;
    t.rows.push_back({{row.metric, row.group1, row.group2, c.test, c.estimate, c.ci, c.statistic,
                       r.computed ? format_p(r.p_value) : "–", r.computed ? format_p(r.p_adjusted) : "–", row.label}});
  }
  return t;
}

}  // namespace

std::string render_across_conditions(const YesNoAnalysis& a, OutputFormat format) {
  TextTable omnibus = omnibus_table(a);
  TextTable pairs = pairs_table(a);
  pairs.notes.assign(a.notes.begin() + 1, a.notes.end());
  for (const auto& row : a.omnibus)
    if (!row.result.note.empty())
      pairs.notes.push_back(fmt::format("{} ({}): {}", row.metric,
                                        row.result.test == "fisher_exact_conditions" ? "Fisher's exact test"
                                        : row.result.test == "cochran_q"             ? "Cochran's Q"
                                                                                     : "chi-square test",
                                        row.result.note));
  for (const auto& row : a.rows)
    if (!row.result.note.empty())
      pairs.notes.push_back(fmt::format("{}, {} vs {}: {}", row.metric, row.group1, row.group2, row.result.note));
  return "\n" + render_table(omnibus, format) + "\n" + render_table(pairs, format);
}

}  // namespace feint::tables::detail
