// Likert analysis assembly. See feint/tables/likert.hpp.
#include "respondents.hpp"
#include "feint/tables/likert.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include <fmt/format.h>

#include "feint/error.hpp"
#include "feint/io/csv.hpp"
#include "feint/io/number.hpp"
#include "feint/io/output.hpp"
#include "feint/stats/descriptive.hpp"
#include "feint/stats/rank_tests.hpp"
#include "feint/stats/reliability.hpp"
#include "feint/stats/bayes_factor.hpp"
#include "feint/stats/effect_size.hpp"
#include "feint/stats/ttest.hpp"

namespace feint::tables {

namespace detail {
namespace {

std::string join(const std::vector<std::string>& names, std::string_view sep = ", ") {
  std::string out;
  for (const auto& n : names) {
    if (!out.empty()) out += sep;
    out += n;
  }
  return out;
}

bool iequals(std::string_view a, std::string_view b) {
  return io::to_lower(io::trim(a)) == io::to_lower(io::trim(b));
}

/// Label of a rank test: direction from the rank-biserial correlation (a rank test has no mean
/// estimate), significance from the (adjusted) p-value.
std::string rank_label(const stats::TestResult& r, double alpha, std::string_view lhs,
                       std::string_view rhs) {
  if (!r.computed) return std::string(kNotComputable);
  const auto p = decision_p(r);
  if (p && *p < alpha && r.rank_biserial && *r.rank_biserial != 0.0) {
    return fmt::format("{}{}{}", lhs, *r.rank_biserial > 0 ? ">" : "<", rhs);
  }
  // A rank test has no Bayes factor or TOST: nothing here is evidence of no difference.
  return std::string(kNotSignificant);
}

LikertSummary summarize(const std::string& name, bool composite, const std::string& group,
                        std::vector<double> values, std::size_t missing, int lo, int hi,
                        double neutral) {
  LikertSummary s;
  s.name = name;
  s.composite = composite;
  s.group = group;
  s.n = values.size();
  s.missing = missing;
  if (!composite) s.counts.assign(static_cast<std::size_t>(hi - lo + 1), 0);
  if (values.empty()) return s;
  std::sort(values.begin(), values.end());
  const auto sum = stats::summarize(values);
  s.mean = sum.mean;
  s.sd = sum.sd();
  s.median = stats::quantile_type7(values, 0.5);
  s.q1 = stats::quantile_type7(values, 0.25);
  s.q3 = stats::quantile_type7(values, 0.75);
  s.iqr = *s.q3 - *s.q1;
  std::size_t below = 0, at = 0, above = 0;
  for (const double v : values) {
    if (!composite) ++s.counts[static_cast<std::size_t>(std::lround(v) - lo)];
    if (v < neutral) {
      ++below;
    } else if (v > neutral) {
      ++above;
    } else {
      ++at;
    }
  }
  const double n = static_cast<double>(values.size());
  s.pct_below = 100.0 * static_cast<double>(below) / n;
  s.pct_at = 100.0 * static_cast<double>(at) / n;
  s.pct_above = 100.0 * static_cast<double>(above) / n;
  return s;
}

std::string fmt_number(double x) { return io::format_double(x); }

}  // namespace
}  // namespace detail

std::vector<std::string> paper_items() {
  return {"entertainment", "deception", "intelligence", "trust"};
}

LikertComposite parse_composite(std::string_view text) {
  const auto eq = text.find('=');
  if (eq == std::string_view::npos) {
    throw UsageError(fmt::format("--composite '{}': expected NAME=ITEM,ITEM,...", text));
  }
  LikertComposite c;
  c.name = std::string(io::trim(text.substr(0, eq)));
  for (const auto& item : io::split_csv_line(text.substr(eq + 1), ',')) {
    const std::string name(io::trim(item));
    if (name.empty()) continue;
    for (const auto& prev : c.items) {
      if (detail::iequals(prev, name)) {
        throw UsageError(fmt::format("--composite '{}': item '{}' is listed twice", text, name));
      }
    }
    c.items.push_back(name);
  }
  if (c.name.empty())
    throw UsageError(fmt::format("--composite '{}': the scale has no name", text));
  if (c.items.size() < 2) {
    throw UsageError(
        fmt::format("--composite '{}': a multi-item scale needs at least two items", text));
  }
  return c;
}

namespace detail {
namespace {

/// Checks the settings and sets up the analysis: scale, neutral point and reference.
LikertAnalysis new_analysis(const io::Questionnaire& q, const LikertSettings& settings) {
  if (!(settings.alpha > 0.0 && settings.alpha < 1.0)) {
    throw UsageError(fmt::format("--alpha {}: expected a number in (0, 1)", settings.alpha));
  }
  LikertAnalysis a;
  a.settings = settings;
  a.source = q.source;
  a.scale_min = q.scale_min;
  a.scale_max = q.scale_max;
  a.neutral = (q.scale_min + q.scale_max) / 2.0;
  a.reference =
      settings.reference ? *settings.reference : (settings.paper ? kPaperReference : a.neutral);
  if (!std::isfinite(a.reference)) throw UsageError("--reference: expected a finite number");
  return a;
}

/// Names the analysis: the questionnaire items, then the composites. Returns the items of each
/// composite (indices into q.items).
std::vector<std::vector<std::size_t>> add_names(LikertAnalysis& a, const io::Questionnaire& q,
                                                const LikertSettings& settings) {
  std::vector<std::vector<std::size_t>> members;
  for (std::size_t i = 0; i < q.items.size(); ++i) {
    a.names.push_back(q.items[i]);
    a.is_composite.push_back(false);
    a.reversed.push_back(q.reversed.size() > i && q.reversed[i]);
  }
  for (const auto& c : settings.composites) {
    for (const auto& n : a.names) {
      if (iequals(n, c.name)) {
        throw UsageError(
            fmt::format("--composite {}: the name is already an item or a composite", c.name));
      }
    }
    std::vector<std::size_t> idx;
    for (const auto& item : c.items) {
      const auto i = q.item_index(item);
      if (!i) {
        throw UsageError(fmt::format("--composite {}: no item '{}' (items: {})", c.name, item,
                                     join(q.items)));
      }
      idx.push_back(*i);
    }
    members.push_back(std::move(idx));
    a.names.push_back(c.name);
    a.is_composite.push_back(true);
    a.reversed.push_back(false);
  }
  return members;
}

using detail::respondents_in;

void check_condition(const io::Questionnaire& q, const std::vector<std::string>& conditions,
                     const std::string& c, std::string_view option) {
  if (!q.has_condition) {
    throw UsageError(fmt::format("{} {}: {} has no condition column (use --condition-column)",
                                 option, c, q.source));
  }
  if (std::find(conditions.begin(), conditions.end(), c) == conditions.end()) {
    throw UsageError(fmt::format("{} {}: no such condition (conditions: {})", option, c,
                                 join(conditions)));
  }
}

/// An analysis block: one condition against the reference, or condition A against B.
struct Block {
  std::string group1, group2;
  std::vector<std::size_t> resp1, resp2;
};

/// The two-sample block of --compare A,B; Mann-Whitney and Welch need independent groups.
Block comparison_block(const io::Questionnaire& q, const std::vector<std::string>& conditions,
                       const std::pair<std::string, std::string>& compare) {
  const auto& [ga, gb] = compare;
  check_condition(q, conditions, ga, "--compare");
  check_condition(q, conditions, gb, "--compare");
  if (ga == gb)
    throw UsageError(fmt::format("--compare {},{}: a condition against itself", ga, gb));
  Block b{ga, gb, respondents_in(q, ga), respondents_in(q, gb)};
  if (const auto shared = detail::shared_participant(q, b.resp1, b.resp2)) {
    throw InvalidData(fmt::format(
        "{}: participant {} answered in both conditions {} and {}; Mann-Whitney and Welch "
        "compare independent groups",
        q.source, *shared, ga, gb));
  }
  return b;
}

/// Within participants: each participant's A answer beside their B answer (resp1[i] and resp2[i]
/// are one participant); those with only one of the two are left out and listed in `unpaired`.
Block paired_block(const io::Questionnaire& q, const std::vector<std::string>& conditions,
                   const std::pair<std::string, std::string>& compare,
                   std::vector<std::string>& unpaired) {
  const auto& [ga, gb] = compare;
  check_condition(q, conditions, ga, "--compare");
  check_condition(q, conditions, gb, "--compare");
  if (ga == gb)
    throw UsageError(fmt::format("--compare {},{}: a condition against itself", ga, gb));
  std::map<std::string, std::size_t> in_a, in_b;
  for (const auto& [group, rows] : {std::pair{&ga, &in_a}, std::pair{&gb, &in_b}})
    for (const auto r : respondents_in(q, *group))
      if (!rows->emplace(q.participants[r], r).second)
        throw InvalidData(fmt::format("{}: participant {} answered twice in condition {}; a paired "
                                      "comparison needs one answer per participant and condition",
                                      q.source, q.participants[r], *group));
  Block b{ga, gb, {}, {}};
  for (const auto r : respondents_in(q, ga)) {
    const auto other = in_b.find(q.participants[r]);
    if (other == in_b.end()) {
      unpaired.push_back(q.participants[r]);
      continue;
    }
    b.resp1.push_back(r);
    b.resp2.push_back(other->second);
  }
  for (const auto r : respondents_in(q, gb))
    if (in_a.count(q.participants[r]) == 0) unpaired.push_back(q.participants[r]);
  return b;
}

/// The blocks: A against B (--compare), the one --condition, or each condition in turn.
std::vector<Block> analysis_blocks(LikertAnalysis& a, const io::Questionnaire& q,
                                   const LikertSettings& settings) {
  const auto conditions = q.condition_names();
  std::vector<Block> blocks;
  if (settings.compare) {
    Block b = settings.paired ? paired_block(q, conditions, *settings.compare, a.unpaired)
                              : comparison_block(q, conditions, *settings.compare);
    a.two_sample = true;
    a.paired = settings.paired;
    blocks.push_back(std::move(b));
  } else if (!settings.condition.empty()) {
    check_condition(q, conditions, settings.condition, "--condition");
    blocks.push_back({settings.condition, "", respondents_in(q, settings.condition), {}});
  } else if (q.has_condition) {
    for (const auto& c : conditions) blocks.push_back({c, "", respondents_in(q, c), {}});
  } else {
    blocks.push_back({"", "", respondents_in(q, ""), {}});
  }
  return blocks;
}

/// Cronbach's alpha of each composite over the block's respondents (both groups in two-sample
/// mode). Returns the raw alpha per name index, for the composites' rows.
std::map<std::size_t, std::optional<double>> add_reliability(
    LikertAnalysis& a, const io::Questionnaire& q,
    const std::vector<std::vector<std::size_t>>& members, const Block& b,
    const LikertSettings& settings) {
  const std::size_t n_items = q.items.size();
  std::vector<std::size_t> everyone = b.resp1;
  everyone.insert(everyone.end(), b.resp2.begin(), b.resp2.end());
  std::map<std::size_t, std::optional<double>> alpha_of;
  for (std::size_t c = 0; c < members.size(); ++c) {
    LikertReliability rel;
    rel.name = a.names[n_items + c];
    rel.group = a.two_sample ? b.group1 + "+" + b.group2 : b.group1;
    // Every respondent, NaN for a missing answer: cronbach_alpha applies the chosen treatment.
    std::vector<std::vector<double>> cols(members[c].size());
    for (const auto r : everyone) {
      for (std::size_t j = 0; j < members[c].size(); ++j) {
        const auto& v = q.responses[members[c][j]][r];
        cols[j].push_back(v ? static_cast<double>(*v) : std::nan(""));
      }
    }
    for (const auto i : members[c]) rel.items.push_back(q.items[i]);
    const auto ca = stats::cronbach_alpha(cols, settings.alpha_missing);
    rel.n = ca.n;
    rel.alpha = ca.raw_alpha;
    rel.if_dropped = ca.if_dropped;
    rel.note = ca.note;
    alpha_of[n_items + c] = ca.raw_alpha;
    a.reliability.push_back(std::move(rel));
  }
  return alpha_of;
}

/// Summaries of name k in the block, then its two rows: the rank test (primary), the t-test.
void add_tests(LikertAnalysis& a, const Answers& answers, const Block& b, std::size_t k,
               const LikertSettings& settings,
               const std::map<std::size_t, std::optional<double>>& alpha_of) {
  const auto& q = answers.q;
  const bool comp = a.is_composite[k];
  auto [x, miss_x] = answers.values_of(k, b.resp1);
  a.summaries.push_back(
      summarize(a.names[k], comp, b.group1, x, miss_x, q.scale_min, q.scale_max, a.neutral));
  TidyRow primary, paper;
  primary.metric = paper.metric = a.names[k];
  primary.group1 = paper.group1 = b.group1;
  primary.group2 = paper.group2 = b.group2;
  std::size_t nonzero = 0;  // the signed-rank test's n for the interval of r
  if (a.paired) {
    auto [y, miss_y] = answers.values_of(k, b.resp2);
    a.summaries.push_back(
        summarize(a.names[k], comp, b.group2, y, miss_y, q.scale_min, q.scale_max, a.neutral));
    // Aligned pairs, NaN where an answer is missing: both tests drop that pair (as R's paired
    // tests drop incomplete pairs).
    std::vector<double> xa, yb, diff;
    for (std::size_t i = 0; i < b.resp1.size(); ++i) {
      xa.push_back(answers.value(k, b.resp1[i]).value_or(std::nan("")));
      yb.push_back(answers.value(k, b.resp2[i]).value_or(std::nan("")));
      diff.push_back(xa.back() - yb.back());
      nonzero += !std::isnan(diff.back()) && diff.back() != 0.0;
    }
    primary.result = stats::wilcoxon_signed_rank(diff, 0.0, settings.test);
    paper.result = stats::t_test_paired(xa, yb, settings.test);
  } else if (a.two_sample) {
    auto [y, miss_y] = answers.values_of(k, b.resp2);
    a.summaries.push_back(
        summarize(a.names[k], comp, b.group2, y, miss_y, q.scale_min, q.scale_max, a.neutral));
    primary.result = stats::mann_whitney(x, y, settings.test);
    paper.result = stats::t_test_welch(x, y, settings.test);
  } else {
    primary.result = stats::wilcoxon_signed_rank(x, a.reference, settings.test);
    paper.result = stats::t_test_one_sample(x, a.reference, settings.test);
  }
  // effect-size intervals (r: n = non-zero differences for the signed-rank test) and the JZS
  // Bayes factor of the t test
  if (!a.two_sample)
    for (double v : x) nonzero += !std::isnan(v) && v != a.reference;
  stats::add_effect_size_intervals(primary.result, a.two_sample && !a.paired ? 0 : nonzero);
  stats::add_effect_size_intervals(paper.result);
  stats::add_bayes_factor(paper.result, settings.bf_prior_r);
  if (comp) primary.cronbach_alpha = paper.cronbach_alpha = alpha_of.at(k);
  a.rows.push_back(std::move(primary));
  a.rows.push_back(std::move(paper));
}

/// Multiple comparisons: one family per test kind within the block (rows alternate rank test,
/// t-test), across items and composites.
void adjust_block(std::vector<TidyRow>& rows, std::size_t first_row,
                  stats::PAdjustMethod method) {
  for (std::size_t kind = 0; kind < 2; ++kind) {
    std::vector<std::optional<double>> p;
    for (std::size_t i = first_row + kind; i < rows.size(); i += 2) {
      const auto& r = rows[i].result;
      p.push_back(r.computed ? r.p_value : std::nullopt);
    }
    const auto adj = stats::p_adjust(p, method);
    std::size_t j = 0;
    for (std::size_t i = first_row + kind; i < rows.size(); i += 2) {
      rows[i].result.p_adjusted = adj[j++];
    }
  }
}

/// Labels (after the adjustment) and APA strings of the block's rows.
void label_block(LikertAnalysis& a, std::size_t first_row, const LikertSettings& settings) {
  for (std::size_t i = first_row; i < a.rows.size(); ++i) {
    auto& row = a.rows[i];
    const bool rank = (i - first_row) % 2 == 0;
    if (a.two_sample) {
      row.label = rank ? rank_label(row.result, settings.alpha, "A", "B")
                       : two_sample_label(row.result, settings.alpha);
    } else {
      row.label = rank ? rank_label(row.result, settings.alpha, "M", "R")
                       : one_sample_label(row.result, settings.alpha);
    }
    if (settings.apa) row.apa = apa_string(row.result);
  }
}

void analyse_block(LikertAnalysis& a, const Answers& answers, const Block& b,
                   const LikertSettings& settings) {
  const std::size_t first_row = a.rows.size();
  const auto alpha_of = add_reliability(a, answers.q, answers.members, b, settings);
  for (std::size_t k = 0; k < a.names.size(); ++k) add_tests(a, answers, b, k, settings, alpha_of);
  if (settings.p_adjust != stats::PAdjustMethod::none) {
    adjust_block(a.rows, first_row, settings.p_adjust);
  }
  label_block(a, first_row, settings);
}

/// What a paired (within-participant) comparison shows, and who was left out.
void add_paired_notes(LikertAnalysis& a, const Block& b) {
  a.notes.push_back(fmt::format(
      "A = {}, B = {}, within participants: each participant's answer after A is paired with their "
      "answer after B ({} participants answered in both). Single Likert items are ordinal: the "
      "Wilcoxon signed-rank test on the differences A - B (R's wilcox.test(x, y, paired = TRUE)) is "
      "the primary analysis, with the matched-pairs rank-biserial correlation r (positive: A answers "
      "higher); the paired t-test (t.test(x, y, paired = TRUE)) with d_z is shown beside it. A pair "
      "missing either answer is left out of that item.",
      b.group1, b.group2, b.resp1.size()));
  a.notes.push_back(
      "Signed-rank p-values are exact when fewer than 50 pairs differ, with no tied and no zero "
      "differences, otherwise from the normal approximation with continuity and tie corrections (R's "
      "rules; column 'dist' of the table, 'exact' of the CSV/JSON, says which ran). Pairs with equal "
      "answers (zero differences) are dropped by the signed-rank test, as in R.");
  if (!a.unpaired.empty()) {
    std::vector<std::string> shown(a.unpaired.begin(),
                                   a.unpaired.begin() + std::min<std::ptrdiff_t>(10, std::ssize(a.unpaired)));
    a.notes.push_back(fmt::format("Left out: {} participant{} answered in only one of the two conditions ({}{}).",
                                  a.unpaired.size(), a.unpaired.size() == 1 ? "" : "s", join(shown),
                                  a.unpaired.size() > shown.size() ? ", ..." : ""));
  }
}

/// The note's first part: what the table shows and how it was made.
void add_method_notes(LikertAnalysis& a, const io::Questionnaire& q,
                      const LikertSettings& settings, bool has_composites,
                      const std::vector<Block>& blocks) {
  auto& notes = a.notes;
  const std::string ref_origin = settings.reference ? "set by --reference"
                                 : settings.paper   ? "the paper's reference mean"
                                                    : "the scale midpoint";
  notes.push_back(fmt::format("Scale {}-{}; neutral point {} (for % below / at / above).",
                              q.scale_min, q.scale_max, fmt_number(a.neutral)));
  if (a.paired) {
    add_paired_notes(a, blocks.front());
  } else if (a.two_sample) {
    notes.push_back(fmt::format(
        "A = {}, B = {}. Single Likert items are ordinal: the Mann-Whitney U test (R's "
        "wilcox.test(x, y)) is the primary analysis, with the rank-biserial correlation r = "
        "2W/(n1 n2) - 1 (positive: A answers higher); Welch's t-test (t.test(x, y)) with Cohen's d "
        "is shown beside it.",
        blocks[0].group1, blocks[0].group2));
  } else {
    notes.push_back(fmt::format(
        "Tests against R = {} ({}). Single Likert items are ordinal: the Wilcoxon signed-rank test "
        "(R's wilcox.test(x, mu = R)) is the primary analysis, with the rank-biserial correlation "
        "r; the one-sample t-test (t.test(x, mu = R)) with Cohen's d is shown beside it{}.",
        fmt_number(a.reference), ref_origin,
        settings.paper ? " because it is the paper's analysis" : ""));
  }
  if (settings.paper) {
    notes.push_back(
        "--paper: the paper's analysis (entertainment, deception, intelligence, trust; one-sample "
        "t-tests against 3.5) is the t-test column; for single items the Wilcoxon column is the "
        "recommended one.");
  }
  if (a.two_sample && !a.paired) {
    notes.push_back(
        "Mann-Whitney p-values are exact when both groups have fewer than 50 answers and there are "
        "no ties, otherwise from the normal approximation with continuity and tie corrections (R's "
        "rules; column 'dist' of the table, 'exact' of the CSV/JSON, says which ran).");
  } else if (!a.two_sample) {
    notes.push_back(
        "Signed-rank p-values are exact when n < 50 with no ties and no answers equal to R, "
        "otherwise from the normal approximation with continuity and tie corrections (R's rules; "
        "column 'dist' of the table, 'exact' of the CSV/JSON, says which ran). Answers equal to R "
        "are dropped by the signed-rank test, as in R.");
  }
  notes.push_back(fmt::format(
      "Labels: {0} when p < {1} (rank tests: direction of r; t-tests: of the mean difference); "
      "{2}: evidence for no difference (t-tests: BF01 ≥ {3:g}); n.s.: not significant at "
      "alpha = {1} and not shown to be equal (rank tests have no Bayes factor, so never {2}).",
      a.two_sample ? "A>B / A<B" : "M>R / M<R", fmt_number(settings.alpha),
      a.two_sample ? fmt::format("A{}B", kApprox) : fmt::format("M{}R", kApprox), kBf01Equivalence));
  notes.push_back(fmt::format(
      "BF10 / BF01 of the t-tests: JZS Bayes factor (Rouder et al. 2009), Cauchy prior on the "
      "standardised effect, scale {}; docs/bayes-factors.md.",
      stats::jzs_prior_text(settings.bf_prior_r)));
  if (settings.test.alternative != stats::Alternative::two_sided) {
    notes.push_back(
        fmt::format("Alternative hypothesis: {}.", to_string(settings.test.alternative)));
  }
  if (settings.p_adjust != stats::PAdjustMethod::none) {
    notes.push_back(fmt::format(
        "p-values adjusted ({}) across the {} items{} of each test{}; the labels use the adjusted "
        "p.",
        to_string(settings.p_adjust), a.names.size(), has_composites ? " and composites" : "",
        blocks.size() > 1 ? " and condition" : ""));
  }
}

/// The note's second part: how the data were read (missing answers, reverse coding, composites,
/// exclusions, text answers) and what could not be computed.
void add_data_notes(LikertAnalysis& a, const io::Questionnaire& q, const LikertSettings& settings,
                    bool has_composites) {
  auto& notes = a.notes;
  notes.push_back(a.two_sample ? "Empty answers are missing: excluded from that item only (n A and "
                                 "n B count the answers; --summary counts the missing)."
                               : "Empty answers are missing: excluded from that item only and "
                                 "counted (miss).");
  std::vector<std::string> rev;
  for (std::size_t i = 0; i < q.items.size(); ++i) {
    if (a.reversed[i]) rev.push_back(q.items[i]);
  }
  if (!rev.empty()) {
    notes.push_back(fmt::format("Reverse-coded before analysis (x -> {} - x): {}.",
                                q.scale_min + q.scale_max, join(rev)));
  }
  if (has_composites) {
    notes.push_back(fmt::format(
        "Composite scores are the mean of their items per respondent; a respondent missing any of "
        "its items is missing for the composite. Cronbach's alpha: raw alpha as psych::alpha, {}.",
        settings.alpha_missing == stats::AlphaMissing::pairwise
            ? "from pairwise covariances (psych's default use = \"pairwise\": each covariance "
              "from the respondents who answered both items; n = respondents who answered any "
              "item; --alpha-missing complete for complete cases)"
            : "on complete cases (--alpha-missing complete; psych::alpha(na.omit(items)))"));
  }
  if (q.qualtrics) {
    notes.push_back("Qualtrics export: the question-text and ImportId header rows were skipped.");
  }
  if (!q.excluded.empty()) notes.push_back(io::describe_exclusions(q));
  if (q.text_answers_mapped > 0) {
    notes.push_back(fmt::format("{} text answer{} mapped to scale points by the {} label map.",
                                q.text_answers_mapped, q.text_answers_mapped == 1 ? "" : "s",
                                q.label_map));
  }
  for (const auto& row : a.rows) {
    if (!row.result.computed) {
      notes.push_back(fmt::format("Not computable: {}{} ({}): {}.", row.metric,
                                  row.group1.empty() || a.two_sample ? "" : " in " + row.group1,
                                  row.result.test, row.result.note));
    }
  }
  for (const auto& rel : a.reliability) {
    if (!rel.alpha) {
      notes.push_back(fmt::format("Cronbach's alpha of {}{} not computable: {}.", rel.name,
                                  rel.group.empty() ? "" : " (" + rel.group + ")", rel.note));
    }
  }
}

}  // namespace
}  // namespace detail

LikertAnalysis analyze_likert(const io::Questionnaire& q, const LikertSettings& settings) {
  LikertAnalysis a = detail::new_analysis(q, settings);
  const auto members = detail::add_names(a, q, settings);
  const detail::Answers answers{q, members};
  const auto blocks = detail::analysis_blocks(a, q, settings);
  for (const auto& b : blocks) a.groups.push_back(b.group1);
  for (const auto& b : blocks) detail::analyse_block(a, answers, b, settings);
  detail::add_method_notes(a, q, settings, !members.empty(), blocks);
  detail::add_data_notes(a, q, settings, !members.empty());
  return a;
}

LikertAnalysis analyze_likert_file(const std::string& path, const LikertSettings& settings) {
  io::QuestionnaireOptions load = settings.load;
  if (!settings.paper || !load.items.empty()) {
    return analyze_likert(io::load_questionnaire(path, load), settings);
  }
  load.items = paper_items();
  std::optional<io::Questionnaire> q;
  try {
    q = io::load_questionnaire(path, load);
  } catch (const UsageError& e) {
    // Say why items the user did not type are looked for.
    throw UsageError(
        fmt::format("--paper analyses the paper's items ({}; name others with "
                    "--items): {}",
                    detail::join(paper_items()), e.what()));
  }
  return analyze_likert(*q, settings);
}

void likert_report_to_file(const std::string& path, const LikertSettings& settings,
                           const std::string& output_path, OutputFormat format) {
  const auto analysis = analyze_likert_file(path, settings);
  const std::string text = render_likert(analysis, format);
  io::AtomicOutput out(output_path);
  out.stream() << text;
  out.commit();
}

}  // namespace feint::tables
