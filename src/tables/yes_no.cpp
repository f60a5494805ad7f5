// The yes/no questions: see feint/tables/yes_no.hpp.
#include "feint/tables/yes_no.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include <fmt/format.h>

#include "feint/error.hpp"
#include "feint/stats/paired_proportions.hpp"
#include "respondents.hpp"
#include "yes_no_detail.hpp"

namespace feint::tables {

namespace {

std::string percent(double v) { return std::isnan(v) ? "–" : fmt::format("{:.0f}%", 100 * v); }
std::string interval(double lo, double hi) {
  return std::isnan(lo) ? "–" : fmt::format("[{:.2f}, {:.2f}]", lo, hi);
}

using detail::respondents_in;

YesNoSummary summarise(const io::Questionnaire& q, std::size_t item, const std::string& group,
                       double conf_level) {
  std::size_t yes = 0, n = 0, missing = 0;
  for (const auto r : respondents_in(q, group)) {
    const auto& a = q.responses[item][r];
    if (!a) ++missing;
    else { ++n; yes += *a == 1 ? 1 : 0; }
  }
  return {q.items[item], group, stats::describe_proportion(yes, n, conf_level), missing};
}

/// Checks the compared conditions exist and are independent (Fisher's and the chi-square test
/// compare two independent groups).
void check_comparison(const io::Questionnaire& q, const std::vector<std::string>& groups,
                      const std::pair<std::string, std::string>& compare, bool paired) {
  if (!q.has_condition)
    throw UsageError(fmt::format("--compare {},{}: {} has no condition column (use --condition-column)",
                                 compare.first, compare.second, q.source));
  for (const auto& c : {compare.first, compare.second})
    if (std::find(groups.begin(), groups.end(), c) == groups.end())
      throw UsageError(fmt::format("--compare {},{}: {} has no condition {} (conditions: {})", compare.first,
                                   compare.second, q.source, c, fmt::join(groups, ", ")));
  if (compare.first == compare.second)
    throw UsageError(fmt::format("--compare {0},{0}: a condition against itself", compare.first));
  if (paired) return;  // the same participants in both: paired by add_paired_rows
  if (const auto shared =
          detail::shared_participant(q, respondents_in(q, compare.first), respondents_in(q, compare.second)))
    throw InvalidData(fmt::format("{}: participant {} answered in both conditions {} and {}; Fisher's exact "
                                  "test compares independent groups (give each participant one condition)",
                                  q.source, *shared, compare.first, compare.second));
}

/// Within participants: per question the table of pairs (the participants who answered it in both
/// conditions), McNemar's exact test, then mcnemar.test. Returns who answered in only one condition.
std::vector<std::string> add_paired_rows(YesNoAnalysis& a, const io::Questionnaire& q,
                                         const std::pair<std::string, std::string>& ab) {
  const auto in_a = detail::rows_by_participant(q, ab.first);
  const auto in_b = detail::rows_by_participant(q, ab.second);
  std::vector<std::string> unpaired;
  for (const auto& [p, _] : in_a)
    if (in_b.count(p) == 0) unpaired.push_back(p);
  for (const auto& [p, _] : in_b)
    if (in_a.count(p) == 0) unpaired.push_back(p);
  for (std::size_t i = 0; i < q.items.size(); ++i) {
    const stats::PairedYesNoTable t = detail::paired_table(q, i, in_a, in_b);
    a.rows.push_back(detail::yes_no_comparison_row(q.items[i], ab.first, ab.second,
                                                   stats::mcnemar_exact(t, a.settings.test), a.settings.alpha));
    a.rows.push_back(
        detail::yes_no_comparison_row(q.items[i], ab.first, ab.second, stats::mcnemar_test(t), a.settings.alpha));
  }
  return unpaired;
}

void add_paired_notes(YesNoAnalysis& a, const std::vector<std::string>& unpaired) {
  const auto& [ga, gb] = *a.settings.compare;
  std::string left_out;
  if (!unpaired.empty()) {
    std::vector<std::string> shown(unpaired.begin(), unpaired.begin() + std::min<std::ptrdiff_t>(10, std::ssize(unpaired)));
    left_out = fmt::format(" Left out: {} participant{} answered in only one of the two conditions ({}{}).",
                           unpaired.size(), unpaired.size() == 1 ? "" : "s", fmt::join(shown, ", "),
                           unpaired.size() > shown.size() ? ", ..." : "");
  }
  a.notes.push_back(fmt::format(
      "{} against {}, within participants: each participant's answer after {} is paired with theirs after {} "
      "(a pair missing either answer is left out of that question). McNemar's exact test (primary: the binomial "
      "test of the discordant pairs, R's binom.test(b, b + c)) with the conditional odds ratio b/c of yes in A "
      "and its exact interval; beside it R's mcnemar.test (chi-square, continuity-corrected) with the "
      "difference of the paired proportions p_A - p_B. A>B / A<B: p < {:g}; n.s. otherwise (no test here gives "
      "evidence of no difference).{}",
      ga, gb, ga, gb, a.settings.alpha, left_out));
}

}  // namespace

namespace detail {

TidyRow yes_no_comparison_row(const std::string& question, const std::string& a, const std::string& b,
                              stats::TestResult result, double alpha) {
  TidyRow row;
  row.metric = question;
  row.group1 = a;
  row.group2 = b;
  // Two proportions: no Bayes factor and no equivalence test, so "≈" is never earned.
  if (!result.computed) row.label = std::string(kNotComputable);
  else if (*result.p_value >= alpha) row.label = std::string(kNotSignificant);
  else row.label = *result.mean1 > *result.mean2 ? "A>B" : "A<B";
  row.result = std::move(result);
  return row;
}

std::map<std::string, std::size_t> rows_by_participant(const io::Questionnaire& q, const std::string& c) {
  std::map<std::string, std::size_t> rows;
  for (const auto r : respondents_in(q, c))
    if (!rows.emplace(q.participants[r], r).second)
      throw InvalidData(fmt::format("{}: participant {} answered twice in condition {}; a paired comparison needs "
                                    "one answer per participant and condition",
                                    q.source, q.participants[r], c));
  return rows;
}

stats::PairedYesNoTable paired_table(const io::Questionnaire& q, std::size_t item,
                                     const std::map<std::string, std::size_t>& in_a,
                                     const std::map<std::string, std::size_t>& in_b) {
  stats::PairedYesNoTable t;
  for (const auto& [p, ra] : in_a) {
    const auto other = in_b.find(p);
    if (other == in_b.end() || !q.responses[item][ra] || !q.responses[item][other->second]) continue;
    const bool ya = *q.responses[item][ra] == 1, yb = *q.responses[item][other->second] == 1;
    ++(ya ? (yb ? t.yes_yes : t.yes_no) : (yb ? t.no_yes : t.no_no));
  }
  return t;
}

ComparisonCells comparison_cells(const TidyRow& row) {
  const auto& r = row.result;
  const bool odds_ratio = r.test == "fisher_exact" || r.test == "mcnemar_exact";
  ComparisonCells c;
  if (r.computed && r.estimate) {
    c.estimate = odds_ratio ? fmt::format("OR = {:.2f}", *r.estimate) : fmt::format("Δ = {:.2f}", *r.estimate);
    if (r.conf_low && r.conf_high) c.ci = fmt::format("[{:.2f}, {:.2f}]", *r.conf_low, *r.conf_high);
  }
  if (r.computed && r.statistic)
    c.statistic = r.df ? fmt::format("χ²({:g}) = {:.2f}", *r.df, *r.statistic) : fmt::format("b = {:g}", *r.statistic);
  c.test = r.test == "fisher_exact"    ? "Fisher's exact"
           : r.test == "mcnemar_exact" ? "McNemar exact"
           : r.test == "mcnemar"       ? "McNemar χ²"
                                       : "χ² (Yates)";
  return c;
}

const YesNoSummary& summary_of(const YesNoAnalysis& a, const std::string& question, const std::string& group) {
  return *std::find_if(a.summaries.begin(), a.summaries.end(),
                       [&](const auto& s) { return s.question == question && s.group == group; });
}

}  // namespace detail

io::QuestionnaireOptions yes_no_load_options() {
  io::QuestionnaireOptions o;
  o.layout = io::QuestionnaireLayout::wide_format;
  o.scale_min = 0;
  o.scale_max = 1;
  o.labels = {{"yes", 1}, {"no", 0}, {"y", 1}, {"n", 0}, {"true", 1}, {"false", 0}};
  return o;
}

YesNoAnalysis analyze_yes_no(const io::Questionnaire& q, const YesNoSettings& settings) {
  YesNoAnalysis a;
  a.settings = settings;
  a.source = q.source;
  a.questions = q.items;
  a.groups = q.has_condition ? q.condition_names() : std::vector<std::string>{""};
  if (settings.compare) check_comparison(q, a.groups, *settings.compare, settings.paired);
  for (std::size_t i = 0; i < q.items.size(); ++i)
    for (const auto& g : a.groups) a.summaries.push_back(summarise(q, i, g, settings.test.conf_level));
  a.notes.push_back(fmt::format(
      "Proportion of yes with its exact (Clopper–Pearson) and Wilson {:g}% intervals; empty answers "
      "are left out of n.", 100 * settings.test.conf_level));
  if (!settings.compare) {
    if (settings.across_conditions && a.groups.size() > 2) detail::compare_across_conditions(a, q);
    return a;
  }
  if (settings.paired) {
    add_paired_notes(a, add_paired_rows(a, q, *settings.compare));
    return a;
  }
  const auto& [ga, gb] = *settings.compare;
  for (std::size_t i = 0; i < q.items.size(); ++i) {
    const auto& sa = detail::summary_of(a, q.items[i], ga);
    const auto& sb = detail::summary_of(a, q.items[i], gb);
    const stats::YesNoTable t{sa.proportion.x, sa.proportion.n, sb.proportion.x, sb.proportion.n};
    a.rows.push_back(
        detail::yes_no_comparison_row(q.items[i], ga, gb, stats::fisher_exact(t, settings.test), settings.alpha));
    a.rows.push_back(
        detail::yes_no_comparison_row(q.items[i], ga, gb, stats::prop_test(t, settings.test), settings.alpha));
  }
  a.notes.push_back(fmt::format(
      "{} against {}: Fisher's exact test (primary) with the conditional maximum-likelihood odds ratio of "
      "yes and its interval; beside it the chi-square test of two proportions (Yates-corrected) with the "
      "difference of the proportions. A>B / A<B: p < {:g}; n.s. otherwise (no test here gives evidence "
      "of no difference).",
      ga, gb, settings.alpha));
  return a;
}

YesNoAnalysis analyze_yes_no_file(const std::string& path, const YesNoSettings& settings) {
  return analyze_yes_no(io::load_questionnaire(path, settings.load), settings);
}

namespace {

std::string render_records(const YesNoAnalysis& a, OutputFormat format) {
  const std::vector<std::string_view> columns{"question", "condition", "yes", "n", "missing", "proportion",
                                              "exact_low", "exact_high", "wilson_low", "wilson_high"};
  std::vector<Record> records;
  for (const auto& s : a.summaries) {
    const auto& p = s.proportion;
    records.push_back({Cell::str(s.question), Cell::str(s.group), Cell::integer(static_cast<long long>(p.x)),
                       Cell::integer(static_cast<long long>(p.n)), Cell::integer(static_cast<long long>(s.missing)),
                       Cell::num(p.n ? std::optional(p.estimate) : std::nullopt),
                       Cell::num(p.n ? std::optional(p.exact_low) : std::nullopt),
                       Cell::num(p.n ? std::optional(p.exact_high) : std::nullopt),
                       Cell::num(p.n ? std::optional(p.wilson_low) : std::nullopt),
                       Cell::num(p.n ? std::optional(p.wilson_high) : std::nullopt)});
  }
  const auto test_columns = table_columns();
  std::vector<TidyRow> tests = a.omnibus;  // across the conditions: the omnibus rows first
  tests.insert(tests.end(), a.rows.begin(), a.rows.end());
  if (format == OutputFormat::csv) {
    std::string out = write_csv(columns, records);
    if (!tests.empty()) out += "\n" + tidy_csv(tests, test_columns);
    return out;
  }
  std::string out = "{\"proportions\": " + write_json(columns, records);
  if (!out.empty() && out.back() == '\n') out.pop_back();
  out += ", \"tests\": " + tidy_json(tests, test_columns);
  if (!out.empty() && out.back() == '\n') out.pop_back();
  return out + "}\n";
}

TextTable comparison_table(const YesNoAnalysis& a) {
  TextTable t;
  t.caption = fmt::format("Yes/no questions: {} against {}{}", a.settings.compare->first, a.settings.compare->second,
                          a.settings.paired ? " within participants" : "");
  t.header = {"Question", "Test", "Estimate", "CI", "Statistic", "p", "Inference"};
  t.right_align = {false, false, true, true, true, true, false};
  for (const auto& row : a.rows) {
    const auto c = detail::comparison_cells(row);
    t.rows.push_back({{row.metric, c.test, c.estimate, c.ci, c.statistic,
                       row.result.computed ? format_p(row.result.p_value) : "–", row.label}});
  }
  return t;
}

}  // namespace

std::string render_yes_no(const YesNoAnalysis& a, OutputFormat format) {
  if (format == OutputFormat::csv || format == OutputFormat::json) return render_records(a, format);
  TextTable t;
  t.caption = "Yes/no questions: proportion of yes per condition";
  t.header = {"Question", "Condition", "Yes", "n", "%", "Exact CI", "Wilson CI"};
  t.right_align = {false, false, true, true, true, true, true};
  for (const auto& s : a.summaries) {
    const auto& p = s.proportion;
    t.rows.push_back({{s.question, s.group.empty() ? "all" : s.group, std::to_string(p.x), std::to_string(p.n),
                       percent(p.estimate), interval(p.exact_low, p.exact_high),
                       interval(p.wilson_low, p.wilson_high)}});
  }
  // Without a comparison table the notes stay here (e.g. why three conditions were not compared).
  t.notes = a.settings.compare || !a.compared.empty() ? std::vector<std::string>{a.notes.front()} : a.notes;
  std::string out = render_table(t, format);
  if (!a.compared.empty()) return out + detail::render_across_conditions(a, format);
  if (a.settings.compare) {
    TextTable c = comparison_table(a);
    c.notes = {a.notes.back()};
    for (const auto& row : a.rows)
      if (!row.result.note.empty()) c.notes.push_back(row.metric + ": " + row.result.note);
    out += "\n" + render_table(c, format);
  }
  return out;
}

}  // namespace feint::tables
