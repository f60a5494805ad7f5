// report.html, report.md and results.json of a study (see feint/publish/study_report.hpp).
#include "feint/publish/study_report.hpp"

#include <fmt/format.h>

#include <filesystem>

#include "feint/io/html_escape.hpp"
#include "feint/io/number.hpp"
#include "feint/io/output.hpp"
#include "feint/plot/canvas.hpp"
#include "feint/plot/html.hpp"
#include "feint/publish/results_text.hpp"
#include "feint/tables/writers.hpp"
#include "report_details.hpp"

namespace feint::publish {

namespace {

// The Reproduce line names a folder outside every folder the report shares with its study as
// PATH_TO/NAME (commands::quoted_command_line): say what to put there.
std::string placeholder_note(const std::string& command_line) {
  return command_line.find("PATH_TO/") == std::string::npos
             ? ""
             : "; PATH_TO stands for where that folder is on your machine";
}

namespace fs = std::filesystem;
using io::html_escape;
using tables::OutputFormat;

// A table of the report: its anchor, heading, Markdown and CSV renderings, and its files' stem.
struct ReportTable {
  std::string id, heading, stem, markdown, csv;
  std::string tests_html = {};  // the tests' statistics under the paper-shaped table (HTML)
};

std::vector<ReportTable> tables(const analysis::StudyResults& r) {
  std::vector<ReportTable> t;
  auto add = [&](std::string id, std::string heading, std::string stem, auto&& render) {
    t.push_back({std::move(id), std::move(heading), std::move(stem), render(OutputFormat::markdown),
                 render(OutputFormat::csv)});
  };
  add("table1", "Table 1 per condition", "table1",
      [&](OutputFormat f) { return tables::render_table1(r.table1, f); });
  if (r.comparison) {
    add("comparison", "Comparison", "table1_compare",
        [&](OutputFormat f) { return tables::render_table1(*r.comparison, f); });
  }
  if (r.anova) {
    add("anova", "Mixed ANOVA", "anova", [&](OutputFormat f) {
      return tables::render_anova(*r.anova, f, r.table1.options.apa);
    });
  }
  // The models' "Singular fit" notes name their metric (a boundary note about one model).
  if (r.model) {
    add("model", "Mixed model (condition x iteration)", "model", [&](OutputFormat f) {
      return detail::name_singular_notes(tables::render_model(*r.model, f), *r.model);
    });
  }
  if (r.trend_model) {
    add("model-trend", "Mixed model (linear trend over the iterations)", "model_trend", [&](OutputFormat f) {
      return detail::name_singular_notes(tables::render_model(*r.trend_model, f), *r.trend_model);
    });
  }
  if (!r.exposure.empty()) {
    add("exposure", "Condition \u00d7 exposure per strategy", "exposure_by_condition",
        [&](OutputFormat f) { return tables::render_exposure(r.exposure, f); });
  }
  if (r.likert) {
    add("questionnaire", "Questionnaire", "likert",
        [&](OutputFormat f) { return tables::render_likert(*r.likert, f); });
  }
  if (r.likert_compare) {
    add("questionnaire-compare",
        r.likert_compare->paired ? "Questionnaire within participants" : "Questionnaire between the conditions",
        "likert_compare",
        [&](OutputFormat f) { return tables::render_likert(*r.likert_compare, f); });
  }
  if (r.likert_conditions) {
    add("questionnaire-conditions", "Questionnaire across the conditions", "likert_conditions",
        [&](OutputFormat f) { return tables::render_likert_conditions(*r.likert_conditions, f); });
  }
  if (r.yes_no) {
    add("yes-no",
        r.yes_no->rows.empty()         ? "Yes/no questions"
        : r.yes_no->settings.paired ? "Yes/no questions within participants"
                                    : "Yes/no questions between the conditions",
        "yes_no",
        [&](OutputFormat f) { return tables::render_yes_no(*r.yes_no, f); });
  }
  // The paper-shaped tables show M, p and the label; t, df, d [CI] and BF (the CSV's) go under them.
  for (auto& x : t) {
    if (x.stem == "table1") x.tests_html = detail::tests_html(r.table1, false);
    if (x.stem == "table1_compare") x.tests_html = detail::tests_html(*r.comparison, true);
    if (x.stem == "likert") x.tests_html = detail::likert_tests_html(*r.likert);
    if (x.stem == "likert_compare") x.tests_html = detail::likert_tests_html(*r.likert_compare);
  }
  return t;
}

std::string percent_encoded(const std::string& s) {
  std::string o;
  for (const unsigned char c : s) {
    if (std::isalnum(c) || c == '-' || c == '_' || c == '.' || c == '~' || c == ',') {
      o += static_cast<char>(c);
    } else {
      o += fmt::format("%{:02X}", c);
    }
  }
  return o;
}

std::string csv_link(const ReportTable& t, bool beside) {
  const std::string href = beside ? t.stem + ".csv"
                                  : "data:text/csv;charset=utf-8," + percent_encoded(t.csv);
  return fmt::format("<p class=\"download\"><a href=\"{}\" download=\"{}.csv\">Download this "
                     "table as CSV ({}.csv)</a></p>\n",
                     html_escape(href), html_escape(t.stem), html_escape(t.stem));
}

std::string facts(const std::vector<std::pair<std::string, std::string>>& rows) {
  std::string o = "<dl class=\"facts\">\n";
  for (const auto& [k, v] : rows) {
    o += fmt::format("<dt>{}</dt><dd>{}</dd>\n", html_escape(k), html_escape(v));
  }
  return o + "</dl>\n";
}

std::vector<std::pair<std::string, std::string>> design_rows(const analysis::StudyResults& r,
                                                             const ReportContext& c) {
  std::vector<std::string> per_condition;
  for (const auto& [cond, n] : r.diagnostics.participants_per_condition) {
    per_condition.push_back(
        fmt::format("{} ({})", cond.empty() ? "(none)" : cond, count(n, "participant")));
  }
  const auto its = r.scores.iterations();
  const auto conditions = r.scores.conditions();
  return {
      {"Study folder", c.study_folder},
      {"Conditions", fmt::format("{}", fmt::join(per_condition, ", "))},
      {"Design", r.design.note.empty() ? std::string("no conditions to relate to the participants") : r.design.note},
      {"Iterations",
       its.empty() ? "none" : fmt::format("{} ({} to {})", its.size(), its.front(), its.back())},
      {"Metrics and references", detail::references_text(r)},
      {"Comparison", r.comparison ? fmt::format("{} against {}{}{}", r.comparison->blocks.front().group1,
                                                r.comparison->blocks.front().group2,
                                                r.comparison->options.paired ? ", paired by participant" : "",
                                                r.comparison_note.empty() ? ""
                                                    : " (" + r.comparison_note + ")")
                                  : conditions.size() > 2
                                      ? fmt::format("all {} conditions: the omnibus tests, then each pair (set "
                                                    "compare = \"A,B\" to compare one pair)",
                                                    conditions.size())
                                      : "none (set compare = \"A,B\")"},
      {"Questionnaire", (c.questionnaire.empty() ? std::string("none") : c.questionnaire) +
                            (r.yes_no ? "; yes/no questions: questionnaire_yesno.csv" : "")},
      {"Settings file", c.config.empty() ? "none" : c.config},
  };
}

std::string title_of(const analysis::StudyResults& r) {
  return fmt::format("Study report: {}", r.study);
}
std::string subtitle_of(const analysis::StudyResults& r) {
  return fmt::format("feint {} analyze, {} of {}", r.tool_version,
                     count(r.diagnostics.scoring.trials_scored, "trial"),
                     count(r.diagnostics.scoring.files, "log file"));
}

std::string exclusion_text(const analysis::Exclusion& e) {
  std::string s = e.count > 0 ? fmt::format("{} {}: {}", e.stage, count(e.count, e.what), e.reason)
                              : fmt::format("{}: {}", e.stage, e.reason);
  if (!e.examples.empty()) {
    // A full list is a list; a partial one gives examples.
    const bool all = e.count == 0 || e.examples.size() >= e.count;
    s += fmt::format(" ({}{})", all ? "" : "e.g. ", fmt::join(e.examples, ", "));
  }
  if (!e.code.empty()) s += fmt::format(" [{}]", e.code);
  return s;
}

}  // namespace

std::string count(std::size_t n, const std::string& singular, const std::string& plural) {
  return fmt::format("{} {}", n, n == 1 ? singular : (plural.empty() ? singular + "s" : plural));
}

std::vector<std::string> diagnostics_lines(const analysis::Diagnostics& d) {
  const auto& s = d.scoring;
  std::vector<std::string> lines = {
      fmt::format("Read {} ({}); {} scored, {} rejected.", count(s.files, "log file"),
                  count(s.rows_read, "row"), count(s.trials_scored, "trial"),
                  count(s.trials_rejected, "trial")),
      fmt::format("{} with at least one scored trial.", count(d.participants, "participant")),
  };
  if (s.overspeed_trials > 0) {
    lines.push_back(fmt::format("{} with a segment faster than the pad speed (kept).",
                                count(s.overspeed_trials, "trial")));
  }
  if (d.questionnaire_rows > 0) {
    lines.push_back(fmt::format("Questionnaire: {} read, {} analysed.",
                                count(d.questionnaire_rows, "row"),
                                count(d.respondents, "respondent")));
  }
  if (d.participants_compared) {
    const auto& c = *d.participants_compared;
    lines.push_back(fmt::format(
        "Participant ids of the logs and the questionnaire: {} in both, {} only in the logs, {} "
        "only in the questionnaire.",
        c.in_both, c.only_in_logs.size(), c.only_in_questionnaire.size()));
  }
  if (d.exclusions.empty() && d.warnings.empty()) {
    lines.emplace_back("Nothing was excluded and there was no warning.");
  }
  for (const auto& e : d.exclusions) lines.push_back(exclusion_text(e));
  if (d.exclusions.empty())
    for (const auto& w : d.warnings) lines.push_back("warning: " + w);
  return lines;
}

namespace {

// The Accounting's list: the data's exclusions and warnings, what the findings left out of an
// analysis (never "nothing was excluded" beside them), and the reference check.
std::vector<std::string> accounting_lines(const analysis::StudyResults& r) {
  std::vector<std::string> lines = diagnostics_lines(r.diagnostics);
  const std::vector<std::string> left_out = detail::left_out_lines(r);
  const std::size_t warned = detail::other_warned_findings(r);
  static const std::string kNothing = "Nothing was excluded and there was no warning.";
  if (!lines.empty() && lines.back() == kNothing && (!left_out.empty() || warned > 0)) {
    lines.pop_back();
    if (left_out.empty()) lines.emplace_back("Nothing was excluded from the data read.");
  }
  lines.insert(lines.end(), left_out.begin(), left_out.end());
  if (warned > 0)
    lines.push_back(fmt::format("{} {} a warning of {} own (Findings in detail, under Results).",
                                count(warned, "finding"), warned == 1 ? "carries" : "carry",
                                warned == 1 ? "its" : "their"));
  lines.push_back(detail::reference_check_line(r));
  return lines;
}

// The Accounting section: what was read, scored and rejected, and every exclusion and warning.
std::string accounting_html(const analysis::StudyResults& r) {
  const auto& s = r.diagnostics.scoring;
  std::vector<std::pair<std::string, std::string>> rows = {
      {"Log files read", std::to_string(s.files)},
      {"Rows read", std::to_string(s.rows_read)},
      {"Rows scored", std::to_string(s.rows_scored)},
      {"Rows rejected", std::to_string(s.rows_rejected)},
      {"Trials scored", std::to_string(s.trials_scored)},
      {"Trials rejected", std::to_string(s.trials_rejected)},
      {"Trials with an overspeed segment", std::to_string(s.overspeed_trials)},
      {"Participants", std::to_string(r.diagnostics.participants)},
      // Named relative to this page, which the output folder carries along when it is moved.
      {"Scores", "scores.csv (beside this report)"},
  };
  if (!s.rejects_path.empty()) {
    rows.emplace_back("Rejected trials listed in", s.rejects_path + " (beside this report)");
  }
  if (r.diagnostics.questionnaire_rows > 0) {
    rows.emplace_back("Questionnaire rows read", std::to_string(r.diagnostics.questionnaire_rows));
    rows.emplace_back("Respondents analysed", std::to_string(r.diagnostics.respondents));
  }
  std::string html = facts(rows);
  html += fmt::format("<p>rows read = rows scored + rows rejected: {} = {} + {}.</p>\n",
                      s.rows_read, s.rows_scored, s.rows_rejected);
  html += "<h3>Excluded and warned about</h3>\n<ul class=\"diagnostics\">\n";
  for (const auto& l : accounting_lines(r)) {
    html += "<li>" + html_escape(l) + "</li>\n";
  }
  html += "</ul>\n";
  return html;
}

// The Figures section: each figure inline (its SVG's ids prefixed, as several share a page) with
// its caption and links to its files, then the notes on figures not drawn.
std::string figures_html(const std::vector<RenderedFigure>& figures,
                         const std::vector<std::string>& notes) {
  std::string html;
  for (std::size_t i = 0; i < figures.size(); ++i) {
    const RenderedFigure& d = figures[i];
    std::string links;
    for (const auto& f : d.files) {
      if (!links.empty()) links += ", ";
      links += fmt::format("<a href=\"{0}\">{1}</a>", html_escape(f),
                           html_escape(fs::path(f).filename().string()));
    }
    // The one-column drawing on a narrow screen (CSS in plot::render_html): its text stays >= 9 px.
    // data-min-font-pt: the drawings' smallest text (pt, their viewBox units), for the browser check.
    const std::string wide = plot::inline_svg(d.svg, fmt::format("f{}-", i + 1), d.alt);
    const std::string drawings =
        d.svg_narrow.empty()
            ? wide
            : fmt::format("<div class=\"fig-wide\" data-min-font-pt=\"{2:g}\">{0}</div>\n<div class=\"fig-narrow\" "
                          "data-min-font-pt=\"{2:g}\">{1}</div>",
                          wide, plot::inline_svg(d.svg_narrow, fmt::format("f{}n-", i + 1), d.alt), plot::kTickFontSize);
    html += fmt::format(
        "<figure id=\"fig-{0}\">\n{1}\n<figcaption><strong>Figure {2}. {3}.</strong> {4}{5}"
        "</figcaption>\n</figure>\n",
        html_escape(d.name), drawings, i + 1,
        html_escape(d.title), html_escape(d.caption),
        links.empty() ? "" : "<br><span class=\"files\">Files: " + links + "</span>");
  }
  for (const auto& n : notes) html += "<p>" + html_escape(n) + "</p>\n";
  return html;
}

// The Settings section: the run's feint.toml, and the scoring settings the scores were made with.
std::string settings_html(const analysis::StudyResults& r) {
  std::string settings;
  std::vector<std::pair<std::string, std::string>> scoring;
  for (const auto& [k, v] : r.table1.provenance.settings) {
    if (k.rfind("settings.", 0) == 0) scoring.emplace_back(k.substr(9), v);
  }
  settings +=
      "<p>Every setting of this run as a feint.toml (also written beside this report as "
      "<a href=\"settings.toml\">settings.toml</a>): <code>feint analyze --config "
      "settings.toml STUDY</code> reproduces it.</p>\n<pre class=\"settings\">" +
      html_escape(r.settings_toml) + "</pre>\n";
  if (!scoring.empty())
    settings += "<h3>Scoring (from the scores' sidecar)</h3>\n" + facts(scoring);
  return settings;
}

// The Reproduce section: the command line that made this report, run from its folder.
std::string reproduce_html(const analysis::StudyResults& r, const ReportContext& c) {
  return fmt::format(
      "<p>This report was made by feint {} with the command below, run from this "
      "report's folder (its paths are relative to it{}):</p>\n<pre>{}</pre>\n"
      "<p>Every table is also in the output folder as text, Markdown, LaTeX, CSV "
      "and JSON (as the formats setting asks); the figures one-column (3.5 in) and "
      "two-column (7.16 in) wide.</p>\n",
      html_escape(r.tool_version), html_escape(placeholder_note(c.command_line)),
      html_escape(c.command_line));
}

// The Results section: the paragraphs, then the findings engine's own list (docs/findings.md:
// strength, sentence, link, warnings) in a <details> that opens on a click.
std::string results_html(const analysis::StudyResults& r) {
  std::string html = study_results_text(r, ResultsFormat::html);
  if (!r.findings.empty()) {
    html += fmt::format("<details id=\"findings\">\n<summary>Findings in detail: every test with its "
                        "strength of evidence and its table ({})</summary>\n{}</details>\n",
                        r.findings.size(), analysis::findings_html(r.findings));
  }
  return html;
}

}  // namespace

std::string study_report_html(const analysis::StudyResults& r,
                              const std::vector<RenderedFigure>& figures,
                              const std::vector<std::string>& notes, const ReportContext& c) {
  plot::HtmlReport page;
  page.title = title_of(r);
  page.subtitle = subtitle_of(r);
  // The page opens with the answers (one paragraph per hypothesis); every finding follows, folded.
  page.sections.push_back({"results", "Results", results_html(r)});
  page.sections.push_back({"design", "Design", facts(design_rows(r, c))});
  page.sections.push_back({"accounting", "Accounting", accounting_html(r)});
  if (!figures.empty() || !notes.empty()) {
    page.sections.push_back({"figures", "Figures", figures_html(figures, notes)});
  }
  for (const auto& t : tables(r)) {
    page.sections.push_back(
        {t.id, t.heading, plot::markdown_to_html(t.markdown) + t.tests_html + csv_link(t, c.csv_beside)});
  }
  page.sections.push_back({"settings", "Settings", settings_html(r)});
  page.sections.push_back({"reproduce", "Reproduce", reproduce_html(r, c)});
  page.footer = fmt::format("feint {}: {}", r.tool_version, c.command_line);
  return plot::render_html(page);
}

std::string study_report_markdown(const analysis::StudyResults& r,
                                  const std::vector<RenderedFigure>& figures,
                                  const ReportContext& c) {
  std::string o = fmt::format("# {}\n\n{}\n\n", title_of(r), subtitle_of(r));
  o += "## Results\n\n" + study_results_text(r, ResultsFormat::markdown) + "\n";
  if (!r.findings.empty()) {
    o += "### Findings in detail\n\n";
    o += analysis::findings_markdown(r.findings);
    o += "\n";
  }
  o += "## Design\n\n";
  for (const auto& [k, v] : design_rows(r, c)) o += fmt::format("- {}: {}\n", k, v);
  o += "\n## Accounting: data read, excluded and warned about\n\n";
  for (const auto& l : accounting_lines(r)) o += "- " + l + "\n";
  if (!figures.empty()) {
    o += "\n## Figures\n\n";
    for (std::size_t i = 0; i < figures.size(); ++i) {
      const auto& f = figures[i];
      std::string image;
      for (const auto& file : f.files) {
        if (file.find("-2col.svg") != std::string::npos || file.find("-2col.png") != std::string::npos) {
          image = file;
        }
      }
      o += fmt::format("**Figure {}. {}.** ", i + 1, f.title);
      if (!image.empty()) o += fmt::format("![{}]({})\n\n", f.alt, image);
      o += f.caption + "\n\n";
    }
  }
  for (const auto& t : tables(r)) {
    o += fmt::format("\n## {}\n\n{}\n", t.heading, t.markdown);
    if (c.csv_beside) o += fmt::format("\n[Download as CSV]({}.csv)\n", t.stem);
  }
  o += "\n## Settings\n\n`feint analyze --config settings.toml STUDY` reproduces this run:\n\n```toml\n" +
       r.settings_toml + "```\n";
  o += fmt::format("\n## Reproduce\n\nMade by feint {} with the command below, run from this "
                   "report's folder (its paths are relative to it{}):\n\n```\n{}\n```\n",
                   r.tool_version, placeholder_note(c.command_line),
                   c.command_line);
  return o;
}

std::string study_results_json(const analysis::StudyResults& r) {
  auto q = [](const std::string& s) { return io::json_quote(s); };
  auto trimmed = [](std::string s) {
    while (!s.empty() && (s.back() == '\n' || s.back() == ' ')) s.pop_back();
    return s;
  };
  std::string o = "{\n";
  o += fmt::format("  \"study\": {},\n  \"version\": {},\n", q(r.study), q(r.tool_version));
  const auto& s = r.diagnostics.scoring;
  o += fmt::format(
      "  \"diagnostics\": {{\"log_files\": {}, \"rows_read\": {}, \"rows_scored\": {}, "
      "\"rows_rejected\": {}, \"trials_scored\": {}, \"trials_rejected\": {}, "
      "\"overspeed_trials\": {}, \"participants\": {}, \"questionnaire_rows\": {}, "
      "\"respondents\": {}, \"warnings\": [",
      s.files, s.rows_read, s.rows_scored, s.rows_rejected, s.trials_scored, s.trials_rejected,
      s.overspeed_trials, r.diagnostics.participants, r.diagnostics.questionnaire_rows,
      r.diagnostics.respondents);
  for (std::size_t i = 0; i < r.diagnostics.warnings.size(); ++i) {
    o += (i ? ", " : "") + q(r.diagnostics.warnings[i]);
  }
  o += "], \"exclusions\": [";
  for (std::size_t i = 0; i < r.diagnostics.exclusions.size(); ++i) {
    const auto& e = r.diagnostics.exclusions[i];
    std::string examples;
    for (std::size_t k = 0; k < e.examples.size(); ++k) examples += (k ? ", " : "") + q(e.examples[k]);
    o += fmt::format("{}{{\"stage\": {}, \"what\": {}, \"count\": {}, \"reason\": {}, "
                     "\"code\": {}, \"examples\": [{}]}}",
                     i ? ", " : "", q(e.stage), q(e.what), e.count, q(e.reason), q(e.code),
                     examples);
  }
  o += "]";
  if (r.diagnostics.participants_compared) {
    const auto& c = *r.diagnostics.participants_compared;
    auto list = [&](const std::vector<std::string>& v) {
      std::string l;
      for (std::size_t i = 0; i < v.size(); ++i) l += (i ? ", " : "") + q(v[i]);
      return l;
    };
    o += fmt::format(", \"participants_compared\": {{\"in_both\": {}, \"only_in_logs\": [{}], "
                     "\"only_in_questionnaire\": [{}]}}",
                     c.in_both, list(c.only_in_logs), list(c.only_in_questionnaire));
  }
  o += "},\n  \"findings\": [";
  for (std::size_t i = 0; i < r.findings.size(); ++i) {
    const auto& f = r.findings[i];
    o += fmt::format("{}{{\"id\": {}, \"question\": {}, \"sentence\": {}, \"evidence\": {}, "
                     "\"source\": {}}}",
                     i ? ", " : "", q(f.id), q(f.question), q(f.sentence), q(f.evidence),
                     q(f.source));
  }
  o += "]";
  for (const auto& t : tables(r)) {
    std::string json;
    if (t.stem == "table1") json = tables::render_table1(r.table1, OutputFormat::json);
    else if (t.stem == "table1_compare") json = tables::render_table1(*r.comparison, OutputFormat::json);
    else if (t.stem == "anova") json = tables::render_anova(*r.anova, OutputFormat::json, r.table1.options.apa);
    else if (t.stem == "model") json = tables::render_model(*r.model, OutputFormat::json);
    else if (t.stem == "model_trend") json = tables::render_model(*r.trend_model, OutputFormat::json);
    else if (t.stem == "exposure_by_condition") json = tables::render_exposure(r.exposure, OutputFormat::json);
    else if (t.stem == "likert") json = tables::render_likert(*r.likert, OutputFormat::json);
    else if (t.stem == "likert_compare") json = tables::render_likert(*r.likert_compare, OutputFormat::json);
    else if (t.stem == "likert_conditions") json = tables::render_likert_conditions(*r.likert_conditions, OutputFormat::json);
    else if (t.stem == "yes_no") json = tables::render_yes_no(*r.yes_no, OutputFormat::json);
    o += fmt::format(",\n  {}: {}", q(t.stem), trimmed(json));
  }
  o += fmt::format(",\n  \"settings_toml\": {}\n}}\n", q(r.settings_toml));
  return o;
}

}  // namespace feint::publish
