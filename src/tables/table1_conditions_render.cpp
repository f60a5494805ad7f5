// Table 1's omnibus comparison of three or more conditions as text, Markdown and LaTeX (one row per
// iteration, a section per metric) and as tidy CSV / JSON records; its numbers are computed in
// table1_conditions.cpp.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "feint/io/number.hpp"
#include "feint/tables/table1.hpp"
#include "feint/tables/table1_conditions.hpp"

namespace feint::tables {

namespace {

constexpr std::string_view kDash = "\u2014";

std::string capitalised(std::string s) {
  if (!s.empty() && s[0] >= 'a' && s[0] <= 'z') s[0] = static_cast<char>(s[0] - 'a' + 'A');
  return s;
}

std::string fixed(std::optional<double> x, int decimals) { return x ? format_mean(x, decimals) : std::string(); }

// "2, 13.41": whole df as integers, fractional ones (Welch, Greenhouse–Geisser) to 2 decimals.
std::string df_text(const stats::TestResult& r) {
  auto one = [](std::optional<double> d) {
    if (!d) return std::string("?");
    return std::fabs(*d - std::round(*d)) < 1e-9 ? fmt::format("{:.0f}", *d) : fmt::format("{:.2f}", *d);
  };
  return one(r.df) + ", " + one(r.df2);
}

struct Columns {
  bool adjusted = false;
  std::vector<std::string> header;
  std::vector<TextTable::Group> groups;
};

Columns columns(const Table1Conditions& c, const Table1Options& o) {
  Columns out;
  out.adjusted = o.p_adjust != stats::PAdjustMethod::none;
  out.header = {"Iteration"};
  auto group = [&](std::string title, std::vector<std::string> names) {
    out.groups.push_back({std::move(title), out.header.size(), names.size()});
    for (auto& n : names) out.header.push_back(std::move(n));
  };
  std::vector<std::string> primary = {"F", "df"};
  if (c.within) primary.emplace_back("\u03b5 GG");
  for (const char* n : {"p", "p maxF"}) primary.emplace_back(n);
  if (out.adjusted) primary.emplace_back("p adj.");
  if (c.within) {
    group("Repeated-measures F (primary)", primary);
    group("Friedman", {"\u03c7\u00b2", "p", "W"});
  } else {
    group("Welch's F (primary)", primary);
    group("One-way ANOVA", {"F", "p", "\u03b7\u00b2", "\u03c9\u00b2"});
    group("Kruskal\u2013Wallis", {"H", "p", "\u03b5\u00b2R"});
  }
  out.header.emplace_back("Inference");
  return out;
}

// A p-value cell and its LaTeX twin; a dash when there is none.
void add_p(std::optional<double> p, std::vector<std::string>& text, std::vector<std::string>& latex) {
  if (!p) {
    text.emplace_back(kDash);
    latex.emplace_back("---");
  } else {
    text.push_back(format_p(p));
    latex.push_back(format_p(p, PStyle::latex));
  }
}

void add_plain(std::string s, std::vector<std::string>& text, std::vector<std::string>& latex) {
  text.push_back(s.empty() ? std::string(kDash) : std::move(s));
  latex.emplace_back(text.back() == kDash ? "---" : "");
}

// The cells of one iteration of one metric, in the order of columns().
void add_cells(const Table1Conditions& c, const Columns& cols, std::size_t i, std::size_t m, TextTable& tt) {
  const std::size_t per = c.rows_per_cell();
  const OmnibusRow* row = &c.primary(i, m);
  std::vector<std::string> text{std::to_string(c.iterations[i])}, latex{""};
  const auto& r = row->row.result;
  add_plain(fixed(r.statistic, 2), text, latex);
  add_plain(r.computed ? df_text(r) : "", text, latex);
  if (c.within) add_plain(fixed(row->sphericity_epsilon, 3), text, latex);
  add_p(r.computed ? r.p_value : std::nullopt, text, latex);
  add_p(row->p_maxf, text, latex);
  if (cols.adjusted) add_p(r.computed ? r.p_adjusted : std::nullopt, text, latex);
  for (std::size_t k = 1; k < per; ++k) {
    const OmnibusRow& o = row[k];
    const auto& s = o.row.result;
    add_plain(fixed(s.statistic, 2), text, latex);
    add_p(s.computed ? s.p_value : std::nullopt, text, latex);
    if (s.test == "anova") {
      add_plain(fixed(s.r_squared, 3), text, latex);
      add_plain(fixed(o.omega_squared, 3), text, latex);
    } else {
      add_plain(fixed(s.test == "friedman" ? o.kendalls_w : s.rank_epsilon_squared, 3), text, latex);
    }
  }
  add_plain(row->row.label, text, latex);
  tt.rows.push_back({std::move(text), false});
  tt.latex_cells.push_back(std::move(latex));
}

std::string conditions_text(const Table1Conditions& c) {
  std::string s;
  for (std::size_t k = 0; k < c.conditions.size(); ++k)
    s += (k == 0 ? "" : (k + 1 == c.conditions.size() ? " and " : ", ")) + c.conditions[k];
  return s;
}

std::string tests_note(const Table1Conditions& c, const Table1Options& o) {
  const std::string head = fmt::format("Whether the {} conditions ({}) differ, per iteration; {}. ", c.conditions.size(),
                                       conditions_text(c), c.design_note);
  const std::string level = io::format_double(o.test.conf_level * 100);
  if (c.within)
    return head + fmt::format(
                      "Primary: the one-way repeated-measures F of the participants with every condition at "
                      "that iteration (afex::aov_ez(id, dv, data, within = \"condition\")), df Greenhouse-Geisser "
                      "corrected (\u03b5 GG; it does not assume sphericity, as Welch's t does not assume equal "
                      "variances); ges in the CSV and JSON tables. Beside it Friedman's test (friedman.test(y ~ "
                      "condition | participant)) with Kendall's W.");
  return head + fmt::format(
                    "Primary: Welch's F (oneway.test(y ~ g); it does not assume equal variances, as Welch's t "
                    "for two conditions). Beside it the one-way ANOVA F (oneway.test(y ~ g, var.equal = TRUE)) "
                    "with \u03b7\u00b2 and \u03c9\u00b2 (effectsize's eta_squared and omega_squared; their "
                    "one-sided {} % intervals in the CSV and JSON tables), and the Kruskal-Wallis test "
                    "(kruskal.test(y ~ g)) with the rank epsilon squared \u03b5\u00b2R = H / (n - 1).",
                    level);
}

// "10,000": the relabellings counted.
std::string thousands(std::uint64_t n) {
  std::string s = std::to_string(n);
  for (int i = static_cast<int>(s.size()) - 3; i > 0; i -= 3) s.insert(static_cast<std::size_t>(i), ",");
  return s;
}

// How each metric's relabellings were counted: "all 210 ..." or "10,000 ... drawn at random".
std::string relabellings(const Table1Conditions& c, const Table1Options& o) {
  const std::string unit = c.within ? "orders of each participant's conditions, the same order at every iteration"
                                    : "assignments of the participants to the conditions, each participant with "
                                      "all of their iterations and the conditions' sizes kept";
  auto one = [&](const OmnibusFamily& f) {
    if (!f.note.empty()) return "not computed: " + f.note;
    return f.exact ? fmt::format("all {} {}", thousands(f.labellings), unit)
                   : fmt::format("{} {}, drawn at random (seed {})", thousands(f.labellings), unit, o.omnibus_seed);
  };
  const bool same = std::all_of(c.families.begin(), c.families.end(), [&](const OmnibusFamily& f) {
    return f.note.empty() && f.exact == c.families.front().exact && f.labellings == c.families.front().labellings;
  });
  if (same && !c.families.empty()) return one(c.families.front()) + (c.families.size() > 1 ? ", for each metric" : "");
  std::string s;
  for (const auto& f : c.families) s += fmt::format("{}{}: {}", s.empty() ? "" : "; ", f.metric, one(f));
  return s;
}

std::string family_note(const Table1Conditions& c, const Table1Options& o) {
  std::string s = fmt::format(
      "p maxF: the primary p-value adjusted over the {} iterations of a metric by the Westfall-Young step-down "
      "maxF on the primary F, relabelling under the null of no difference ({}); it holds the family-wise error "
      "rate whatever the dependence between the iterations.",
      c.iterations.size(), relabellings(c, o));
  if (o.p_adjust != stats::PAdjustMethod::none)
    s += fmt::format(" p adj.: R's p.adjust(method = \"{}\") over the iterations, each kind of test in its own "
                     "family.",
                     stats::to_string(o.p_adjust));
  return s;
}

std::vector<std::string> notes(const Table1Conditions& c, const Table1Options& o) {
  std::vector<std::string> out{tests_note(c, o), family_note(c, o)};
  out.push_back(fmt::format(
      "differ: the primary test's {} < {}; n.s.: not significant, which is not evidence that the conditions are "
      "alike. F and chi-squared tests are one-sided by construction: the alternative does not apply.",
      o.p_adjust == stats::PAdjustMethod::none ? "p" : "adjusted p", io::format_double(o.alpha)));
  std::string nc;
  for (const auto& row : c.rows)
    if (!row.row.result.computed)
      nc += fmt::format("{}{} of {}, iteration {}: {}", nc.empty() ? "" : "; ", row.row.result.method, row.row.metric,
                        row.row.iteration.value_or(0), row.row.result.note);
  if (!nc.empty()) out.push_back("Not computable: " + nc + ".");
  for (const auto& w : c.warnings) out.push_back("Warning: " + w);
  if (o.apa) {
    out.emplace_back("APA-style results:");
    for (const auto& row : c.rows)
      out.push_back(fmt::format("{}, iteration {} ({}): {}", row.row.metric, row.row.iteration.value_or(0),
                                row.row.result.method, row.row.apa));
  }
  return out;
}

// latex_escape knows eta and chi but not omega and epsilon: set them in math here.
std::string latex_greek(std::string s) {
  for (const auto& [from, to] : {std::pair<std::string_view, std::string_view>{"\u03c9", "\\ensuremath{\\omega}"},
                                 {"\u03b5", "\\ensuremath{\\varepsilon}"}}) {
    for (auto at = s.find(from); at != std::string::npos; at = s.find(from, at + to.size()))
      s.replace(at, from.size(), to);
  }
  return s;
}

}  // namespace

std::string render_table1_conditions(const Table1Conditions& c, const Table1Options& o, OutputFormat format,
                                     const std::string& latex_label, bool latex_wide) {
  if (format == OutputFormat::csv || format == OutputFormat::json)
    throw std::invalid_argument("render_table1_conditions: csv and json are Table 1's tidy rows");
  const Columns cols = columns(c, o);
  TextTable tt;
  tt.caption = fmt::format("The {} conditions compared per iteration ({} participants): {}", c.conditions.size(),
                           c.within ? "within" : "between",
                           c.within ? "repeated-measures F (primary) and Friedman"
                                    : "Welch's F (primary), one-way ANOVA and Kruskal-Wallis");
  tt.header = cols.header;
  tt.groups = cols.groups;
  tt.right_align.assign(tt.header.size(), true);
  tt.right_align.back() = false;
  tt.latex_label = latex_label;
  tt.latex_wide = latex_wide;
  for (std::size_t m = 0; m < c.metrics.size(); ++m) {
    tt.rows.push_back({{capitalised(c.metrics[m])}, true});
    tt.latex_cells.emplace_back();
    for (std::size_t i = 0; i < c.iterations.size(); ++i) add_cells(c, cols, i, m, tt);
  }
  tt.notes = notes(c, o);
  const std::string out = render_table(tt, format);
  return format == OutputFormat::latex ? latex_greek(out) : out;
}

std::vector<std::string_view> table1_conditions_columns() {
  return {"df2", "p_maxf", "eta_squared", "eta_squared_low", "eta_squared_high", "omega_squared", "omega_squared_low",
          "omega_squared_high", "ges", "ges_low", "ges_high", "sphericity_epsilon", "rank_epsilon_squared",
          "kendalls_w"};
}

std::string render_table1_with_conditions(std::span<const TidyRow> rows, const Table1Conditions& c,
                                          std::span<const std::string_view> columns, OutputFormat format) {
  const auto extra = table1_conditions_columns();
  std::vector<std::string_view> all(columns.begin(), columns.end());
  all.insert(all.end(), extra.begin(), extra.end());
  std::vector<Record> records = tidy_records(rows, columns);
  for (auto& r : records) r.resize(all.size());
  for (const auto& o : c.rows) {
    Record r = tidy_records(std::span<const TidyRow>(&o.row, 1), columns).front();
    const auto& t = o.row.result;
    for (const auto v : {t.df2, o.p_maxf, t.r_squared, t.eta_squared_low, t.eta_squared_high, o.omega_squared,
                         o.omega_squared_low, o.omega_squared_high, o.ges, o.ges_low, o.ges_high, o.sphericity_epsilon,
                         t.rank_epsilon_squared, o.kendalls_w})
      r.push_back(Cell::num(v));
    records.push_back(std::move(r));
  }
  return format == OutputFormat::csv ? write_csv(all, records) : write_json(all, records);
}

}  // namespace feint::tables
