#include "feint/report/table1.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include <fmt/format.h>

#include "feint/error.hpp"
#include "feint/io/number.hpp"
#include "feint/stats/bayes_factor.hpp"
#include "feint/stats/effect_size.hpp"
#include "feint/stats/ttest.hpp"

namespace feint::report {

std::vector<MetricSpec> default_metrics() { return {{"error", 0.5}, {"confusion", 0.95}}; }

MetricSpec parse_metric_spec(std::string_view text) {
  const auto eq = text.find('=');
  const std::string name(io::trim(text.substr(0, eq)));
  if (name.empty()) {
    throw UsageError(fmt::format("--metric '{}': expected NAME=REFERENCE, e.g. error=0.5", text));
  }
  if (eq == std::string_view::npos) {
    for (const auto& d : default_metrics()) {
      if (io::to_lower(name) == d.column) return {name, d.reference};
    }
    throw UsageError(fmt::format(
        "--metric '{}': no default reference mean for '{}'; give one as {}=REFERENCE", text, name,
        name));
  }
  const auto ref = io::parse_double(text.substr(eq + 1));
  if (!ref) {
    throw UsageError(fmt::format("--metric '{}': reference '{}' is not a number", text,
                                 text.substr(eq + 1)));
  }
  return {name, *ref};
}

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

// BF01 >= 3: moderate evidence for no difference (docs/findings.md).
constexpr double kBf01Equivalence = 3.0;

std::string label_for(const Table1Options& o, const stats::TestResult& diff,
                      const stats::TestResult* tost) {
  std::string label = two_sample(o) ? two_sample_label(diff, o.alpha, tost)
                                    : one_sample_label(diff, o.alpha, tost);
  if (!o.equivalence_by_evidence || label.find(kApprox) == std::string::npos) return label;
  // "≈" from a non-significant p alone is not kept: it needs BF01 >= 3 or TOST.
  const bool by_bf = diff.log_bf10 && -*diff.log_bf10 >= std::log(kBf01Equivalence);
  const auto tp = tost ? decision_p(*tost) : std::nullopt;
  const bool by_tost = tost && tost->computed && tp && *tp < o.alpha;
  return by_bf || by_tost ? label : std::string(kInconclusive);
}

// p.adjust within a family of row indices (one metric column of one block).
void adjust_family(std::vector<TidyRow>& rows, const std::vector<std::size_t>& family,
                   stats::PAdjustMethod method) {
  if (method == stats::PAdjustMethod::none || family.empty()) return;
  std::vector<std::optional<double>> p;
  p.reserve(family.size());
  for (auto i : family) {
    p.push_back(rows[i].result.computed ? rows[i].result.p_value : std::nullopt);
  }
  const auto adjusted = stats::p_adjust(p, method);
  for (std::size_t k = 0; k < family.size(); ++k) rows[family[k]].result.p_adjusted = adjusted[k];
}

// A paired test needs participants who were measured in both conditions. With none (a
// between-subjects design) every cell would be "not computable": say what is wrong instead.
void require_pairs(const io::ScoresTable& scores, const std::string& a, const std::string& b) {
  std::set<std::string> in_a;
  for (const auto& r : scores.records) {
    if (r.condition == a) in_a.insert(r.participant);
  }
  for (const auto& r : scores.records) {
    if (r.condition == b && in_a.count(r.participant) != 0) return;
  }
  throw UsageError(fmt::format(
      "{}: --paired: no participant occurs in both conditions {} and {} (a between-subjects "
      "design); the paired t-test needs the same participants in both. Leave out --paired for "
      "Welch's t-test of independent groups",
      scores.path, a, b));
}

// Notes name files without their folders: a table pasted into a paper must not carry the
// author's home directory.
std::string file_name(const std::string& path) {
  if (path.empty() || path == "-") return "standard input";
  const auto slash = path.find_last_of('/');
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

}  // namespace

Table1 build_table1(const io::ScoresTable& scores, const Table1Options& options) {
  const Table1Options& o = options;
  if (!(o.alpha > 0.0 && o.alpha < 1.0)) {
    throw UsageError(fmt::format("--alpha {}: expected a number in (0, 1)", o.alpha));
  }
  if (!(o.test.conf_level > 0.0 && o.test.conf_level < 1.0)) {
    throw UsageError(fmt::format("--conf-level {}: expected a number in (0, 1)", o.test.conf_level));
  }
  if (o.equivalence && !(std::isfinite(*o.equivalence) && *o.equivalence > 0.0)) {
    throw UsageError(fmt::format("--equivalence {}: expected a margin > 0", *o.equivalence));
  }
  if (o.metrics.empty()) throw UsageError("no metric to tabulate (--metric NAME=REFERENCE)");
  if (!two_sample(o) && (o.paired || o.var_equal)) {
    throw UsageError("--paired and --var-equal need --compare A,B");
  }
  if (o.paired && o.var_equal) throw UsageError("--paired and --var-equal exclude each other");

  Table1 t;
  t.options = o;
  t.source = scores.path;
  t.provenance = io::read_scores_provenance(scores.path);

  std::vector<int> metric_index;
  for (const auto& m : o.metrics) {
    const int i = scores.metric_index(m.column);
    if (i < 0) throw InvalidData(fmt::format("{}: metric column '{}' was not loaded", scores.path, m.column));
    metric_index.push_back(i);
  }

  const auto conditions = scores.conditions();
  auto conditions_text = [&] {
    std::string s;
    for (const auto& c : conditions) s += (s.empty() ? "" : ", ") + c;
    return s;
  };
  auto require_condition = [&](const std::string& c, std::string_view option) {
    // The data are valid; the command names a condition they do not have: a usage error (64),
    // as in feint likert and feint analyze.
    if (!scores.has_condition) {
      throw UsageError(fmt::format("{}: {} '{}': the file has no condition column", scores.path,
                                   option, c));
    }
    if (std::find(conditions.begin(), conditions.end(), c) == conditions.end()) {
      throw UsageError(fmt::format(
          "{}: {}: condition '{}' does not occur in column 'condition' (conditions: {})",
          scores.path, option, c, conditions_text()));
    }
  };

  const auto iterations = scores.iterations();
  if (two_sample(o)) {
    const auto& [a, b] = *o.compare;
    require_condition(a, "--compare");
    require_condition(b, "--compare");
    if (a == b) {
      throw UsageError(fmt::format("--compare {},{}: a condition cannot be compared with itself", a, b));
    }
    if (o.paired) require_pairs(scores, a, b);
    Table1Block blk;
    blk.group1 = a;
    blk.group2 = b;
    blk.iterations = iterations;
    t.blocks.push_back(std::move(blk));
  } else {
    std::vector<std::string> chosen = conditions;
    if (!o.condition.empty()) {
      require_condition(o.condition, "--condition");
      chosen = {o.condition};
    }
    for (const auto& c : chosen) {
      Table1Block blk;
      blk.title = c;
      blk.group1 = c;
      blk.iterations = iterations;
      t.blocks.push_back(std::move(blk));
    }
  }

  // Index records by (condition, iteration) once.
  std::map<std::pair<std::string, long long>, std::vector<const io::ScoreRecord*>> cell_records;
  for (const auto& r : scores.records) cell_records[{r.condition, r.iteration}].push_back(&r);
  auto records_of = [&](const std::string& c, long long it) {
    const auto f = cell_records.find({c, it});
    return f == cell_records.end() ? std::vector<const io::ScoreRecord*>{} : f->second;
  };

  for (auto& blk : t.blocks) {
    blk.cells.assign(blk.iterations.size(), std::vector<Table1Cell>(o.metrics.size()));
  }
  for (std::size_t m = 0; m < o.metrics.size(); ++m) {
    const auto& spec = o.metrics[m];
    const auto mi = static_cast<std::size_t>(metric_index[m]);
    for (auto& blk : t.blocks) {
      std::vector<std::size_t> family, tost_family;
      std::size_t missing = 0;
      std::vector<std::string> unpaired_notes;
      for (std::size_t ii = 0; ii < blk.iterations.size(); ++ii) {
        const long long it = blk.iterations[ii];
        std::vector<double> x, y;
        stats::TestResult diff, tost;
        if (!two_sample(o)) {
          for (const auto* r : records_of(blk.group1, it)) {
            if (r->values[mi]) x.push_back(*r->values[mi]);
            else ++missing;
          }
          diff = stats::t_test_one_sample(x, spec.reference, o.test);
          if (o.equivalence) tost = stats::tost_one_sample(x, spec.reference, *o.equivalence, o.test);
        } else if (o.paired) {
          std::map<std::string, double> xa, yb;
          for (const auto* r : records_of(blk.group1, it)) {
            if (r->values[mi]) xa[r->participant] = *r->values[mi];
            else ++missing;
          }
          for (const auto* r : records_of(blk.group2, it)) {
            if (r->values[mi]) yb[r->participant] = *r->values[mi];
            else ++missing;
          }
          std::vector<std::string> lone;
          for (const auto& [p, v] : xa) {
            const auto f = yb.find(p);
            if (f == yb.end()) {
              lone.push_back(p);
              continue;
            }
            x.push_back(v);
            y.push_back(f->second);
          }
          for (const auto& [p, v] : yb) {
            if (!xa.count(p)) lone.push_back(p);
          }
          if (!lone.empty()) {
            std::sort(lone.begin(), lone.end());
            std::string who;
            for (const auto& p : lone) who += (who.empty() ? "" : ", ") + p;
            unpaired_notes.push_back(fmt::format("iteration {}: {}", it, who));
          }
          diff = stats::t_test_paired(x, y, o.test);
          if (o.equivalence) tost = stats::tost_paired(x, y, *o.equivalence, o.test);
        } else {
          for (const auto* r : records_of(blk.group1, it)) {
            if (r->values[mi]) x.push_back(*r->values[mi]);
            else ++missing;
          }
          for (const auto* r : records_of(blk.group2, it)) {
            if (r->values[mi]) y.push_back(*r->values[mi]);
            else ++missing;
          }
          diff = o.var_equal ? stats::t_test_student(x, y, o.test) : stats::t_test_welch(x, y, o.test);
          if (o.equivalence) {
            tost = stats::tost_two_sample(x, y, *o.equivalence, o.var_equal, o.test);
          }
        }
        // Appends the tidy row of one test of this cell; returns its index.
        auto add_row = [&](stats::TestResult result) {
          TidyRow row;
          row.metric = spec.column;
          row.iteration = static_cast<int>(it);
          row.group1 = blk.group1;
          row.group2 = blk.group2;
          row.result = std::move(result);
          t.rows.push_back(std::move(row));
          return t.rows.size() - 1;
        };
        stats::add_effect_size_intervals(diff);
        stats::add_bayes_factor(diff, o.bf_prior_r);
        blk.cells[ii][m].difference_row = add_row(std::move(diff));
        family.push_back(blk.cells[ii][m].difference_row);
        if (o.equivalence) {
          blk.cells[ii][m].tost_row = add_row(std::move(tost));
          tost_family.push_back(*blk.cells[ii][m].tost_row);
        }
      }
      adjust_family(t.rows, family, o.p_adjust);
      adjust_family(t.rows, tost_family, o.p_adjust);
      const std::string where = blk.group2.empty()
                                    ? (blk.group1.empty() ? std::string() : " (" + blk.group1 + ")")
                                    : " (" + blk.group1 + ", " + blk.group2 + ")";
      if (missing > 0) {
        t.warnings.push_back(fmt::format("{}{}: {} empty cell{} excluded as missing.", spec.column,
                                         where, missing, missing == 1 ? "" : "s"));
      }
      if (!unpaired_notes.empty()) {
        std::string s;
        for (const auto& u : unpaired_notes) s += (s.empty() ? "" : "; ") + u;
        t.warnings.push_back(fmt::format(
            "{}{}: participants without a pair excluded from the paired test: {}.", spec.column,
            where, s));
      }
    }
  }

  // Labels (after adjustment) and APA strings.
  for (const auto& blk : t.blocks) {
    for (const auto& row_cells : blk.cells) {
      for (const auto& cell : row_cells) {
        TidyRow& d = t.rows[cell.difference_row];
        const stats::TestResult* tost = cell.tost_row ? &t.rows[*cell.tost_row].result : nullptr;
        d.label = label_for(o, d.result, tost);
        if (cell.tost_row) t.rows[*cell.tost_row].label = d.label;
      }
    }
  }
  if (o.apa) {
    for (auto& r : t.rows) r.apa = apa_string(r.result);
  }
  return t;
}

std::vector<std::string> table1_note(const Table1& t) {
  const Table1Options& o = t.options;
  std::vector<std::string> notes;
  const bool two = two_sample(o);
  const std::string alt(stats::to_string(o.test.alternative));

  std::string refs;
  for (const auto& m : o.metrics) {
    refs += fmt::format("{}{} R = {}", refs.empty() ? "" : ", ", m.column, io::format_double(m.reference));
  }
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
  const std::string n_text = n_min == SIZE_MAX ? "0"
                             : n_min == n_max  ? std::to_string(n_min)
                                               : fmt::format("{}\u2013{}", n_min, n_max);
  if (!two) {
    notes.push_back(fmt::format(
        "{}s ({}, alternative = {}) of one value per participant and iteration against the "
        "reference mean R ({}); n = {} per test; alpha = {}.",
        capitalised(test_name(o)), test_call(o), alt, refs, n_text, io::format_double(o.alpha)));
  } else {
    notes.push_back(fmt::format(
        "{}s ({}, alternative = {}) of one value per participant and iteration, A = {} against "
        "B = {}{}; n = {} per group; alpha = {}.",
        capitalised(test_name(o)), test_call(o), alt, o.compare->first, o.compare->second,
        o.paired ? " (pairs matched by participant)" : "", n_text, io::format_double(o.alpha)));
  }
  const std::size_t family = t.blocks.empty() ? 0 : t.blocks.front().iterations.size();
  if (o.p_adjust == stats::PAdjustMethod::none) {
    notes.push_back(fmt::format(
        "p-values are not adjusted for multiple comparisons ({} tests per metric column).", family));
  } else {
    notes.push_back(fmt::format(
        "p-values are adjusted by {} (R's p.adjust, method = \"{}\") within each metric column "
        "(family of {} tests); \"p adj.\" is the adjusted p-value and the labels use it.",
        p_adjust_name(o.p_adjust), stats::to_string(o.p_adjust), family));
  }
  const std::string lhs = two ? "A" : "M";
  const std::string rhs = two ? "B" : "R";
  const std::string what = two ? "the mean of A is" : "the mean is";
  const std::string than = two ? "that of B" : "R";
  const std::string p_used = o.p_adjust == stats::PAdjustMethod::none ? "p" : "adjusted p";
  if (o.equivalence_by_evidence) {
    notes.push_back(fmt::format(
        "{0}>{1} / {0}<{1}: {2} significantly greater / smaller than {3} ({4} < {5}). "
        "{0}\u2248{1}: evidence for no difference, from the JZS Bayes factor BF01 \u2265 {6:g} "
        "(bf01 in the CSV and JSON tables){7}; a non-significant p alone is not evidence of equivalence. "
        "inconclusive: neither significantly different nor shown to be equivalent.",
        lhs, rhs, what, than, p_used, io::format_double(o.alpha), kBf01Equivalence,
        o.equivalence ? fmt::format(" or from TOST within \u00b1{} (two one-sided t-tests, {} < {}, "
                                    "column \"p TOST\")",
                                    io::format_double(*o.equivalence), p_used, io::format_double(o.alpha))
                      : std::string()));
  } else if (!o.equivalence) {
    notes.push_back(fmt::format(
        "{0}>{1} / {0}<{1}: {2} significantly greater / smaller than {3} ({4} < {5}). "
        "{0}\u2248{1}: not significantly different; this is not evidence that they are equal.",
        lhs, rhs, what, than, p_used, io::format_double(o.alpha)));
  } else {
    notes.push_back(fmt::format(
        "{0}>{1} / {0}<{1}: {2} significantly greater / smaller than {3} ({4} < {5}). "
        "{0}\u2248{1}: equivalent within \u00b1{6} by TOST (two one-sided t-tests, {4} < {5}, "
        "column \"p TOST\"); inconclusive: neither significantly different nor shown to be "
        "equivalent.",
        lhs, rhs, what, than, p_used, io::format_double(o.alpha),
        io::format_double(*o.equivalence)));
  }
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
  if (has_confusion) {
    if (!t.provenance.confusion_normalisation.empty()) {
      notes.push_back(fmt::format("Confusion normalisation: {} (from {}).",
                                  t.provenance.confusion_normalisation,
                                  file_name(t.provenance.sidecar_path)));
    } else if (!t.provenance.sidecar_path.empty()) {
      notes.push_back(fmt::format("Confusion normalisation: unknown ({} does not record it).",
                                  file_name(t.provenance.sidecar_path)));
    } else {
      notes.push_back("Confusion normalisation: unknown (no scores sidecar found beside the input).");
    }
  }
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

std::string render_table1(const Table1& t, OutputFormat format,
                          const TablePresentation& presentation) {
  const Table1Options& o = t.options;
  if (format == OutputFormat::csv || format == OutputFormat::json) {
    const auto cols = table_columns(o.apa);
    return format == OutputFormat::csv ? tidy_csv(t.rows, cols) : tidy_json(t.rows, cols);
  }
  const bool two = two_sample(o);
  const bool adj = o.p_adjust != stats::PAdjustMethod::none;
  const bool eq = o.equivalence.has_value();
  TextTable tt;
  std::string metric_names;
  for (std::size_t m = 0; m < o.metrics.size(); ++m) {
    metric_names += (m == 0 ? "" : (m + 1 == o.metrics.size() ? " and " : ", ")) + o.metrics[m].column;
  }
  if (!two) {
    tt.caption = fmt::format("One-sample t-tests of {} per iteration against the reference means",
                             metric_names);
    if (t.blocks.size() == 1 && !t.blocks.front().title.empty()) {
      tt.caption += fmt::format(" (condition: {})", t.blocks.front().title);
    }
  } else {
    tt.caption = fmt::format("{}s of {} per iteration: A = {} vs B = {}",
                             capitalised(test_name(o)), metric_names, o.compare->first,
                             o.compare->second);
  }
  apply_presentation(tt, presentation, table1_default_label(t));
  tt.header.push_back("Iteration");
  tt.right_align.push_back(true);
  for (const auto& m : o.metrics) {
    TextTable::Group g;
    g.title = two ? capitalised(m.column)
                  : fmt::format("{} (R = {})", capitalised(m.column), io::format_double(m.reference));
    g.first = tt.header.size();
    if (two) {
      tt.header.insert(tt.header.end(), {"Mean A", "Mean B"});
      tt.right_align.insert(tt.right_align.end(), {true, true});
    } else {
      tt.header.push_back("Mean (M)");
      tt.right_align.push_back(true);
    }
    tt.header.push_back("p");
    tt.right_align.push_back(true);
    if (adj) {
      tt.header.push_back("p adj.");
      tt.right_align.push_back(true);
    }
    if (eq) {
      tt.header.push_back("p TOST");
      tt.right_align.push_back(true);
    }
    tt.header.push_back("Inference");
    tt.right_align.push_back(false);
    g.count = tt.header.size() - g.first;
    tt.groups.push_back(g);
  }
  const bool sections = t.blocks.size() > 1;
  auto p_cell = [&](const stats::TestResult& r, std::optional<double> p, std::vector<std::string>& text,
                    std::vector<std::string>& latex) {
    if (!r.computed || !p) {
      text.emplace_back(kDash);
      latex.emplace_back("---");
    } else {
      text.push_back(format_p(p));
      latex.push_back(format_p(p, PStyle::latex));
    }
  };
  for (const auto& blk : t.blocks) {
    if (sections) {
      tt.rows.push_back({{"Condition: " + blk.title}, true});
      tt.latex_cells.emplace_back();
    }
    for (std::size_t i = 0; i < blk.iterations.size(); ++i) {
      std::vector<std::string> cells{std::to_string(blk.iterations[i])};
      std::vector<std::string> latex{""};
      for (std::size_t m = 0; m < o.metrics.size(); ++m) {
        const auto& cell = blk.cells[i][m];
        const TidyRow& d = t.rows[cell.difference_row];
        const auto mean_text = [](std::optional<double> v) {
          return v ? format_mean(v) : std::string(kDash);
        };
        cells.push_back(mean_text(d.result.mean1));
        latex.emplace_back(d.result.mean1 ? "" : "---");
        if (two) {
          cells.push_back(mean_text(d.result.mean2));
          latex.emplace_back(d.result.mean2 ? "" : "---");
        }
        p_cell(d.result, d.result.p_value, cells, latex);
        if (adj) p_cell(d.result, d.result.p_adjusted, cells, latex);
        if (eq) {
          const auto& tr = t.rows[*cell.tost_row].result;
          p_cell(tr, decision_p(tr), cells, latex);
        }
        cells.push_back(d.label);
        latex.push_back(latex_label(d.label));
      }
      tt.rows.push_back({std::move(cells), false});
      tt.latex_cells.push_back(std::move(latex));
    }
  }
  tt.notes = table1_note(t);
  if (o.apa) {  // --apa in a table for people: one line per test under the note
    tt.notes.emplace_back("APA-style results:");
    for (const auto& r : t.rows) {
      std::string where;
      if (!r.group2.empty()) where = " (" + r.group1 + " vs " + r.group2 + ")";
      else if (t.blocks.size() > 1) where = " (" + r.group1 + ")";
      tt.notes.push_back(fmt::format("{}, iteration {}{}: {}", r.metric, r.iteration.value_or(0),
                                     where, r.apa));
    }
  }
  if (format == OutputFormat::latex) {  // the LaTeX cells already read 1.5 x 10^-4
    for (auto& n : tt.notes) {
      if (n.rfind("Means to 4 decimals", 0) == 0) {
        n = "Means to 4 decimals; p-values to 4 decimals, in scientific notation below 0.001.";
      }
    }
  }
  return render_table(tt, format);
}

}  // namespace feint::report
