// Table 1 as text, Markdown, LaTeX, CSV and JSON, and its notes (see feint/tables/table1.hpp);
// its numbers are computed in table1.cpp.
#include <fmt/format.h>

#include <algorithm>
#include <string>
#include <string_view>
#include <vector>

#include "feint/io/number.hpp"
#include "feint/stats/bayes_factor.hpp"
#include "feint/tables/table1.hpp"

namespace feint::tables {

namespace {

std::string capitalised(std::string s) {
  if (!s.empty() && s[0] >= 'a' && s[0] <= 'z') s[0] = static_cast<char>(s[0] - 'a' + 'A');
  return s;
}

bool two_sample(const Table1Options& o) { return o.compare.has_value(); }

std::string test_name(const Table1Options& o) {
  if (!two_sample(o)) return "one-sample t-test";
  if (o.paired) return "paired t-test";
  return o.var_equal ? "Student two-sample t-test" : "Welch two-sample t-test";
}

std::string test_call(const Table1Options& o) {
  if (!two_sample(o)) return "t.test(x, mu = R)";
  if (o.paired) return "t.test(x, y, paired = TRUE)";
  return o.var_equal ? "t.test(x, y, var.equal = TRUE)" : "t.test(x, y)";
}

std::string p_adjust_name(stats::PAdjustMethod m) {
  switch (m) {
    case stats::PAdjustMethod::bonferroni: return "Bonferroni's method";
    case stats::PAdjustMethod::holm: return "Holm's method";
    case stats::PAdjustMethod::hochberg: return "Hochberg's method";
    case stats::PAdjustMethod::hommel: return "Hommel's method";
    case stats::PAdjustMethod::BH: return "the Benjamini-Hochberg method (false discovery rate)";
    case stats::PAdjustMethod::BY: return "the Benjamini-Yekutieli method (false discovery rate)";
    case stats::PAdjustMethod::none: break;
  }
  return "no adjustment";
}

// Notes name files without their folders: a table pasted into a paper must not carry the
// author's home directory.
std::string file_name(const std::string& path) {
  if (path.empty() || path == "-") return "standard input";
  const auto slash = path.find_last_of('/');
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

// "error R = 0.5, confusion R = 0.95": the reference mean of each metric.
std::string reference_means(const Table1Options& o) {
  std::string refs;
  for (const auto& m : o.metrics) {
    refs += fmt::format("{}{} R = {}{}", refs.empty() ? "" : ", ", m.column,
                        io::format_double(m.reference), m.scale.empty() ? "" : " on the " + m.scale + " scale");
  }
  return refs;
}

// n per difference test (per group in two-sample mode): one number, or the range when it varies.
std::string n_per_test(const Table1& t, bool two) {
  std::size_t n_min = SIZE_MAX, n_max = 0;
  for (const auto& r : t.rows) {
    if (r.result.test == "tost") continue;
    const std::vector<std::size_t> ns =
        two ? std::vector<std::size_t>{r.result.n1, r.result.n2} : std::vector<std::size_t>{r.result.n1};
    for (std::size_t n : ns) {
      n_min = std::min(n_min, n);
      n_max = std::max(n_max, n);
    }
  }
  return n_min == SIZE_MAX ? "0"
         : n_min == n_max  ? std::to_string(n_min)
                           : fmt::format("{}\u2013{}", n_min, n_max);
}

std::string test_note(const Table1& t) {
  const Table1Options& o = t.options;
  const bool two = two_sample(o);
  const std::string alt(stats::to_string(o.test.alternative));
  const std::string n_text = n_per_test(t, two);
  if (!two) {
    return fmt::format(
        "{}s ({}, alternative = {}) of one value per participant and iteration against the "
        "reference mean R ({}); n = {} per test; alpha = {}.",
        capitalised(test_name(o)), test_call(o), alt, reference_means(o), n_text,
        io::format_double(o.alpha));
  }
  return fmt::format(
      "{}s ({}, alternative = {}) of one value per participant and iteration, A = {} against "
      "B = {}{}; n = {} per group; alpha = {}.",
      capitalised(test_name(o)), test_call(o), alt, o.compare->first, o.compare->second,
      o.paired ? " (pairs matched by participant)" : "", n_text, io::format_double(o.alpha));
}

// The family of an adjustment is one metric column: the iterations of a block.
std::string p_adjust_note(const Table1& t) {
  const Table1Options& o = t.options;
  const std::size_t family = t.blocks.empty() ? 0 : t.blocks.front().iterations.size();
  if (o.p_adjust == stats::PAdjustMethod::none) {
    return fmt::format(
        "p-values are not adjusted for multiple comparisons ({} tests per metric column).", family);
  }
  return fmt::format(
      "p-values are adjusted by {} (R's p.adjust, method = \"{}\") within each metric column "
      "(family of {} tests); \"p adj.\" is the adjusted p-value and the labels use it.",
      p_adjust_name(o.p_adjust), stats::to_string(o.p_adjust), family);
}

// What the labels mean; "≈" is never presented as evidence of equality unless it is one.
std::string labels_note(const Table1Options& o) {
  const bool two = two_sample(o);
  const std::string lhs = two ? "A" : "M";
  const std::string rhs = two ? "B" : "R";
  const std::string what = two ? "the mean of A is" : "the mean is";
  const std::string than = two ? "that of B" : "R";
  const std::string p_used = o.p_adjust == stats::PAdjustMethod::none ? "p" : "adjusted p";
  return fmt::format(
      "{0}>{1} / {0}<{1}: {2} significantly greater / smaller than {3} ({4} < {5}). "
      "{0}\u2248{1}: evidence for no difference, from the JZS Bayes factor BF01 \u2265 {6:g} "
      "(bf01 in the CSV and JSON tables){7}. n.s.: not significant and not shown to be equivalent "
      "(a non-significant p alone is not evidence of equality).",
      lhs, rhs, what, than, p_used, io::format_double(o.alpha), kBf01Equivalence,
      o.equivalence ? fmt::format(" or from TOST within \u00b1{} (two one-sided t-tests, {} < {}, "
                                  "column \"p TOST\")",
                                  io::format_double(*o.equivalence), p_used, io::format_double(o.alpha))
                    : std::string());
}

// Where the confusion metric's normalisation came from: the scores sidecar, when there is one.
std::string confusion_note(const Table1& t) {
  if (!t.provenance.confusion_normalisation.empty()) {
    return fmt::format("Confusion normalisation: {} (from {}).",
                       t.provenance.confusion_normalisation,
                       file_name(t.provenance.sidecar_path));
  }
  if (!t.provenance.sidecar_path.empty()) {
    return fmt::format("Confusion normalisation: unknown ({} does not record it).",
                       file_name(t.provenance.sidecar_path));
  }
  return "Confusion normalisation: unknown (no scores sidecar found beside the input).";
}

// One note listing every test that was not computable, with its metric, iteration and reason.
void add_not_computable_note(const Table1& t, std::vector<std::string>& notes) {
  std::vector<std::string> nc;
  for (const auto& r : t.rows) {
    if (r.result.computed) continue;
    const std::string where = t.blocks.size() > 1 ? " (" + r.group1 + ")" : std::string();
    nc.push_back(fmt::format("{}{}, iteration {}{}: {}", r.result.test == "tost" ? "TOST " : "",
                             r.metric, r.iteration.value_or(0), where,
                             r.result.note.empty() ? "no reason given" : r.result.note));
  }
  if (!nc.empty()) {
    std::string s;
    for (const auto& x : nc) s += (s.empty() ? "" : "; ") + x;
    notes.push_back("Not computable: " + s + ".");
  }
}

}  // namespace

std::vector<std::string> table1_note(const Table1& t) {
  const Table1Options& o = t.options;
  std::vector<std::string> notes;
  notes.push_back(test_note(t));
  notes.push_back(p_adjust_note(t));
  notes.push_back(labels_note(o));
  notes.push_back(
      "Means to 4 decimals; p-values to 4 decimals, in scientific notation below 0.001 "
      "(1.5e-04 = 1.5 \u00d7 10^-4).");
  if (std::any_of(t.rows.begin(), t.rows.end(), [](const TidyRow& r) { return r.result.bf10.has_value(); })) {
    notes.push_back(fmt::format(
        "BF10 / BF01 (bf10, bf01 in the CSV and JSON tables; in the APA strings): JZS Bayes factor of each t-test (Rouder et al. 2009), "
        "Cauchy prior on the standardised effect, scale {}; docs/bayes-factors.md.",
        stats::jzs_prior_text(o.bf_prior_r)));
  }
  const bool has_confusion = std::any_of(o.metrics.begin(), o.metrics.end(), [](const MetricSpec& m) {
    return io::to_lower(m.column) == "confusion";
  });
  if (has_confusion) notes.push_back(confusion_note(t));
  add_not_computable_note(t, notes);
  for (const auto& w : t.warnings) notes.push_back("Warning: " + w);
  notes.push_back(fmt::format("Source: {}.", file_name(t.source)));
  return notes;
}

namespace {

std::string latex_label(const std::string& label) {
  // "M>R" -> "$M > R$", "A≈B" -> "$A \approx B$"; other labels are plain text.
  for (std::string_view op : {">", "<", "\u2248"}) {
    const auto k = label.find(op);
    if (k == std::string::npos || label.size() > 6) continue;
    const std::string l = label.substr(0, k);
    const std::string r = label.substr(k + op.size());
    return fmt::format("${} {} {}$", l, op == "\u2248" ? "\\approx" : std::string(op), r);
  }
  return {};
}

constexpr std::string_view kDash = "\u2014";

}  // namespace

std::string table1_default_label(const Table1& t) {
  const Table1Options& o = t.options;
  if (o.compare) {
    return fmt::format("tab:feint-table1-{}-vs-{}", latex_label_part(o.compare->first),
                       latex_label_part(o.compare->second));
  }
  if (!o.condition.empty()) return "tab:feint-table1-" + latex_label_part(o.condition);
  return "tab:feint-table1";
}

namespace {

// "error and confusion", "a, b and c": the metric columns as the caption names them.
std::string metric_names(const Table1Options& o) {
  std::string names;
  for (std::size_t m = 0; m < o.metrics.size(); ++m) {
    names += (m == 0 ? "" : (m + 1 == o.metrics.size() ? " and " : ", ")) + o.metrics[m].column;
  }
  return names;
}

// The default caption; --caption replaces it later (apply_presentation).
std::string table1_caption(const Table1& t) {
  const Table1Options& o = t.options;
  if (!two_sample(o)) {
    std::string caption = fmt::format(
        "One-sample t-tests of {} per iteration against the reference means", metric_names(o));
    if (t.blocks.size() == 1 && !t.blocks.front().title.empty()) {
      caption += fmt::format(" (condition: {})", t.blocks.front().title);
    }
    return caption;
  }
  return fmt::format("{}s of {} per iteration: A = {} vs B = {}", capitalised(test_name(o)),
                     metric_names(o), o.compare->first, o.compare->second);
}

void add_column(TextTable& tt, std::string name, bool right) {
  tt.header.push_back(std::move(name));
  tt.right_align.push_back(right);
}

// "Iteration", then per metric a group of columns: the mean(s), p, [p adj.], [p TOST], Inference.
void add_table1_header(TextTable& tt, const Table1Options& o) {
  const bool two = two_sample(o);
  add_column(tt, "Iteration", true);
  for (const auto& m : o.metrics) {
    TextTable::Group g;
    g.title = two ? capitalised(m.column)
                  : fmt::format("{} (R = {})", capitalised(m.column), io::format_double(m.reference));
    g.first = tt.header.size();
    if (two) {
      add_column(tt, "Mean A", true);
      add_column(tt, "Mean B", true);
    } else {
      add_column(tt, "Mean (M)", true);
    }
    add_column(tt, "p", true);
    if (o.p_adjust != stats::PAdjustMethod::none) add_column(tt, "p adj.", true);
    if (o.equivalence.has_value()) add_column(tt, "p TOST", true);
    add_column(tt, "Inference", false);
    g.count = tt.header.size() - g.first;
    tt.groups.push_back(g);
  }
}

// A p-value cell and its LaTeX twin; a dash when the test was not computed.
void add_p_cell(const stats::TestResult& r, std::optional<double> p,
                std::vector<std::string>& text, std::vector<std::string>& latex) {
  if (!r.computed || !p) {
    text.emplace_back(kDash);
    latex.emplace_back("---");
  } else {
    text.push_back(format_p(p));
    latex.push_back(format_p(p, PStyle::latex));
  }
}

// The cells of one metric in one iteration's row, in the order of add_table1_header.
void add_metric_cells(const Table1& t, const Table1Cell& cell, std::vector<std::string>& cells,
                      std::vector<std::string>& latex) {
  const Table1Options& o = t.options;
  const TidyRow& d = t.rows[cell.difference_row];
  const auto mean_text = [](std::optional<double> v) {
    return v ? format_mean(v) : std::string(kDash);
  };
  cells.push_back(mean_text(d.result.mean1));
  latex.emplace_back(d.result.mean1 ? "" : "---");
  if (two_sample(o)) {
    cells.push_back(mean_text(d.result.mean2));
    latex.emplace_back(d.result.mean2 ? "" : "---");
  }
  add_p_cell(d.result, d.result.p_value, cells, latex);
  if (o.p_adjust != stats::PAdjustMethod::none) {
    add_p_cell(d.result, d.result.p_adjusted, cells, latex);
  }
  if (o.equivalence.has_value()) {
    const auto& tr = t.rows[*cell.tost_row].result;
    add_p_cell(tr, decision_p(tr), cells, latex);
  }
  cells.push_back(d.label);
  latex.push_back(latex_label(d.label));
}

// One row per iteration of each block; with several blocks each starts with a section heading.
void add_table1_rows(TextTable& tt, const Table1& t) {
  const bool sections = t.blocks.size() > 1;
  for (const auto& blk : t.blocks) {
    if (sections) {
      tt.rows.push_back({{"Condition: " + blk.title}, true});
      tt.latex_cells.emplace_back();
    }
    for (std::size_t i = 0; i < blk.iterations.size(); ++i) {
      std::vector<std::string> cells{std::to_string(blk.iterations[i])};
      std::vector<std::string> latex{""};
      for (std::size_t m = 0; m < t.options.metrics.size(); ++m) {
        add_metric_cells(t, blk.cells[i][m], cells, latex);
      }
      tt.rows.push_back({std::move(cells), false});
      tt.latex_cells.push_back(std::move(latex));
    }
  }
}

// --apa in a table for people: one line per test under the note.
void add_apa_notes(std::vector<std::string>& notes, const Table1& t) {
  notes.emplace_back("APA-style results:");
  for (const auto& r : t.rows) {
    std::string where;
    if (!r.group2.empty()) where = " (" + r.group1 + " vs " + r.group2 + ")";
    else if (t.blocks.size() > 1) where = " (" + r.group1 + ")";
    notes.push_back(fmt::format("{}, iteration {}{}: {}", r.metric, r.iteration.value_or(0),
                                where, r.apa));
  }
}

// The LaTeX cells already read 1.5 x 10^-4: the note need not explain the e-notation.
void shorten_notation_note(std::vector<std::string>& notes) {
  for (auto& n : notes) {
    if (n.rfind("Means to 4 decimals", 0) == 0) {
      n = "Means to 4 decimals; p-values to 4 decimals, in scientific notation below 0.001.";
    }
  }
}

}  // namespace

std::string render_table1(const Table1& t, OutputFormat format,
                          const TablePresentation& presentation) {
  const Table1Options& o = t.options;
  const bool omnibus = t.conditions && !t.conditions->rows.empty();
  if (format == OutputFormat::csv || format == OutputFormat::json) {
    const auto cols = table_columns(o.apa);
    // Three or more conditions: the omnibus rows follow, with their own columns after Table 1's.
    if (omnibus) return render_table1_with_conditions(t.rows, *t.conditions, cols, format);
    return format == OutputFormat::csv ? tidy_csv(t.rows, cols) : tidy_json(t.rows, cols);
  }
  TextTable tt;
  tt.caption = table1_caption(t);
  apply_presentation(tt, presentation, table1_default_label(t));
  add_table1_header(tt, o);
  add_table1_rows(tt, t);
  tt.notes = table1_note(t);
  if (o.apa) add_apa_notes(tt.notes, t);
  if (t.conditions && !t.conditions->not_computed.empty())
    tt.notes.push_back("The conditions are not compared per iteration: " + t.conditions->not_computed);
  if (format == OutputFormat::latex) shorten_notation_note(tt.notes);
  if (!omnibus) return render_table(tt, format);
  // The omnibus comparison is a second table, labelled after the first.
  return render_table(tt, format) + "\n" +
         render_table1_conditions(*t.conditions, o, format, tt.latex_label + "-conditions", tt.latex_wide);
}

}  // namespace feint::tables
