// Rendering of the Likert analysis: the item table, the response distribution, reliability, the
// note (text / Markdown / LaTeX), the tidy rows (CSV / JSON) and the descriptive summary CSV.
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <fmt/format.h>

#include "feint/io/number.hpp"
#include "feint/tables/likert.hpp"

namespace feint::tables {

namespace detail {
namespace {

constexpr std::size_t kMaxPointColumns = 11;

std::string fixed(std::optional<double> x, int decimals) { return format_mean(x, decimals); }

/// V and W are whole or half numbers: shortest exact text. t gets two decimals.
std::string statistic_text(const stats::TestResult& r) {
  if (!r.statistic) return "";
  if (r.statistic_name == "t") return fixed(r.statistic, 2);
  return io::format_double(std::round(*r.statistic * 1e6) / 1e6);
}

std::string df_text(const stats::TestResult& r) {
  if (!r.df) return "";
  if (*r.df == std::floor(*r.df)) return io::format_double(*r.df);
  return fixed(r.df, 2);
}

std::string exact_text(const stats::TestResult& r) {
  if (!r.exact) return "";
  return *r.exact ? "exact" : "approx.";
}

/// A table under construction with plain cells and, for LaTeX, the p-value cells.
struct Builder {
  TextTable table;
  std::vector<std::size_t> p_columns;  ///< columns holding p-values

