// A questionnaire across three or more conditions: Kruskal-Wallis per item, then every pair,
// Holm-adjusted over the pairs and protected by the omnibus test. See
// feint/tables/likert_conditions.hpp.
#include "feint/tables/likert_conditions.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "feint/error.hpp"
#include "feint/io/number.hpp"
#include "feint/stats/anova.hpp"
#include "feint/stats/p_adjust.hpp"
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
      a.pairs.push_back(analyze_likert(q, s));  // throws InvalidData for a shared participant
    }
  a.names = a.pairs.front().names;
  const auto members = composite_members(q, settings);
  const detail::Answers answers{q, members};
  for (std::size_t k = 0; k < a.names.size(); ++k) a.omnibus.push_back(omnibus_row(answers, k, a.names[k], a.conditions));
  adjust_and_protect(a);
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
