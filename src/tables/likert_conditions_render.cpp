// Rendering of a questionnaire across three or more conditions: the omnibus table (Kruskal-Wallis
// per item, the conditions' means beside it), the pairs table, the note; CSV / JSON as tidy rows.
#include <cmath>

#include <fmt/format.h>

#include "feint/io/number.hpp"
#include "feint/tables/likert_conditions.hpp"

namespace feint::tables {

namespace {

std::string fixed(std::optional<double> x, int decimals) { return format_mean(x, decimals); }

const LikertSummary* summary_of(const LikertConditions& a, const std::string& name, const std::string& group) {
  for (const auto& pair : a.pairs)
    for (const auto& s : pair.summaries)
      if (s.name == name && s.group == group) return &s;
  return nullptr;
}

std::string omnibus_label(const TidyRow& row, double alpha) {
  if (!row.result.computed) return std::string(kNotComputable);
  return row.result.p_value && *row.result.p_value < alpha ? "differ" : std::string(kNotSignificant);
}

TextTable omnibus_table(const LikertConditions& a) {
  TextTable t;
  t.caption = a.paired ? fmt::format("Questionnaire across the {} conditions within participants: Friedman test per item",
                                     a.conditions.size())
                       : fmt::format("Questionnaire across the {} conditions: Kruskal-Wallis test per item",
                                     a.conditions.size());
  t.header = {"Item"};
  for (const auto& c : a.conditions) t.header.push_back("M " + c);
  for (const char* h : {"n", a.paired ? "X2" : "H", "df", "p", a.paired ? "W" : "E2", "inference"})
    t.header.emplace_back(h);
  t.right_align.assign(t.header.size(), true);
  t.right_align[0] = false;
  for (std::size_t k = 0; k < a.omnibus.size(); ++k) {
    const TidyRow& row = a.omnibus[k];
    std::vector<std::string> cells{row.metric};
    for (const auto& c : a.conditions) {
      const LikertSummary* s = summary_of(a, row.metric, c);
      cells.push_back(s ? fixed(s->mean, 2) : "");
    }
    cells.push_back(std::to_string(row.result.n1));
    cells.push_back(fixed(row.result.statistic, 2));
    cells.push_back(row.result.df ? io::format_double(*row.result.df) : "");
    cells.push_back(format_p(row.result.p_value));
    cells.push_back(fixed(a.paired ? a.kendalls_w[k] : row.result.rank_epsilon_squared, 3));
    cells.push_back(omnibus_label(row, a.settings.alpha));
    t.rows.push_back({std::move(cells), false});
  }
  return t;
}

TextTable pairs_table(const LikertConditions& a) {
  TextTable t;
  t.caption = "Questionnaire: each pair of conditions (Holm over the pairs of an item, protected by its omnibus test)";
  t.header = {"Item", "A", "B", "M A", "M B", a.paired ? "V" : "W", "p", "p Holm", "r", "t", "df", "p Holm", "BF10",
              "inference"};
  t.right_align.assign(t.header.size(), true);
  for (std::size_t j = 0; j < 3; ++j) t.right_align[j] = false;
  if (a.paired)
    t.groups = {{"Wilcoxon signed-rank, paired (primary)", 5, 4}, {"Paired t-test", 9, 4}};
  else
    t.groups = {{"Mann-Whitney U (primary)", 5, 4}, {"Welch t-test", 9, 4}};
  for (std::size_t k = 0; k < a.names.size(); ++k) {
    for (const auto& pair : a.pairs) {
      const TidyRow& rank = pair.rows[2 * k];
      const TidyRow& tt = pair.rows[2 * k + 1];
      const auto& r = rank.result;
      t.rows.push_back({{a.names[k], rank.group1, rank.group2, fixed(tt.result.mean1, 2), fixed(tt.result.mean2, 2),
                         r.statistic ? io::format_double(*r.statistic) : "", format_p(r.p_value),
                         format_p(r.p_adjusted), fixed(r.rank_biserial, 2), fixed(tt.result.statistic, 2),
                         fixed(tt.result.df, 2), format_p(tt.result.p_adjusted),
                         tt.result.bf10 ? fmt::format("{:.3g}", *tt.result.bf10) : "", rank.label},
                        false});
    }
  }
  return t;
}

}  // namespace

std::string render_likert_conditions(const LikertConditions& a, OutputFormat format) {
  if (format == OutputFormat::csv || format == OutputFormat::json) {
    std::vector<TidyRow> rows = a.omnibus;
    for (const auto& pair : a.pairs) rows.insert(rows.end(), pair.rows.begin(), pair.rows.end());
    const auto columns = likert_columns(a.settings.apa);
    return format == OutputFormat::csv ? tidy_csv(rows, columns) : tidy_json(rows, columns);
  }
  TextTable omnibus = omnibus_table(a);
  omnibus.latex_label = "tab:feint-likert-conditions";
  TextTable pairs = pairs_table(a);
  pairs.latex_label = "tab:feint-likert-conditions-pairs";
  pairs.notes = a.notes;
  return render_table(omnibus, format) + "\n" + render_table(pairs, format);
}

}  // namespace feint::tables
