// study_findings(): see feint/analysis/study_findings.hpp.
#include "feint/analysis/study_findings.hpp"

#include <cmath>
#include <map>

#include <fmt/format.h>

namespace feint::analysis {

namespace {

bool is_t_test(const std::string& test) {
  return test == "one_sample_t" || test == "welch_t" || test == "student_t" || test == "paired_t";
}

}  // namespace

std::vector<Finding> study_findings(const StudyResults& r, const std::vector<report::MetricSpec>& metrics,
                                    const WordingRules& rules) {
  std::vector<Finding> out;
  const auto conditions = r.scores.conditions();
  for (const auto& m : metrics) {
    const std::string question =
        fmt::format("Does {} differ between the conditions, iteration by iteration?", m.column);
    if (r.comparison) {
      std::vector<stats::TestResult> tests;
      std::string g1, g2;
      for (const auto& row : r.comparison->rows) {
        if (row.metric != m.column || !is_t_test(row.result.test)) continue;
        tests.push_back(row.result);
        g1 = row.group1;
        g2 = row.group2;
      }
      if (!tests.empty()) {
        out.push_back(family_finding("H1-iterations-" + m.column, "H1", question,
                                     fmt::format("per-iteration contrasts of {}, {} vs {}", m.column, g1, g2),
                                     std::move(tests), "comparison", rules));
      }
    } else if (conditions.size() < 2) {
      out.push_back(one_condition_only("H1-iterations-" + m.column, "H1", question,
                                       conditions.empty() ? std::string() : conditions.front(), "table1"));
    }
    // Reference plausibility over every participant and iteration.
    const int k = r.scores.metric_index(m.column);
    if (k < 0) continue;
    std::map<long long, std::vector<double>> per_iteration;
    for (const auto& rec : r.scores.records) {
      const auto& v = rec.values[static_cast<std::size_t>(k)];
      per_iteration[rec.iteration].push_back(v ? *v : std::nan(""));
    }
    std::vector<std::vector<double>> values;
    for (auto& [it, v] : per_iteration) values.push_back(std::move(v));
    const ReferenceCheck c = check_reference(m.column, m.reference, values);
    if (c.outside) {
      Finding f;
      f.id = "reference-" + m.column;
      f.hypothesis = "H1";
      f.question = fmt::format("Is the reference {} = {:g} a plausible value of the metric?", m.column, m.reference);
      f.sentence = c.warning;
      f.evidence = "reference outside the data";
      f.strength = Strength::not_computable;
      f.source = "table1";
      f.warnings.push_back(c.warning);
      out.push_back(std::move(f));
    }
  }
  // H2: the questionnaire.
  auto likert = [&](const std::optional<report::LikertAnalysis>& a, bool between) {
    if (!a) return;
    for (const auto& row : a->rows) {
      if (!is_t_test(row.result.test)) continue;
      const std::string what =
          between ? fmt::format("{}: {} vs {}", row.metric, row.group1, row.group2)
                  : fmt::format("{}{} against the reference", row.metric,
                                row.group1.empty() ? std::string() : " (" + row.group1 + ")");
      out.push_back(difference_finding(
          fmt::format("H2-{}-{}{}", between ? "compare" : "reference", row.metric,
                      row.group1.empty() || between ? std::string() : "-" + row.group1),
          "H2",
          between ? fmt::format("Do the conditions differ on {}?", row.metric)
                  : fmt::format("Does {} differ from the reference?", row.metric),
          what, row.result, nullptr, between ? "questionnaire-compare" : "questionnaire", rules));
    }
  };
  likert(r.likert, false);
  likert(r.likert_compare, true);
  return out;
}

}  // namespace feint::analysis
