// A questionnaire across three or more conditions: Kruskal-Wallis per item, then every pair,
// Holm-adjusted over the pairs and protected by the omnibus test. See
// feint/tables/likert_conditions.hpp.
#include "feint/tables/likert_conditions.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "feint/error.hpp"
#include "feint/io/number.hpp"
#include "feint/stats/anova.hpp"
#include "feint/stats/p_adjust.hpp"
#include "feint/stats/rank_tests.hpp"
#include "respondents.hpp"

namespace feint::tables {

namespace {

// The items of each composite (indices into q.items); analyze_likert has checked the names.
std::vector<std::vector<std::size_t>> composite_members(const io::Questionnaire& q, const LikertSettings& s) {
  std::vector<std::vector<std::size_t>> members;
  for (const auto& c : s.composites) {
    std::vector<std::size_t> idx;
    for (const auto& item : c.items)
      if (const auto i = q.item_index(item)) idx.push_back(*i);
    members.push_back(std::move(idx));
  }
  return members;
}

// Kruskal-Wallis of name k over the conditions.
TidyRow omnibus_row(const detail::Answers& answers, std::size_t k, const std::string& name,
                    const std::vector<std::string>& conditions) {
  std::vector<std::vector<double>> groups;
  for (const auto& c : conditions) groups.push_back(answers.values_of(k, detail::respondents_in(answers.q, c)).first);
  TidyRow row;
  row.metric = name;
  std::string all;
  for (const auto& c : conditions) all += (all.empty() ? "" : ", ") + c;
  row.group1 = all;
  row.result = stats::kruskal_wallis(groups);
  return row;
}

// Friedman's test of name k: one block per participant (first appearance order), their answers in
// the conditions' order, NaN where missing (the block is then left out, as complete cases).
TidyRow friedman_row(const detail::Answers& answers, std::size_t k, const std::string& name,
                     const std::vector<std::string>& conditions) {
  const auto& q = answers.q;
  std::vector<std::string> order;
  std::map<std::string, std::vector<double>> blocks;
  for (std::size_t r = 0; r < q.respondents(); ++r) {
    auto [it, fresh] = blocks.try_emplace(q.participants[r], conditions.size(), std::nan(""));
    if (fresh) order.push_back(q.participants[r]);
    const auto j = static_cast<std::size_t>(
        std::find(conditions.begin(), conditions.end(), q.conditions[r]) - conditions.begin());
    if (const auto v = answers.value(k, r)) it->second[j] = *v;
  }
  std::vector<std::vector<double>> rows;
  for (const auto& p : order) rows.push_back(blocks[p]);
  TidyRow row;
  row.metric = name;
  for (const auto& c : conditions) row.group1 += (row.group1.empty() ? "" : ", ") + c;
  row.result = stats::friedman_test(rows);
  return row;
}

// Holm over the pairs of each name, per test kind (the rows of a pair alternate rank test, t test),
// then the labels: a difference only where the adjusted p and the name's omnibus test both show it.
void adjust_and_protect(LikertConditions& a) {
  const std::size_t rows = a.pairs.empty() ? 0 : a.pairs.front().rows.size();
  for (std::size_t i = 0; i < rows; ++i) {
    std::vector<std::optional<double>> p;
    for (const auto& pair : a.pairs) {
      const auto& r = pair.rows[i].result;
      p.push_back(r.computed ? r.p_value : std::nullopt);
    }
    const auto adjusted = stats::p_adjust(p, stats::PAdjustMethod::holm);
    const TidyRow& omnibus = a.omnibus[i / 2];
    const bool omnibus_shows = omnibus.result.computed && omnibus.result.p_value &&
                               *omnibus.result.p_value < a.settings.alpha;
    for (std::size_t j = 0; j < a.pairs.size(); ++j) {
      TidyRow& row = a.pairs[j].rows[i];
      row.result.p_adjusted = adjusted[j];
      const bool claims = row.label.find('>') != std::string::npos || row.label.find('<') != std::string::npos;
      if (claims && (!omnibus_shows || !adjusted[j] || *adjusted[j] >= a.settings.alpha))
        row.label = std::string(kNotSignificant);
    }
  }
}

// What the within-participant tables show.
void add_within_notes(LikertConditions& a) {
  a.notes.push_back(fmt::format(
      "{} conditions ({}), within participants (each participant answered after each condition). Per item, "
      "Friedman's test (R's friedman.test(y ~ condition | participant), tie-corrected) on the participants who "
      "answered the item in every condition, with Kendall's W = X2 / (n (k - 1)); then each pair of conditions "
      "compared paired: the Wilcoxon signed-rank test on the differences A - B (primary; matched-pairs r, "
      "positive when A answers higher) and the paired t-test with d_z and the JZS Bayes factor beside it, p "
      "Holm-adjusted over the {} pairs of the item (R's pairwise.wilcox.test(y, g, paired = TRUE, "
      "p.adjust.method = \"holm\")).",
      a.conditions.size(), fmt::join(a.conditions, ", "), a.pairs.size()));
  a.notes.push_back(fmt::format(
      "Protected: a pair is labelled as differing only when its item's Friedman test is significant at alpha = {} "
      "and the pair's Holm-adjusted p is below alpha.",
      io::format_double(a.settings.alpha)));
  for (const auto& row : a.omnibus)
    if (!row.result.note.empty()) a.notes.push_back(fmt::format("{} (Friedman): {}.", row.metric, row.result.note));
  for (const auto& pair : a.pairs)
    for (const auto& note : pair.notes)
      if (note.rfind("Left out:", 0) == 0) a.notes.push_back(fmt::format("{} vs {}: {}", pair.groups.front(),
                                                                        pair.settings.compare->second, note));
}

}  // namespace

LikertConditions analyze_likert_conditions(const io::Questionnaire& q, const LikertSettings& settings) {
  if (!q.has_condition)
    throw UsageError(fmt::format("{}: no condition column: the conditions cannot be compared", q.source));
  LikertConditions a;
  a.settings = settings;
  a.source = q.source;
  a.conditions = q.condition_names();
  if (a.conditions.size() < 2)
    throw UsageError(fmt::format("{}: {} condition(s): a comparison needs two or more", q.source, a.conditions.size()));
  for (std::size_t i = 0; i < a.conditions.size(); ++i)
    for (std::size_t j = i + 1; j < a.conditions.size(); ++j) {
      LikertSettings s = settings;
      s.compare = std::pair{a.conditions[i], a.conditions[j]};
      s.condition.clear();
      s.p_adjust = stats::PAdjustMethod::none;  // Holm over the pairs below, not over the items
      a.pairs.push_back(analyze_likert(q, s));  // between: throws InvalidData for a shared participant
    }
  a.names = a.pairs.front().names;
  const auto members = composite_members(q, settings);
  const detail::Answers answers{q, members};
  a.paired = settings.paired;
  for (std::size_t k = 0; k < a.names.size(); ++k) {
    a.omnibus.push_back(a.paired ? friedman_row(answers, k, a.names[k], a.conditions)
                                 : omnibus_row(answers, k, a.names[k], a.conditions));
    if (a.paired) a.kendalls_w.push_back(stats::kendalls_w(a.omnibus.back().result));
  }
  adjust_and_protect(a);
  if (a.paired) {
    add_within_notes(a);
    return a;
  }
  a.notes.push_back(fmt::format(
      "{} conditions ({}), between participants. Per item, the Kruskal-Wallis test (R's kruskal.test(y ~ g), "
      "tie-corrected) with the rank epsilon squared E2 = H / (n - 1); then each pair of conditions as two are "
      "compared: Mann-Whitney U (primary; rank-biserial r, positive when A answers higher) and Welch's t with "
      "the JZS Bayes factor beside it, p Holm-adjusted over the {} pairs of the item (R's pairwise.wilcox.test(y, "
      "g, p.adjust.method = \"holm\")).",
      a.conditions.size(), fmt::join(a.conditions, ", "), a.pairs.size()));
  a.notes.push_back(fmt::format(
      "Protected: a pair is labelled as differing only when its item's Kruskal-Wallis test is significant at "
      "alpha = {} and the pair's Holm-adjusted p is below alpha.",
      io::format_double(settings.alpha)));
  return a;
}

}  // namespace feint::tables
