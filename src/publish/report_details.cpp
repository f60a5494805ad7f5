// The parts of the study report that must agree with the rest of it (see report_details.hpp).
#include "report_details.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <map>
#include <set>

#include "feint/io/html_escape.hpp"
#include "feint/plot/html.hpp"
#include "feint/tables/table1.hpp"
#include "feint/tables/writers.hpp"

namespace feint::publish::detail {

namespace {

std::string mean_text(const std::optional<double>& v) { return v ? fmt::format("{:.4f}", *v) : ""; }

// The APA string of a row ("t(57.07) = 1.49, p = .143, d = 0.38 [-0.13, 0.89], BF₀₁ = 1.52"), or
// why there is none.
std::string statistics_of(const tables::TidyRow& row) {
  if (!row.result.computed) return "not computable: " + row.result.note;
  return tables::apa_string(row.result);
}

std::string folded(const std::string& summary, const std::string& markdown) {
  return fmt::format("<details class=\"tests\">\n<summary>{}</summary>\n{}</details>\n",
                     io::html_escape(summary), plot::markdown_to_html(markdown));
}

}  // namespace

std::string tests_html(const tables::Table1& t, bool comparison) {
  std::string md = comparison ? "| Metric | Iteration | Mean A | Mean B | Test of A \u2212 B |\n|---|---:|---:|---:|---|\n"
                              : "| Metric | Iteration | Condition | Mean | Test against the reference |\n|---|---:|---|---:|---|\n";
  std::size_t n = 0;
  for (const auto& row : t.rows) {
    if (row.result.test == "tost") continue;  // the equivalence rows have their own columns
    const std::string it = row.iteration ? std::to_string(*row.iteration) : "";
    if (comparison)
      md += fmt::format("| {} | {} | {} | {} | {} |\n", row.metric, it, mean_text(row.result.mean1),
                        mean_text(row.result.mean2), statistics_of(row));
    else
      md += fmt::format("| {} | {} | {} | {} | {} |\n", row.metric, it, row.group1.empty() ? "all" : row.group1,
                        mean_text(row.result.mean1), statistics_of(row));
    ++n;
  }
  return folded(fmt::format("Every test of this table in APA style: t, df, p, d with its CI, and the Bayes "
                            "factor ({} tests)", n),
                md);
}

std::string likert_tests_html(const tables::LikertAnalysis& l) {
  std::string md = "| Item | Groups | Test | Statistics (effect size with its CI) |\n|---|---|---|---|\n";
  for (const auto& row : l.rows) {
    const std::string groups = row.group2.empty() ? (row.group1.empty() ? "all" : row.group1)
                                                  : row.group1 + " vs " + row.group2;
    md += fmt::format("| {} | {} | {} | {} |\n", row.metric, groups, row.result.method, statistics_of(row));
  }
  return folded(fmt::format("Every test of this table with its effect size: rank-biserial r with its CI for "
                            "the rank test, d with its CI and the Bayes factor for the t test ({} tests)",
                            l.rows.size()),
                md);
}

std::string references_text(const analysis::StudyResults& r) {
  const std::string scores = tables::scores_scale(r.table1.provenance);
  std::vector<std::string> out;
  for (const auto& m : r.table1.options.metrics) {
    std::string s = fmt::format("{} against {:g}", m.column, m.reference);
    if (m.column == "confusion") {
      const std::string scale = m.scale.empty() ? scores : m.scale;
      s += scale.empty() ? " on the scores' scale (not recorded)" : " on the " + scale + " scale";
    }
    out.push_back(std::move(s));
  }
  return fmt::format("{}", fmt::join(out, "; "));
}

std::string reference_check_line(const analysis::StudyResults& r) {
  const std::string scores = tables::scores_scale(r.table1.provenance);
  std::vector<std::string> refs;
  for (const auto& m : r.table1.options.metrics) {
    if (m.column != "confusion") {
      refs.push_back(fmt::format("{} against {:g} ({} has one scale)", m.column, m.reference, m.column));
      continue;
    }
    const std::string scale = m.scale.empty() ? scores : m.scale;
    refs.push_back(fmt::format("{} against {:g} on the {} scale{}", m.column, m.reference,
                               scale.empty() ? "scores'" : scale,
                               m.scale.empty() ? " (the reference names no scale: taken as the scores')" : ""));
  }
  const std::string checked =
      scores.empty() ? "the scores' confusion scale is not recorded, so it could not be checked"
                     : fmt::format("the scores' confusion is on the {} scale, the same as each reference's", scores);
  return fmt::format("Reference check: {}; {}.", fmt::join(refs, "; "), checked);
}

std::vector<std::string> left_out_lines(const analysis::StudyResults& r) {
  std::vector<std::string> out;
  std::set<std::string> seen;
  for (const auto& f : r.findings)
    for (const auto& w : f.warnings)
      if ((w.find("left out") != std::string::npos || w.find("dropped") != std::string::npos) &&
          seen.insert(w).second)
        out.push_back("analysis: " + w);
  return out;
}

std::size_t other_warned_findings(const analysis::StudyResults& r) {
  std::size_t n = 0;
  for (const auto& f : r.findings)
    n += std::any_of(f.warnings.begin(), f.warnings.end(), [&](const std::string& w) {
      return w != f.sentence && w.find("left out") == std::string::npos && w.find("dropped") == std::string::npos;
    });
  return n;
}

bool paper_design(const analysis::StudyResults& r) {
  if (!r.comparison || r.scores.conditions().size() != 2) return false;
  std::map<std::string, std::string> condition_of;
  for (const auto& rec : r.scores.records) {
    const auto [it, added] = condition_of.emplace(rec.participant, rec.condition);
    if (!added && it->second != rec.condition) return false;  // within participants
  }
  const auto its = r.scores.iterations();
  return its.size() == 20 && its.front() == 1 && its.back() == 20;
}

std::string name_singular_notes(std::string text, const tables::ModelAnalysis& model) {
  static const std::string kNote = "Singular fit: ";
  std::size_t at = 0;
  for (const auto& m : model.models) {
    if (!m.fit.singular) continue;
    at = text.find(kNote, at);
    if (at == std::string::npos) break;
    const std::string named = fmt::format("Singular fit of the {} model: ", m.metric);
    text.replace(at, kNote.size(), named);
    at += named.size();
  }
  return text;
}

}  // namespace feint::publish::detail
