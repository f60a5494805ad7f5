// The findings engine: see feint/analysis/findings.hpp and docs/findings.md (the wording rules).
#include "feint/analysis/findings.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "feint/tables/writers.hpp"
#include "feint/stats/p_adjust.hpp"

namespace feint::analysis {

std::string to_string(Strength s) {
  switch (s) {
    case Strength::evidence_for_difference: return "evidence for a difference";
    case Strength::no_evidence_either_way: return "no evidence either way";
    case Strength::evidence_for_no_difference: return "evidence for no difference";
    case Strength::not_computable: break;
  }
  return "not computable";
}

std::string to_string(Grade g) {
  switch (g) {
    case Grade::moderate: return "moderate";
    case Grade::strong: return "strong";
    case Grade::none: break;
  }
  return "";
}

namespace {

std::string evidence_text(Strength s, Grade g) {
  const std::string grade = to_string(g);
  return grade.empty() ? to_string(s) : grade + " " + to_string(s);
}

Grade grade_of(double bf, const WordingRules& rules) {
  if (bf >= rules.bf_strong) return Grade::strong;
  if (bf >= rules.bf_moderate) return Grade::moderate;
  return Grade::none;
}

std::string capitalised(std::string s) {
  if (!s.empty() && s[0] >= 'a' && s[0] <= 'z') s[0] = static_cast<char>(s[0] - 'a' + 'A');
  return s;
}

std::string number(double v) { return fmt::format("{:.2f}", v); }

// "[0.01, 0.05]"; a one-sided interval as R gives it, open at its infinite end: "[0.01, ∞)".
std::string interval_text(double low, double high) {
  const std::string lo = std::isinf(low) ? "(\u2212\u221e" : "[" + number(low);
  const std::string hi = std::isinf(high) ? "\u221e)" : number(high) + "]";
  return lo + ", " + hi;
}

}  // namespace

Strength classify(const stats::TestResult& d, const stats::TestResult* tost, const WordingRules& rules,
                  Grade* grade) {
  if (grade) *grade = Grade::none;
  if (!d.computed || !d.p_value) return Strength::not_computable;
  const double p = d.p_adjusted.value_or(*d.p_value);
  const bool tost_equivalent = tost && tost->computed && tost->p_value &&
                               tost->p_adjusted.value_or(*tost->p_value) < rules.alpha;
  if (d.log_bf10) {
    const double bf10 = std::exp(*d.log_bf10), bf01 = std::exp(-*d.log_bf10);
    if (bf10 >= rules.bf_moderate && p < rules.alpha) {
      if (grade) *grade = grade_of(bf10, rules);
      return Strength::evidence_for_difference;
    }
    if (bf01 >= rules.bf_moderate) {
      if (grade) *grade = grade_of(bf01, rules);
      return Strength::evidence_for_no_difference;
    }
    if (tost_equivalent) return Strength::evidence_for_no_difference;
    return Strength::no_evidence_either_way;
  }
  // No Bayes factor (rank tests, model terms): the interval must exclude the null at the corrected
  // level; "no difference" only from TOST.
  if (p < rules.alpha) return Strength::evidence_for_difference;
  if (tost_equivalent) return Strength::evidence_for_no_difference;
  return Strength::no_evidence_either_way;
}

namespace {

std::string test_name(const stats::TestResult& d) {
  static const std::pair<const char*, const char*> names[] = {
      {"one_sample_t", "one-sample t test"}, {"welch_t", "Welch t test"},
      {"student_t", "Student t test"},       {"paired_t", "paired t test"},
      {"wilcoxon_signed_rank", "Wilcoxon signed-rank test"},
      {"mann_whitney", "Mann-Whitney test"}, {"anova", "F test"}, {"welch_anova", "Welch F test"},
      {"kruskal_wallis", "Kruskal-Wallis test"}};
  for (const auto& [id, name] : names)
    if (d.test == id) return name;
  return d.method.empty() ? d.test : d.method;
}

bool one_sample(const stats::TestResult& d) {
  return d.test == "one_sample_t" || d.test == "wilcoxon_signed_rank";
}

std::optional<EffectSize> effect_size_of(const stats::TestResult& d) {
  if (d.cohen_d && std::isfinite(*d.cohen_d))
    return EffectSize{d.test == "paired_t" ? "d_z" : "d", *d.cohen_d, d.cohen_d_low, d.cohen_d_high};
  if (d.rank_biserial && std::isfinite(*d.rank_biserial))
    return EffectSize{"r_rb", *d.rank_biserial, d.rank_biserial_low, d.rank_biserial_high};
  if (d.rank_epsilon_squared && std::isfinite(*d.rank_epsilon_squared))
    return EffectSize{"epsilon2_rank", *d.rank_epsilon_squared, std::nullopt, std::nullopt};
  if (d.r_squared && std::isfinite(*d.r_squared))
    return EffectSize{"eta2_p", *d.r_squared, d.eta_squared_low, d.eta_squared_high};
  return std::nullopt;
}

}  // namespace

void set_test_fields(Finding& f, const stats::TestResult& d, std::string_view lhs,
                     std::string_view rhs) {
  f.test = test_name(d);
  f.alternative = d.alternative;
  if (d.alternative != stats::Alternative::two_sided) f.test = "one-sided " + f.test;
  f.conf_level = d.conf_level;
  f.p = d.p_value;
  f.p_adjusted = d.p_adjusted;
  f.effect_size = effect_size_of(d);
  // A one-sample estimate is a mean: its difference is from the reference.
  const double shift = one_sample(d) ? d.mu.value_or(0.0) : 0.0;
  if (d.mean1 && d.mean2) f.means = {{*d.mean1, *d.mean2}};
  else if (d.mean1 && d.mu && one_sample(d)) f.means = {{*d.mean1, *d.mu}};
  if (f.contrast.empty()) f.contrast = fmt::format("{} - {}", lhs, rhs);
  if (d.estimate && std::isfinite(*d.estimate)) {
    f.estimate = *d.estimate - shift;
    if (d.conf_low && d.conf_high) {
      f.ci_low = *d.conf_low - shift;
      f.ci_high = *d.conf_high - shift;
    }
  } else if (d.rank_biserial) {
    f.estimate.reset();
  }
  const double lean = f.estimate ? *f.estimate : d.rank_biserial.value_or(0.0);
  if (f.estimate || d.rank_biserial)
    f.direction = fmt::format("{} {} {}", lhs, lean > 0 ? ">" : lean < 0 ? "<" : "=", rhs);
  if (d.log_bf10) {
    f.bf10 = std::exp(*d.log_bf10);
    if (!std::isfinite(*f.bf10)) {
      f.bf10.reset();
      f.bf_note = fmt::format("BF10 exceeds the largest double; ln BF10 = {:.1f}", *d.log_bf10);
    }
  } else if (f.bf_note.empty()) {
    f.bf_note = d.test == "mann_whitney" || d.test == "wilcoxon_signed_rank" || d.test == "kruskal_wallis"
                    ? "a rank test has no JZS Bayes factor; see the t test beside it"
                    : "no Bayes factor for this test";
  }
}

namespace {

// The sides of a test for its direction: "M"/"R" style names are replaced by the caller's.
std::pair<std::string, std::string> sides_of(const stats::TestResult& d) {
  if (one_sample(d)) return {"mean", fmt::format("{:g}", d.mu.value_or(0.0))};
  return {"A", "B"};
}

}  // namespace

Finding difference_finding(std::string id, std::string hypothesis, std::string question,
                           std::string what, const stats::TestResult& d,
                           const stats::TestResult* tost, std::string source,
                           const WordingRules& rules) {
  Finding f;
  f.id = std::move(id);
  f.hypothesis = std::move(hypothesis);
  f.question = std::move(question);
  f.source = std::move(source);
  f.strength = classify(d, tost, rules, &f.grade);
  f.evidence = evidence_text(f.strength, f.grade);
  const auto [lhs, rhs] = sides_of(d);
  set_test_fields(f, d, lhs, rhs);
  if (f.strength == Strength::not_computable) {
    f.sentence = fmt::format("{}: not computable ({}).", capitalised(what),
                             d.note.empty() ? std::string("no test result") : d.note);
    return f;
  }
  f.statistics = tables::apa_string(d);
  std::string means;
  if (one_sample(d) && d.mean1 && d.mu)
    means = fmt::format("M = {} against R = {}", number(*d.mean1), number(*d.mu));
  else if (d.mean1 && d.mean2)
    means = fmt::format("M = {} vs {}", number(*d.mean1), number(*d.mean2));
  std::string ci;
  if (f.estimate && f.ci_low && f.ci_high && !std::isnan(*f.ci_low) && !std::isnan(*f.ci_high))
    ci = fmt::format("difference {}, {:.0f}% CI {}", number(*f.estimate), 100 * d.conf_level,
                     interval_text(*f.ci_low, *f.ci_high));
  std::string basis;
  if (f.strength == Strength::evidence_for_no_difference && !(d.log_bf10 && std::exp(-*d.log_bf10) >= rules.bf_moderate))
    basis = fmt::format("; equivalent within \u00b1{:g} by TOST", rules.equivalence_margin.value_or(tost && tost->margin ? *tost->margin : 0));
  f.sentence = fmt::format("{}: {} ({}{}{}{}{}).", capitalised(what), f.evidence, means,
                           means.empty() || ci.empty() ? "" : "; ", ci,
                           (means.empty() && ci.empty()) ? f.statistics : "; " + f.statistics, basis);
  return f;
}

Finding family_finding(std::string id, std::string hypothesis, std::string question, std::string what,
                       std::vector<stats::TestResult> tests, std::string source, const WordingRules& rules,
                       std::string correction) {
  Finding f;
  f.id = std::move(id);
  f.hypothesis = std::move(hypothesis);
  f.question = std::move(question);
  f.source = std::move(source);
  // Holm within the family, unless the caller already adjusted.
  const bool adjusted = std::any_of(tests.begin(), tests.end(), [](const auto& t) { return t.p_adjusted.has_value(); });
  if (!adjusted) {
    std::vector<std::optional<double>> p;
    for (const auto& t : tests) p.push_back(t.computed ? t.p_value : std::nullopt);
    const auto adj = stats::p_adjust(p, stats::PAdjustMethod::holm);
    for (std::size_t i = 0; i < tests.size(); ++i) tests[i].p_adjusted = adj[i];
  }
  std::vector<std::size_t> diff, none_diff, neither, missing;
  Grade best = Grade::none;
  for (std::size_t i = 0; i < tests.size(); ++i) {
    Grade g = Grade::none;
    switch (classify(tests[i], nullptr, rules, &g)) {
      case Strength::evidence_for_difference:
        diff.push_back(i);
        if (g > best) best = g;
        break;
      case Strength::evidence_for_no_difference: none_diff.push_back(i); break;
      case Strength::no_evidence_either_way: neither.push_back(i); break;
      case Strength::not_computable: missing.push_back(i); break;
    }
  }
  const std::size_t computed = tests.size() - missing.size();
  if (computed == 0) {
    f.strength = Strength::not_computable;
    f.evidence = to_string(f.strength);
    f.sentence = fmt::format("{}: not computable in any of the {} tests ({}).", capitalised(what),
                             tests.size(), tests.empty() ? "no tests" : tests.front().note);
    return f;
  }
  if (!diff.empty()) {
    f.strength = Strength::evidence_for_difference;
    f.grade = best;
  } else if (none_diff.size() == computed) {
    f.strength = Strength::evidence_for_no_difference;
  } else {
    f.strength = Strength::no_evidence_either_way;
  }
  f.evidence = evidence_text(f.strength, f.grade);
  auto list = [&](const std::vector<std::size_t>& idx) {
    std::string s;
    for (std::size_t k = 0; k < idx.size(); ++k) s += (k ? ", " : "") + std::to_string(idx[k] + 1);
    return s;
  };
  if (correction.empty()) correction = fmt::format("Holm-corrected over {} tests", tests.size());
  f.sentence = fmt::format("{} ({}): {}; evidence for a difference in {} ({}), "
                           "for no difference in {}, neither in {}",
                           capitalised(what), correction, f.evidence, diff.size(),
                           diff.empty() ? std::string("none") : "tests " + list(diff), none_diff.size(),
                           neither.size());
  if (!missing.empty()) f.sentence += fmt::format(", not computable in {} (tests {})", missing.size(), list(missing));
  std::size_t smallest = tests.size();
  for (std::size_t i = 0; i < tests.size(); ++i)
    if (tests[i].computed && tests[i].p_adjusted &&
        (smallest == tests.size() || *tests[i].p_adjusted < *tests[smallest].p_adjusted))
      smallest = i;
  if (smallest < tests.size())
    f.sentence += fmt::format("; smallest adjusted {} (test {})", tables::apa_p(*tests[smallest].p_adjusted), smallest + 1);
  f.sentence += ".";
  if (!diff.empty()) f.statistics = tables::apa_string(tests[diff.front()]);
  if (smallest < tests.size()) {
    const auto [lhs, rhs] = sides_of(tests[smallest]);
    set_test_fields(f, tests[smallest], lhs, rhs);
    f.member = fmt::format("test {}", smallest + 1);
  }
  return f;
}

std::vector<Finding> exposure_findings(const models::ExposureByCondition& e, const WordingRules& rules,
                                       std::string source, const std::string& metric) {
  std::vector<Finding> out;
  const std::string question =
      metric.empty() ? std::string("Does a strategy wear off with exposure differently under the two conditions?")
                     : fmt::format("Does a strategy's effect on {} wear off with exposure differently under the "
                                   "two conditions?", metric);
  const std::string id_prefix = metric.empty() ? std::string("H1-exposure") : "H1-exposure-" + metric;
  const std::string of_metric = metric.empty() ? std::string() : " (" + metric + ")";
  if (e.differences.empty()) {
    out.push_back(one_condition_only(id_prefix, "H1", question,
                                     e.slopes.empty() ? std::string("none") : e.slopes.front().condition,
                                     source));
    return out;
  }
  std::vector<std::optional<double>> p;
  for (const auto& d : e.differences) p.push_back(d.test.computed ? d.test.p_value : std::nullopt);
  const auto adj = stats::p_adjust(p, stats::PAdjustMethod::holm);
  const std::size_t k = e.differences.size();
  for (std::size_t i = 0; i < k; ++i) {
    stats::TestResult d = e.differences[i].test;
    d.p_adjusted = adj[i];
    const auto& a = e.slopes[i];
    const auto& b = e.slopes[k + i];
    Finding f;
    f.id = id_prefix + "-" + e.differences[i].strategy;
    f.hypothesis = "H1";
    f.question = question;
    f.source = source;
    f.strength = classify(d, nullptr, rules, &f.grade);
    f.evidence = evidence_text(f.strength, f.grade);
    f.measure = metric;
    set_test_fields(f, d, a.condition + " slope", b.condition + " slope");
    auto slope_text = [](const models::ExposureSlope& s) {
      if (!s.test.computed || !s.test.estimate) return fmt::format("{}: not computable", s.condition);
      return fmt::format("{}: {:.3f} per exposure, {:g}% CI [{:.3f}, {:.3f}], n = {}", s.condition,
                         *s.test.estimate, 100 * s.test.conf_level, *s.test.conf_low, *s.test.conf_high,
                         s.participants);
    };
    if (f.strength == Strength::not_computable) {
      f.sentence = fmt::format("Exposure slope{} of strategy '{}' by condition: not computable ({}).",
                               of_metric, e.differences[i].strategy, d.note);
    } else {
      // A Welch t test with its Bayes factor: classify() above applied the same rules as to every
      // other Welch test, and apa_string() writes the same statistics (adjusted p, d, BF).
      f.statistics = tables::apa_string(d);
      f.sentence = fmt::format(
          "Exposure slope{} of strategy '{}' ({}; {}): {} between the conditions (difference {:.3f}, "
          "{:g}% CI [{:.3f}, {:.3f}]; {}; Holm-corrected over {} strategies).",
          of_metric, e.differences[i].strategy, slope_text(a), slope_text(b), f.evidence, *d.estimate,
          100 * d.conf_level, *d.conf_low, *d.conf_high, f.statistics, k);
    }
    out.push_back(std::move(f));
  }
  return out;
}

ReferenceCheck check_reference(const std::string& metric, double reference,
                               std::span<const std::vector<double>> values) {
  ReferenceCheck c;
  c.min = std::numeric_limits<double>::infinity();
  c.max = -c.min;
  for (const auto& it : values)
    for (double v : it)
      if (!std::isnan(v)) c.min = std::min(c.min, v), c.max = std::max(c.max, v);
  if (!(c.min <= c.max)) return c;  // no data: nothing to say here
  if (reference > c.max || reference < c.min) {
    c.outside = true;
    c.above = reference > c.max;
    c.warning = fmt::format(
        "The reference {} = {:g} lies {} every participant's score in every iteration (range {:g} to "
        "{:g}): a one-sample test against it only restates that fact.",
        metric, reference, c.above ? "above" : "below", c.min, c.max);
  }
  return c;
}

Finding one_condition_only(std::string id, std::string hypothesis, std::string question,
                           const std::string& condition, std::string source) {
  Finding f;
  f.id = std::move(id);
  f.hypothesis = std::move(hypothesis);
  f.question = std::move(question);
  f.source = std::move(source);
  f.strength = Strength::not_computable;
  f.evidence = to_string(f.strength);
  f.sentence = fmt::format("Only one condition ('{}') is in the data: there is no comparison between "
                           "conditions, so this question cannot be answered.", condition);
  return f;
}

Finding questionnaire_without_log(std::string id, std::span<const std::string> participants) {
  Finding f;
  f.id = std::move(id);
  f.hypothesis = "H2";
  f.question = "Do questionnaire answers belong to logged participants?";
  f.source = "questionnaire";
  f.strength = Strength::not_computable;
  f.evidence = to_string(f.strength);
  std::string names;
  for (std::size_t i = 0; i < participants.size() && i < 10; ++i) names += (i ? ", " : "") + participants[i];
  if (participants.size() > 10) names += fmt::format(" and {} more", participants.size() - 10);
  f.sentence = fmt::format("{} questionnaire{} without a matching log ({}): their answers have no "
                           "condition and are left out of the comparison between conditions.",
                           participants.size(), participants.size() == 1 ? "" : "s", names);
  f.warnings.push_back(f.sentence);
  return f;
}

// ------------------------------------------------------------------------------------------------
// Renderers

namespace {

std::string html_escape(std::string_view s) {
  std::string o;
  for (char c : s) {
    switch (c) {
      case '&': o += "&amp;"; break;
      case '<': o += "&lt;"; break;
      case '>': o += "&gt;"; break;
      case '"': o += "&quot;"; break;
      default: o += c;
    }
  }
  return o;
}

std::string json_string(std::string_view s) {
  std::string o = "\"";
  for (char c : s) {
    switch (c) {
      case '"': o += "\\\""; break;
      case '\\': o += "\\\\"; break;
      case '\n': o += "\\n"; break;
      case '\t': o += "\\t"; break;
      default:
        if (static_cast<unsigned char>(c) < 0x20) o += fmt::format("\\u{:04x}", static_cast<int>(c));
        else o += c;
    }
  }
  return o + "\"";
}

std::string strength_key(Strength s) {
  switch (s) {
    case Strength::evidence_for_difference: return "difference";
    case Strength::no_evidence_either_way: return "inconclusive";
    case Strength::evidence_for_no_difference: return "no-difference";
    case Strength::not_computable: break;
  }
  return "not-computable";
}

}  // namespace

std::string findings_markdown(std::span<const Finding> findings) {
  std::string o;
  for (const auto& f : findings) {
    o += fmt::format("- **{}** ({}). {}", capitalised(f.evidence), f.hypothesis, f.sentence);
    if (!f.source.empty()) o += fmt::format(" [{}](#{})", f.source, f.source);
    o += "\n";
    for (const auto& w : f.warnings)
      if (w != f.sentence) o += "  - Warning: " + w + "\n";
  }
  return o;
}

std::string findings_html(std::span<const Finding> findings) {
  std::string o = "<ul class=\"findings\">\n";
  for (const auto& f : findings) {
    o += fmt::format("<li class=\"finding {}\" id=\"finding-{}\"><strong>{}</strong> ({}). {}",
                     strength_key(f.strength), html_escape(f.id), html_escape(capitalised(f.evidence)),
                     html_escape(f.hypothesis), html_escape(f.sentence));
    if (!f.source.empty()) o += fmt::format(" <a href=\"#{}\">{}</a>", html_escape(f.source), html_escape(f.source));
    for (const auto& w : f.warnings)
      if (w != f.sentence) o += "<br><span class=\"warning\">" + html_escape(w) + "</span>";
    o += "</li>\n";
  }
  return o + "</ul>\n";
}

namespace {

std::string json_number(const std::optional<double>& v) {
  return v && std::isfinite(*v) ? fmt::format("{}", *v) : "null";
}

// The structured fields (docs/findings.md "Fields"), as JSON members after the sentence's.
std::string json_fields(const Finding& f) {
  std::string es = "null";
  if (f.effect_size)
    es = fmt::format("{{\"name\": {}, \"value\": {}, \"ci_low\": {}, \"ci_high\": {}}}",
                     json_string(f.effect_size->name), json_number(f.effect_size->value),
                     json_number(f.effect_size->ci_low), json_number(f.effect_size->ci_high));
  return fmt::format(
      ", \"measure\": {}, \"contrast\": {}, \"direction\": {}, \"mean_a\": {}, \"mean_b\": {}, "
      "\"estimate\": {}, \"ci_low\": {}, \"ci_high\": {}, \"conf_level\": {}, \"effect_size\": {}, "
      "\"test\": {}, \"p\": {}, \"p_adjusted\": {}, \"bf10\": {}, \"bf_note\": {}, "
      "\"confirmatory\": {}, \"member\": {}, \"alternative\": {}",
      json_string(f.measure), json_string(f.contrast), json_string(f.direction),
      json_number(f.means ? std::optional<double>(f.means->first) : std::nullopt),
      json_number(f.means ? std::optional<double>(f.means->second) : std::nullopt), json_number(f.estimate),
      json_number(f.ci_low), json_number(f.ci_high), json_number(f.conf_level), es, json_string(f.test),
      json_number(f.p), json_number(f.p_adjusted), json_number(f.bf10), json_string(f.bf_note),
      f.confirmatory ? "true" : "false", json_string(f.member),
      json_string(stats::to_string(f.alternative)));
}

}  // namespace

std::string findings_json(std::span<const Finding> findings) {
  std::string o = "[";
  for (std::size_t i = 0; i < findings.size(); ++i) {
    const auto& f = findings[i];
    std::string warnings = "[";
    for (std::size_t k = 0; k < f.warnings.size(); ++k) warnings += (k ? ", " : "") + json_string(f.warnings[k]);
    warnings += "]";
    o += fmt::format(
        "{}\n  {{\"id\": {}, \"hypothesis\": {}, \"question\": {}, \"sentence\": {}, \"evidence\": {}, "
        "\"strength\": {}, \"grade\": {}, \"statistics\": {}, \"source\": {}, \"warnings\": {}{}}}",
        i ? "," : "", json_string(f.id), json_string(f.hypothesis), json_string(f.question),
        json_string(f.sentence), json_string(f.evidence), json_string(to_string(f.strength)),
        json_string(to_string(f.grade)), json_string(f.statistics), json_string(f.source), warnings,
        json_fields(f));
  }
  return o + (findings.empty() ? "]\n" : "\n]\n");
}

std::string findings_text(std::span<const Finding> findings) {
  std::string o = "Findings\n";
  for (const auto& f : findings) {
    o += fmt::format("* [{}] {}: {}\n", f.hypothesis, capitalised(f.evidence), f.sentence);
    for (const auto& w : f.warnings)
      if (w != f.sentence) o += "  warning: " + w + "\n";
  }
  return o;
}

}  // namespace feint::analysis