  void add(std::vector<std::string> cells, const std::vector<std::optional<double>>& p_values) {
    std::vector<std::string> latex(cells.size());
    for (std::size_t j = 0; j < p_columns.size() && j < p_values.size(); ++j) {
      latex[p_columns[j]] = format_p(p_values[j], PStyle::latex);
    }
    table.rows.push_back({std::move(cells), false});
    table.latex_cells.push_back(std::move(latex));
  }
  void section(const std::string& title) {
    TextTable::Row row;
    row.section = true;
    row.cells.assign(table.header.size(), "");
    row.cells[0] = title;
    table.rows.push_back(std::move(row));
    table.latex_cells.emplace_back(table.header.size());
  }
};

const LikertSummary* find_summary(const LikertAnalysis& a, const std::string& name,
                                  const std::string& group) {
  for (const auto& s : a.summaries) {
    if (s.name == name && s.group == group) return &s;
  }
  return nullptr;
}

std::string display_name(const LikertAnalysis& a, std::size_t k) {
  if (a.is_composite[k]) return a.names[k] + " (scale)";
  if (a.reversed[k]) return a.names[k] + " (reversed)";
  return a.names[k];
}

/// Caption, header and column groups of the item table: descriptives, the rank test (primary),
/// the t-test, and Cronbach's alpha when there is a composite.
void set_item_table_header(Builder& b, const LikertAnalysis& a, bool adj, bool has_composite) {
  auto& t = b.table;
  t.latex_label = "tab:likert";
  std::vector<std::string> head{"Item"};
  std::size_t desc_first = 1;
  if (a.two_sample) {
    const auto& ga = a.settings.compare->first;
    const auto& gb = a.settings.compare->second;
    t.caption = fmt::format("Likert items: {} (A) against {} (B){}, scale {}-{}", ga, gb,
                            a.paired ? " within participants" : "", a.scale_min, a.scale_max);
    for (const char* h : {"n A", "n B", "Mdn A", "Mdn B", "IQR A", "IQR B", "M A", "M B"}) {
      head.emplace_back(h);
    }
  } else {
    t.caption = fmt::format("Likert items against R = {}, scale {}-{}",
                            io::format_double(a.reference), a.scale_min, a.scale_max);
    for (const char* h : {"n", "miss", "Mdn", "IQR", "M", "SD"}) head.emplace_back(h);
  }
  const std::size_t desc_count = head.size() - desc_first;
  const std::size_t rank_first = head.size();
  head.emplace_back(a.two_sample && !a.paired ? "W" : "V");
  b.p_columns.push_back(head.size());
  head.emplace_back("p");
  if (adj) {
    b.p_columns.push_back(head.size());
    head.emplace_back("p adj");
  }
  for (const char* h : {"r", "dist", "inference"}) head.emplace_back(h);
  const std::size_t rank_count = head.size() - rank_first;
  const std::size_t t_first = head.size();
  for (const char* h : {"t", "df"}) head.emplace_back(h);
  b.p_columns.push_back(head.size());
  head.emplace_back("p");
  if (adj) {
    b.p_columns.push_back(head.size());
    head.emplace_back("p adj");
  }
  for (const char* h : {"d", "inference"}) head.emplace_back(h);
  const std::size_t t_count = head.size() - t_first;
  if (has_composite) head.emplace_back("alpha");
  t.header = head;
  t.right_align.assign(head.size(), true);
  t.right_align[0] = false;

  t.groups.push_back({"Descriptives", desc_first, desc_count});
  t.groups.push_back({a.paired       ? "Wilcoxon signed-rank, paired (primary)"
                      : a.two_sample ? "Mann-Whitney U (primary)"
                                     : "Wilcoxon signed-rank (primary)",
                      rank_first, rank_count});
  t.groups.push_back({a.paired                ? "Paired t-test"
                       : a.two_sample         ? "Welch t-test"
                       : a.settings.paper ? "One-sample t-test (the paper's analysis)"
                                          : "One-sample t-test",
                      t_first, t_count});
}

/// Descriptive cells of questionnaire item (or composite) k: A and B side by side in two-sample
/// mode, the one condition otherwise.
void add_descriptive_cells(std::vector<std::string>& cells, const LikertAnalysis& a,
                           std::size_t k, const TidyRow& rank) {
  if (a.two_sample) {
    const auto* sa = find_summary(a, a.names[k], rank.group1);
    const auto* sb = find_summary(a, a.names[k], rank.group2);
    cells.push_back(std::to_string(sa->n));
    cells.push_back(std::to_string(sb->n));
    cells.push_back(fixed(sa->median, 2));
    cells.push_back(fixed(sb->median, 2));
    cells.push_back(fixed(sa->iqr, 2));
    cells.push_back(fixed(sb->iqr, 2));
    cells.push_back(fixed(sa->mean, 4));
    cells.push_back(fixed(sb->mean, 4));
  } else {
    const auto* s = find_summary(a, a.names[k], rank.group1);
    cells.push_back(std::to_string(s->n));
    cells.push_back(std::to_string(s->missing));
    cells.push_back(fixed(s->median, 2));
    cells.push_back(fixed(s->iqr, 2));
    cells.push_back(fixed(s->mean, 4));
    cells.push_back(fixed(s->sd, 4));
  }
}

/// Cells of the rank test, then of the t-test; `ps` collects their p-values for the LaTeX cells.
void add_test_cells(std::vector<std::string>& cells, std::vector<std::optional<double>>& ps,
                    const TidyRow& rank, const TidyRow& tt, bool adj) {
  cells.push_back(statistic_text(rank.result));
  cells.push_back(format_p(rank.result.p_value));
  ps.push_back(rank.result.p_value);
  if (adj) {
    cells.push_back(format_p(rank.result.p_adjusted));
    ps.push_back(rank.result.p_adjusted);
  }
  cells.push_back(fixed(rank.result.rank_biserial, 2));
  cells.push_back(exact_text(rank.result));
  cells.push_back(rank.label);
  cells.push_back(statistic_text(tt.result));
  cells.push_back(df_text(tt.result));
  cells.push_back(format_p(tt.result.p_value));
  ps.push_back(tt.result.p_value);
  if (adj) {
    cells.push_back(format_p(tt.result.p_adjusted));
    ps.push_back(tt.result.p_adjusted);
  }
  cells.push_back(fixed(tt.result.cohen_d, 2));
  cells.push_back(tt.label);
}

TextTable main_table(const LikertAnalysis& a) {
  const bool adj = a.settings.p_adjust != stats::PAdjustMethod::none;
  const bool has_composite =
      std::find(a.is_composite.begin(), a.is_composite.end(), true) != a.is_composite.end();
  Builder b;
  set_item_table_header(b, a, adj, has_composite);

  // a.rows holds, per block (condition, or A against B), per name: the rank test, then the t-test.
  const std::size_t per_block = a.names.size() * 2;
  for (std::size_t blk = 0; blk * per_block < a.rows.size(); ++blk) {
    if (!a.two_sample && a.groups.size() > 1) b.section("Condition: " + a.groups[blk]);
    for (std::size_t k = 0; k < a.names.size(); ++k) {
      const TidyRow& rank = a.rows[blk * per_block + 2 * k];
      const TidyRow& tt = a.rows[blk * per_block + 2 * k + 1];
      std::vector<std::string> cells{display_name(a, k)};
      std::vector<std::optional<double>> ps;
      add_descriptive_cells(cells, a, k, rank);
      add_test_cells(cells, ps, rank, tt, adj);
      if (has_composite) cells.push_back(fixed(rank.cronbach_alpha, 2));
      b.add(std::move(cells), ps);
    }
  }
  return b.table;
}

TextTable distribution_table(const LikertAnalysis& a) {
  TextTable t;
  t.caption = fmt::format("Responses per scale point: count (% of n); neutral point {}",
                          io::format_double(a.neutral));
  t.latex_label = "tab:likert-responses";
  t.header.emplace_back("Item");
  // Per-point columns for the usual short scales; long ones (e.g. 0-100) only get < = >.
  const auto points = static_cast<std::size_t>(a.scale_max - a.scale_min + 1);
  const bool per_point = points <= kMaxPointColumns;
  if (!per_point)
    t.caption = fmt::format("Responses: % of n below / at / above the neutral point {}",
                            io::format_double(a.neutral));
  for (int v = a.scale_min; per_point && v <= a.scale_max; ++v) {
    t.header.push_back(std::to_string(v));
  }
  const std::string nt = io::format_double(a.neutral);
  t.header.push_back("< " + nt);
  t.header.push_back("= " + nt);
  t.header.push_back("> " + nt);
  t.right_align.assign(t.header.size(), true);
  t.right_align[0] = false;
  const bool sections = a.two_sample || a.groups.size() > 1;
  std::string current = "\x01";
  for (const auto& s : a.summaries) {
    if (sections && s.group != current) {
      TextTable::Row row;
      row.section = true;
      row.cells.assign(t.header.size(), "");
      row.cells[0] = "Condition: " + s.group;
      t.rows.push_back(std::move(row));
    }
    current = s.group;
    std::string name = s.name;
    for (std::size_t k = 0; k < a.names.size(); ++k) {
      if (a.names[k] == s.name) name = display_name(a, k);
    }
    std::vector<std::string> cells{name};
    const auto pct = [](std::optional<double> p) {
      return p ? fmt::format("{:.0f}%", *p) : std::string();
    };
    for (std::size_t v = 0; per_point && v < points; ++v) {
      if (s.composite || s.n == 0) {
        cells.emplace_back("");
      } else {
        cells.push_back(
            fmt::format("{} ({:.0f}%)", s.counts[v],
                        100.0 * static_cast<double>(s.counts[v]) / static_cast<double>(s.n)));
      }
    }
    cells.push_back(pct(s.pct_below));
    cells.push_back(pct(s.pct_at));
    cells.push_back(pct(s.pct_above));
    t.rows.push_back({std::move(cells), false});
  }
  return t;
}

TextTable reliability_table(const LikertAnalysis& a) {
  TextTable t;
  t.caption = a.settings.alpha_missing == stats::AlphaMissing::pairwise
                  ? "Reliability of the composite scales (Cronbach's raw alpha, pairwise "
                    "covariances)"
                  : "Reliability of the composite scales (Cronbach's raw alpha, complete cases)";
  t.latex_label = "tab:likert-reliability";
  t.header = {"Scale", "Respondents", "n", "alpha", "Item dropped", "alpha if dropped"};
  t.right_align = {false, false, true, true, false, true};
  for (const auto& rel : a.reliability) {
    const std::string who = rel.group.empty() ? "all" : rel.group;
    for (std::size_t j = 0; j < rel.items.size(); ++j) {
      std::vector<std::string> cells;
      if (j == 0) {
        cells = {rel.name, who, std::to_string(rel.n), fixed(rel.alpha, 2)};
      } else {
        cells = {"", "", "", ""};
      }
      cells.push_back(rel.items[j]);
      cells.push_back(j < rel.if_dropped.size() ? fixed(rel.if_dropped[j], 2) : "");
      t.rows.push_back({std::move(cells), false});
    }
  }
  return t;
}

/// One line per item and group: the primary test's APA string, then the t-test's.
std::vector<std::string> apa_lines(const LikertAnalysis& a) {
  std::vector<std::string> out;
  for (std::size_t i = 0; i + 1 < a.rows.size(); i += 2) {
    const auto& rank = a.rows[i];
    std::string who = rank.metric;
    if (!a.two_sample && !rank.group1.empty() && a.groups.size() > 1) {
      who += " (" + rank.group1 + ")";
    }
    out.push_back(fmt::format("APA, {}: {}; {}", who, rank.apa, a.rows[i + 1].apa));
  }
  return out;
}

}  // namespace
}  // namespace detail

std::string render_likert(const LikertAnalysis& a, OutputFormat format,
                          const TablePresentation& presentation) {
  if (format == OutputFormat::csv || format == OutputFormat::json) {
    const auto columns = likert_columns(a.settings.apa);
    return format == OutputFormat::csv ? tidy_csv(a.rows, columns) : tidy_json(a.rows, columns);
  }
  std::vector<TextTable> tables;
  tables.push_back(detail::main_table(a));
  tables.push_back(detail::distribution_table(a));
  if (!a.reliability.empty()) tables.push_back(detail::reliability_table(a));
  std::string label = presentation.label;
  if (label.empty()) {
    label = "tab:feint-likert";
    if (a.settings.compare) {
      label += "-" + latex_label_part(a.settings.compare->first) + "-vs-" +
               latex_label_part(a.settings.compare->second);
    } else if (!a.settings.condition.empty()) {
      label += "-" + latex_label_part(a.settings.condition);
    }
  }
  apply_presentation(tables[0], presentation, label);
  for (std::size_t i = 1; i < tables.size(); ++i) {
    tables[i].latex_label = label + (i == 1 ? "-responses" : "-reliability");
    tables[i].latex_wide = presentation.wide;
  }
  auto& last = tables.back();
  last.notes = a.notes;
  if (a.settings.apa) {
    for (auto& line : detail::apa_lines(a)) last.notes.push_back(std::move(line));
  }
  std::string out;
  for (std::size_t i = 0; i < tables.size(); ++i) {
    if (i > 0) out += "\n";
    out += render_table(tables[i], format);
  }
  return out;
}

std::string likert_summary_csv(const LikertAnalysis& a) {
  std::vector<std::string> names{"group", "name",      "kind",   "n",        "missing",
                                 "mean",  "sd",        "median", "q1",       "q3",
                                 "iqr",   "pct_below", "pct_at", "pct_above"};
  for (int v = a.scale_min; v <= a.scale_max; ++v) names.push_back(fmt::format("n_{}", v));
  for (int v = a.scale_min; v <= a.scale_max; ++v) names.push_back(fmt::format("pct_{}", v));
  std::vector<std::string_view> columns(names.begin(), names.end());
  std::vector<Record> records;
  for (const auto& s : a.summaries) {
    Record r{Cell::str(s.group),
             Cell::str(s.name),
             Cell::str(s.composite ? "composite" : "item"),
             Cell::integer(static_cast<long long>(s.n)),
             Cell::integer(static_cast<long long>(s.missing)),
             Cell::num(s.mean),
             Cell::num(s.sd),
             Cell::num(s.median),
             Cell::num(s.q1),
             Cell::num(s.q3),
             Cell::num(s.iqr),
             Cell::num(s.pct_below),
             Cell::num(s.pct_at),
             Cell::num(s.pct_above)};
    const auto points = static_cast<std::size_t>(a.scale_max - a.scale_min + 1);
    for (std::size_t v = 0; v < points; ++v) {
      r.push_back(s.composite ? Cell::none() : Cell::integer(static_cast<long long>(s.counts[v])));
    }
    for (std::size_t v = 0; v < points; ++v) {
      if (s.composite || s.n == 0) {
        r.push_back(Cell::none());
      } else {
        r.push_back(Cell::num(100.0 * static_cast<double>(s.counts[v]) / static_cast<double>(s.n)));
      }
    }
    records.push_back(std::move(r));
  }
  return write_csv(columns, records);
}

}  // namespace feint::tables
