// The questionnaire's findings (H2): see questionnaire_findings.hpp.
#include "questionnaire_findings.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "condition_effect.hpp"
#include "feint/tables/writers.hpp"
#include "finding_words.hpp"

namespace feint::analysis::detail {

namespace {

// A sentence starts with a capital, as every finding's.
std::string title_case(std::string s) {
  if (!s.empty() && s[0] >= 'a' && s[0] <= 'z') s[0] = static_cast<char>(s[0] - 'a' + 'A');
  return s;
}

// The t test of the same item, condition(s) as a rank row (the questionnaire's secondary test).
const stats::TestResult* t_row_of(const tables::LikertAnalysis& a, const tables::TidyRow& rank) {
  for (const auto& row : a.rows)
    if (is_t_test(row.result.test) && row.metric == rank.metric && row.group1 == rank.group1 &&
        row.group2 == rank.group2)
      return &row.result;
  return nullptr;
}

// H2: the questionnaire, against the reference or (between) between the conditions. Each finding
// rests on the primary rank test (Wilcoxon signed-rank / Mann-Whitney, rank-biserial r); the t
// test beside it gives the means, their difference with its CI and the JZS Bayes factor, which the
// strength uses as for every test (docs/findings.md "Questionnaire").
void add_likert_findings(std::vector<Finding>& out, const std::optional<tables::LikertAnalysis>& a,
                         bool between, const WordingRules& rules) {
  if (!a) return;
  for (const auto& row : a->rows) {
    if (row.result.test != "mann_whitney" && row.result.test != "wilcoxon_signed_rank") continue;
    stats::TestResult primary = row.result;
    const stats::TestResult* t = t_row_of(*a, row);
    // Paired (within participants): the signed-rank test of the differences A - B compares two
    // conditions, not a mean with a reference.
    const bool paired = between && a->paired;
    if (t) {
      primary.mean1 = t->mean1;
      primary.mean2 = t->mean2;
      primary.mu = paired ? std::nullopt : t->mu;
      primary.estimate = t->estimate;
      primary.conf_low = t->conf_low;
      primary.conf_high = t->conf_high;
      primary.conf_level = t->conf_level;
      primary.log_bf10 = t->log_bf10;
    }
    const std::string what =
        between ? fmt::format("{}: {} vs {}{}", row.metric, row.group1, row.group2,
                              one_sided_words(row.result.alternative, row.group1, row.group2))
                : fmt::format("{}{} against the reference", row.metric,
                              row.group1.empty() ? std::string() : " (" + row.group1 + ")");
    Finding f = difference_finding(
        fmt::format("H2-{}-{}{}", between ? "compare" : "reference", row.metric,
                    row.group1.empty() || between ? std::string() : "-" + row.group1),
        "H2",
        between ? fmt::format("Do the conditions differ on {}?", row.metric)
                : fmt::format("Does {} differ from the reference?", row.metric),
        what, primary, nullptr, between ? "questionnaire-compare" : "questionnaire", rules);
    f.measure = row.metric;
    if (paired) {
      const double lean = f.estimate ? *f.estimate : primary.rank_biserial.value_or(0.0);
      f.contrast = "A - B";
      f.direction = fmt::format("A {} B", lean > 0 ? ">" : lean < 0 ? "<" : "=");
      f.test = "Wilcoxon signed-rank test (paired)";
      if (row.result.alternative != stats::Alternative::two_sided) f.test = "one-sided " + f.test;
    }
    if (between) detail::name_conditions(f, row.group1, row.group2);
    if (primary.log_bf10) {
      f.bf_note = fmt::format("JZS Bayes factor of the {} on the same answers (secondary to the {})",
                              t ? t->method : std::string("t test"), row.result.method);
      // The sentence names the Bayes factor its strength rests on, and which test it belongs to.
      const std::string bf = ", " + tables::apa_bayes_factor(*primary.log_bf10) + " of the t test";
      f.statistics += bf;
      if (f.sentence.size() > 2 && f.sentence.compare(f.sentence.size() - 2, 2, ").") == 0)
        f.sentence.insert(f.sentence.size() - 2, bf);
    }
    out.push_back(std::move(f));
  }
}

// How much, in the omnibus finding's words: each condition's mean and the rank epsilon squared
// ("M = 4.80 (adaptive), 5.10 (random), 4.60 (fixed-block); rank ε² = .11; χ²(2) = 3.23, ...").
void describe_omnibus(Finding& f, const tables::LikertConditions& a, std::size_t k) {
  if (f.strength == Strength::not_computable || f.statistics.empty()) return;
  auto mean_of = [&](const std::string& c) -> std::optional<double> {
    for (const auto& pair : a.pairs)
      for (const auto& s : pair.summaries)
        if (s.name == a.names[k] && s.group == c) return s.mean;
    return std::nullopt;
  };
  std::vector<std::string> means;
  for (const auto& c : a.conditions)
    if (const auto m = mean_of(c)) means.push_back(fmt::format("{:.2f} ({})", *m, c));
  std::string words = means.empty() ? "" : fmt::format("M = {}; ", fmt::join(means, ", "));
  if (f.effect_size) {
    std::string e = fmt::format("{:.2f}", f.effect_size->value);
    if (e.rfind("0.", 0) == 0) e.erase(0, 1);
    words += a.paired ? fmt::format("Kendall's W = {}; ", e) : fmt::format("rank \u03b5\u00b2 = {}; ", e);
  }
  if (const auto at = f.sentence.rfind("(" + f.statistics); at != std::string::npos) f.sentence.insert(at + 1, words);
}

// H2 with three or more conditions and no pair named: per item, the Kruskal-Wallis finding, then
// one finding per pair (as two conditions are compared, the p Holm-adjusted over the item's
// pairs), protected by the item's omnibus finding.
void add_likert_conditions_findings(std::vector<Finding>& out, const std::optional<tables::LikertConditions>& a,
                                    const WordingRules& rules) {
  if (!a) return;
  const std::string conditions = fmt::format("{}", fmt::join(a->conditions, ", "));
  for (std::size_t k = 0; k < a->omnibus.size(); ++k) {
    const tables::TidyRow& row = a->omnibus[k];
    Finding omnibus = difference_finding(
        fmt::format("H2-conditions-{}", row.metric), "H2", fmt::format("Do the conditions differ on {}?", row.metric),
        fmt::format("{} across the {} conditions ({})", row.metric, a->conditions.size(), conditions), row.result,
        nullptr, "questionnaire-conditions", rules);
    omnibus.measure = row.metric;
    omnibus.omnibus = true;
    if (a->paired && a->kendalls_w[k])  // Friedman's effect size (the omnibus row has no field for it)
      omnibus.effect_size = EffectSize{"kendalls_w", *a->kendalls_w[k], std::nullopt, std::nullopt};
    describe_omnibus(omnibus, *a, k);
    out.push_back(omnibus);
    for (const auto& pair : a->pairs) {
      std::optional<tables::LikertAnalysis> one = pair;
      one->rows = {pair.rows[2 * k], pair.rows[2 * k + 1]};
      std::vector<Finding> fs;
      add_likert_findings(fs, one, true, rules);
      for (auto& f : fs) {
        f.id = fmt::format("H2-pair-{}-{}-{}", row.metric, one->rows[0].group1, one->rows[0].group2);
        f.question = fmt::format("Which conditions differ on {}?", row.metric);
        f.source = "questionnaire-conditions";
        detail::protect_by_omnibus(f, &omnibus, row.metric);
        out.push_back(std::move(f));
      }
    }
  }
}

// A yes/no comparison of two conditions (Fisher's exact test between participants, McNemar's exact
// test within), with the proportions of yes and the conditional odds ratio (docs/yes-no.md). No
// Bayes factor exists here, so a large p is never evidence for no difference. Across three or more
// conditions `row` is one pair, its p Holm-adjusted over the question's pairs.
Finding yes_no_pair_finding(const tables::TidyRow& row, const tables::YesNoAnalysis& a, std::string id,
                            std::string question, const WordingRules& rules) {
  const bool paired = row.result.test == "mcnemar_exact";
  const stats::TestResult& r = row.result;
  const std::string what = fmt::format("{} (yes/no): {} vs {}", row.metric, row.group1, row.group2);
  std::string title = what;  // a sentence starts with a capital, as every finding's
  if (!title.empty() && title[0] >= 'a' && title[0] <= 'z') title[0] = static_cast<char>(title[0] - 'a' + 'A');
  Finding f = difference_finding(std::move(id), "H2", std::move(question), what, r, nullptr, "yes-no", rules);
  f.measure = row.metric;
  detail::name_conditions(f, row.group1, row.group2);
  f.test = paired ? "McNemar's exact test" : "Fisher's exact test";
  if (!r.computed || !r.mean1 || !r.mean2) return f;
  f.direction = fmt::format("{} {} {}", row.group1, *r.mean1 > *r.mean2 ? ">" : *r.mean1 < *r.mean2 ? "<" : "=",
                            row.group2);
  // The difference of the proportions of yes with its interval (prop.test's, beside Fisher's);
  // the odds ratio, whose null value is 1, is the effect size.
  f.estimate.reset();
  f.ci_low.reset();
  f.ci_high.reset();
  for (const auto& other : a.rows)
    if (other.metric == row.metric && other.group1 == row.group1 && other.group2 == row.group2 &&
        other.result.test == (paired ? "mcnemar" : "prop_test") && other.result.computed) {
      f.estimate = other.result.estimate;
      f.ci_low = other.result.conf_low;
      f.ci_high = other.result.conf_high;
    }
  if (r.estimate) f.effect_size = EffectSize{"odds_ratio", *r.estimate, r.conf_low, r.conf_high};
  const std::string odds =
      r.estimate && r.conf_low && r.conf_high
          ? fmt::format("; odds ratio {:.2f}, {:.0f}% CI [{:.2f}, {}]", *r.estimate, 100 * r.conf_level, *r.conf_low,
                        std::isinf(*r.conf_high) ? std::string("inf") : fmt::format("{:.2f}", *r.conf_high))
          : std::string();
  f.statistics = f.test + ", " + tables::apa_p(*r.p_value) +
                 (r.p_adjusted ? ", Holm-adjusted " + tables::apa_p(*r.p_adjusted) : std::string());
  f.sentence = fmt::format(
      "{}: {} (yes {:.0f}% of {} vs {:.0f}% of {}{}; {}{}).", title, f.evidence, 100 * *r.mean1, r.n1, 100 * *r.mean2,
      r.n2, odds, f.statistics,
      f.strength == Strength::evidence_for_difference
          ? ""
          : "; no Bayes factor is available for this test, so a non-significant result is not evidence for no difference");
  return f;
}

// "yes 67% of 12 (adaptive), 58% of 12 (random), 75% of 12 (fixed-block): most often in
// fixed-block, least in random": how often each condition answered yes, and which way they lean.
std::string yes_no_which_way(const tables::YesNoAnalysis& a, const std::string& question) {
  std::vector<std::string> parts, most, least;
  double top = -1, bottom = 2;
  for (const auto& s : a.summaries) {
    if (s.question != question || s.proportion.n == 0 ||
        std::find(a.compared.begin(), a.compared.end(), s.group) == a.compared.end())
      continue;
    const double p = s.proportion.estimate;
    parts.push_back(fmt::format("{:.0f}% of {} ({})", 100 * p, s.proportion.n, s.group));
    if (p > top) top = p, most.clear();
    if (p == top) most.push_back(s.group);
    if (p < bottom) bottom = p, least.clear();
    if (p == bottom) least.push_back(s.group);
  }
  if (parts.empty()) return {};
  const std::string lean = top == bottom ? "the same in every condition"
                                         : fmt::format("most often in {}, least in {}", fmt::join(most, " and "),
                                                       fmt::join(least, " and "));
  return fmt::format("yes {}: {}", fmt::join(parts, ", "), lean);
}

// Three or more conditions, per question: the omnibus finding (Fisher's exact test of the C x 2
// table, or the chi-square test where its tables were too many; within participants Cochran's Q)
// stated as which way (the conditions by their proportion of yes), how much (Cramér's V with its
// interval, between) and how sure; then one finding per pair, Holm-adjusted over the pairs and
// protected by the omnibus finding.
void add_yes_no_conditions_findings(std::vector<Finding>& out, const tables::YesNoAnalysis& a,
                                    const WordingRules& rules) {
  const bool paired = a.settings.paired;
  const std::size_t pairs = a.compared.size() * (a.compared.size() - 1) / 2;
  for (std::size_t k = 0; k < a.questions.size(); ++k) {
    const std::string& q = a.questions[k];
    const tables::TidyRow& fisher = paired ? a.omnibus[k] : a.omnibus[2 * k];
    const tables::TidyRow* chisq = paired ? nullptr : &a.omnibus[2 * k + 1];
    const tables::TidyRow& row = fisher.result.computed || !chisq ? fisher : *chisq;
    const stats::TestResult& r = row.result;
    const std::string what = fmt::format("{} (yes/no) across the {} conditions ({}){}", q, a.compared.size(),
                                         fmt::join(a.compared, ", "), paired ? ", within participants" : "");
    Finding f = difference_finding("H2-yesno-" + q, "H2",
                                   fmt::format("Do the conditions differ in how often they answer yes to {}?", q), what,
                                   r, nullptr, "yes-no", rules);
    f.measure = q;
    f.omnibus = true;
    f.test = r.test == "cochran_q" ? "Cochran's Q test" : r.test == "chisq_test" ? "chi-square test" : "Fisher's exact test";
    f.estimate.reset();  // the chi-square row's estimate is Cramér's V, not a difference
    f.ci_low.reset();
    f.ci_high.reset();
    f.direction.clear();
    f.contrast.clear();
    if (r.computed && r.p_value) {
      const auto& x = chisq ? chisq->result : r;
      if (chisq && x.computed && x.estimate)
        f.effect_size = EffectSize{"cramers_v", *x.estimate, x.conf_low, x.conf_high};
      f.statistics = r.test == "fisher_exact_conditions" ? f.test + ", " + tables::apa_p(*r.p_value)
                                                         : tables::apa_string(r);
      std::string v;
      if (f.effect_size) {
        auto apa = [](double d) {  // APA: no leading zero for a value that cannot exceed 1
          std::string t = fmt::format("{:.2f}", d);
          return t.rfind("0.", 0) == 0 ? t.substr(1) : t;
        };
        v = fmt::format("; bias-corrected Cram\u00e9r's V = {}, one-sided {:.0f}% CI [{}, {}]", apa(f.effect_size->value),
                        100 * x.conf_level, apa(*f.effect_size->ci_low), apa(*f.effect_size->ci_high));
      }
      const std::string beside =
          chisq && &row != chisq && chisq->result.computed ? "; " + tables::apa_string(chisq->result) : std::string();
      f.sentence = fmt::format(
          "{}: {} ({}{}; {}{}{}).", title_case(what), f.evidence, yes_no_which_way(a, q), v, f.statistics, beside,
          f.strength == Strength::evidence_for_difference
              ? ""
              : "; no Bayes factor is available for this test, so a non-significant result is not evidence for no "
                "difference");
    }
    out.push_back(f);
    for (std::size_t j = 0; j < pairs; ++j) {
      const tables::TidyRow& pair = a.rows[(k * pairs + j) * 2];
      Finding p = yes_no_pair_finding(pair, a, fmt::format("H2-yesno-pair-{}-{}-{}", q, pair.group1, pair.group2),
                                      fmt::format("Which conditions differ in how often they answer yes to {}?", q),
                                      rules);
      detail::protect_by_omnibus(p, &f, q);
      out.push_back(std::move(p));
    }
  }
}

// The yes/no questions: two conditions compared (one finding per question), or three or more
// (the omnibus finding, then the pairs).
void add_yes_no_findings(std::vector<Finding>& out, const std::optional<tables::YesNoAnalysis>& a,
                         const WordingRules& rules) {
  if (!a) return;
  if (!a->omnibus.empty()) {
    add_yes_no_conditions_findings(out, *a, rules);
    return;
  }
  for (const auto& row : a->rows) {
    // Fisher's exact test between participants, McNemar's exact test within (docs/yes-no.md).
    if (row.result.test != "fisher_exact" && row.result.test != "mcnemar_exact") continue;
    out.push_back(yes_no_pair_finding(
        row, *a, "H2-yesno-" + row.metric,
        fmt::format("Do the conditions differ in how often they answer yes to {}?", row.metric), rules));
  }
}

}  // namespace

void add_questionnaire_findings(std::vector<Finding>& out, const StudyResults& r, const WordingRules& rules) {
  add_likert_findings(out, r.likert, false, rules);
  add_likert_findings(out, r.likert_compare_one_sided ? r.likert_compare_one_sided : r.likert_compare, true,
                      rules);
  add_likert_conditions_findings(out, r.likert_conditions, rules);
  add_yes_no_findings(out, r.yes_no, rules);
}

}  // namespace feint::analysis::detail
