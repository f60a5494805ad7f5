// feint plot and the figures + report.html of feint analyze, end to end: every figure
// renders to PDF and SVG at both widths, the SVG parses as XML, a paper that \includegraphics
// every PDF compiles without warnings (where pdflatex is installed), bad options are usage errors
// and the inputs are never written.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <set>
#include <sstream>
#include <string>

#include "cli/cli_helpers.hpp"
#include "feint/io/csv.hpp"

namespace fs = std::filesystem;
using feint::test::read_text;
using feint::test::run_feint;
using feint::test::shell_quote;
using feint::test::TempDir;
using feint::test::write_text;

namespace {

const fs::path kDemo = fs::path(FEINT_SOURCE_DIR) / "data" / "demo";

// One analysis of the demo study shared by the tests (about a second).
const fs::path& demo_output() {
  static TempDir dir;
  static bool done = false;
  if (!done) {
    const auto r = run_feint("analyze " + shell_quote(kDemo.string()) + " -o " +
                             shell_quote((dir / "out").string()));
    EXPECT_EQ(r.exit_code, 0) << r.err;
    done = true;
  }
  static const fs::path out = dir / "out";
  return out;
}

std::set<std::string> files_in(const fs::path& dir) {
  std::set<std::string> names;
  if (!fs::is_directory(dir)) return names;
  for (const auto& e : fs::directory_iterator(dir)) names.insert(e.path().filename().string());
  return names;
}

bool have(const char* tool) {
  return std::system((std::string("command -v ") + tool + " >/dev/null 2>&1").c_str()) == 0;
}

}  // namespace

TEST(AnalyzeFigures, EveryFigureInPdfAndSvgAtBothWidths) {
  const auto names = files_in(demo_output() / "figures");
  for (const char* fig : {"error", "confusion", "participants-error", "participants-confusion",
                          "strategies", "traces", "likert", "likert-means", "model-error",
                          "model-confusion", "exposure-error", "exposure-confusion"}) {
    for (const char* suffix : {"-1col.pdf", "-1col.svg", "-2col.pdf", "-2col.svg"}) {
      const std::string name = std::string(fig) + suffix;
      ASSERT_TRUE(names.count(name)) << name;
      const std::string bytes = read_text(demo_output() / "figures" / name);
      if (name.ends_with(".pdf")) {
        EXPECT_EQ(bytes.rfind("%PDF-1.5", 0), 0u) << name;
      } else {
        EXPECT_NE(bytes.find("<svg"), std::string::npos) << name;
      }
    }
  }
  EXPECT_EQ(names.size(), 12u * 4u);
}

TEST(AnalyzeFigures, SvgFilesParseAsXml) {
  if (!have("xmllint")) GTEST_SKIP() << "xmllint not installed (Debian: libxml2-utils): skipped";
  for (const auto& name : files_in(demo_output() / "figures")) {
    if (!name.ends_with(".svg")) continue;
    const std::string cmd =
        "xmllint --noout " + shell_quote((demo_output() / "figures" / name).string());
    EXPECT_EQ(std::system(cmd.c_str()), 0) << name;
  }
}

TEST(AnalyzeFigures, ReportIsOneSelfContainedPageWithEveryFigureAndTable) {
  const std::string html = read_text(demo_output() / "report.html");
  ASSERT_FALSE(html.empty());
  std::size_t figures = 0;
  for (std::size_t p = html.find("<figure"); p != std::string::npos;
       p = html.find("<figure", p + 1))
    ++figures;
  EXPECT_EQ(figures, 12u);
  for (const char* part :
       {"<svg", "Table 1 per condition", "Comparison", "Questionnaire", "Accounting",
        "Rows read</dt><dd>219587", "Welch two-sample", "Wilcoxon", "feint analyze",
        "compare = &quot;adaptive,random&quot;", "@media print"}) {
    EXPECT_NE(html.find(part), std::string::npos) << part;
  }
  for (const char* fetch : {"<script", "<link", "@import", "<img", "<iframe"}) {
    EXPECT_EQ(html.find(fetch), std::string::npos) << fetch;
  }
  // The run writes into a staging folder renamed into place: the page never names it.
  EXPECT_EQ(html.find("feint-staging"), std::string::npos);
  EXPECT_NE(html.find("scores.csv (beside this report)"), std::string::npos);
  // Every id is unique: figures inline side by side must not share glyph or clip ids.
  std::set<std::string> ids;
  for (std::size_t p = html.find(" id=\""); p != std::string::npos;
       p = html.find(" id=\"", p + 1)) {
    const std::size_t end = html.find('"', p + 5);
    EXPECT_TRUE(ids.insert(html.substr(p + 5, end - p - 5)).second)
        << html.substr(p + 5, end - p - 5);
  }
}

TEST(AnalyzeFigures, ReportShowsTheMixedAnovaOfAnovaCsv) {
  const std::string html = read_text(demo_output() / "report.html");
  const std::size_t begin = html.find("<section id=\"anova\">");
  ASSERT_NE(begin, std::string::npos) << "no ANOVA section in report.html";
  const std::string section = html.substr(begin, html.find("</section>", begin) - begin);
  EXPECT_NE(section.find("<h2>Mixed ANOVA</h2>"), std::string::npos);
  EXPECT_NE(section.find("<table"), std::string::npos);
  EXPECT_NE(section.find("Type-III sums of squares"), std::string::npos) << "the note";
  // Every effect of anova.csv, with its F as the table shows it (two decimals).
  std::istringstream csv(read_text(demo_output() / "anova.csv"));
  std::string line;
  ASSERT_TRUE(std::getline(csv, line));
  const auto header = feint::io::split_csv_line(line);
  std::size_t metric = header.size(), effect = header.size(), f = header.size();
  for (std::size_t i = 0; i < header.size(); ++i) {
    if (header[i] == "metric") metric = i;
    if (header[i] == "effect") effect = i;
    if (header[i] == "F") f = i;
  }
  ASSERT_LT(f, header.size());
  ASSERT_LT(effect, header.size());
  std::size_t rows = 0;
  std::set<std::string> metrics;
  while (std::getline(csv, line)) {
    if (line.empty()) continue;
    const auto cells = feint::io::split_csv_line(line);
    ASSERT_GT(cells.size(), f) << line;
    metrics.insert(cells[metric]);
    const std::string shown = fmt::format("{:.2f}", std::stod(cells[f]));
    EXPECT_NE(section.find("<td>" + cells[effect] + "</td>"), std::string::npos) << cells[effect];
    EXPECT_NE(section.find(">" + shown + "</td>"), std::string::npos)
        << cells[metric] << " " << cells[effect] << " F = " << shown;
    ++rows;
  }
  EXPECT_EQ(rows, 6u);  // condition, iteration and their interaction, for error and confusion
  for (const auto& m : metrics) {
    EXPECT_NE(section.find("Metric: " + m), std::string::npos) << m;
  }
  // Placed after Table 1 and the comparison, before the questionnaire.
  EXPECT_LT(html.find("<section id=\"table1\">"), begin);
  EXPECT_LT(begin, html.find("<section id=\"questionnaire\">"));
}

TEST(AnalyzeFigures, PdfFiguresCompileInAPaperWithoutWarnings) {
  if (!have("pdflatex")) GTEST_SKIP() << "pdflatex not installed: LaTeX figure check skipped";
  TempDir dir;
  std::string body;
  for (const auto& name : files_in(demo_output() / "figures")) {
    if (!name.ends_with(".pdf")) continue;
    const bool wide = name.find("-2col") != std::string::npos;
    body += std::string("\\begin{") + (wide ? "figure*" : "figure") + "}[p]\n\\centering\n" +
            "\\includegraphics{" + (demo_output() / "figures" / name).string() + "}\n" +
            "\\caption{" + name.substr(0, name.size() - 4) + "}\n\\end{" +
            (wide ? "figure*" : "figure") + "}\n";
  }
  // A two-column paper (IEEE-like): 3.5 in columns, 7.16 in text width; the figures must fit.
  write_text(dir / "paper.tex",
             "\\documentclass[twocolumn]{article}\n\\usepackage[T1]{fontenc}\n"
             "\\usepackage[paperwidth=8.5in,paperheight=11in,textwidth=7.16in,columnsep=0.16in,"
             "textheight=9in]{geometry}\n\\usepackage{graphicx}\n\\begin{document}\n"
             "Text of the paper.\n" +
                 body + "\\end{document}\n");
  const std::string cmd = "cd " + shell_quote(dir.path().string()) +
                          " && pdflatex -interaction=nonstopmode -halt-on-error paper.tex > "
                          "paper.out 2>&1";
  if (std::system(("kpsewhich geometry.sty >/dev/null 2>&1")) != 0) {
    GTEST_SKIP() << "LaTeX package geometry not installed: LaTeX figure check skipped";
  }
  ASSERT_EQ(std::system(cmd.c_str()), 0) << read_text(dir / "paper.out");
  const std::string log = read_text(dir / "paper.log");
  EXPECT_EQ(log.find("Warning"), std::string::npos) << log;
  EXPECT_EQ(log.find("Overfull"), std::string::npos) << log;
  EXPECT_EQ(log.find("PDF inclusion"), std::string::npos) << log;
}

TEST(AnalyzeFigures, OptionsChooseFormatsOrNoFigures) {
  TempDir dir;
  auto r = run_feint("analyze " + shell_quote(kDemo.string()) + " -o " +
                     shell_quote((dir / "svg").string()) + " --figure-formats svg");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto svg = files_in(dir / "svg" / "figures");
  EXPECT_TRUE(svg.count("error-1col.svg"));
  EXPECT_FALSE(svg.count("error-1col.pdf"));
  EXPECT_NE(read_text(dir / "svg" / "report.html").find("<svg"), std::string::npos);

  r = run_feint("analyze " + shell_quote(kDemo.string()) + " -o " +
                shell_quote((dir / "none").string()) + " --no-figures");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_FALSE(fs::exists(dir / "none" / "figures"));
  const std::string html = read_text(dir / "none" / "report.html");
  EXPECT_EQ(html.find("<figure"), std::string::npos);
  EXPECT_NE(html.find("Table 1 per condition"), std::string::npos);

  r = run_feint("analyze " + shell_quote(kDemo.string()) + " -o " +
                shell_quote((dir / "noreport").string()) + " --no-report");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_FALSE(fs::exists(dir / "noreport" / "report.html"));
  EXPECT_TRUE(fs::exists(dir / "noreport" / "figures" / "error-1col.pdf"));

  r = run_feint("analyze " + shell_quote(kDemo.string()) + " -o " +
                shell_quote((dir / "bad").string()) + " --figure-formats gif");
  EXPECT_EQ(r.exit_code, 64) << r.err;
  EXPECT_NE(r.err.find("gif"), std::string::npos);
}

TEST(PlotCommand, DrawsEachFigureInTheFormatOfItsExtension) {
  const std::string scores = (demo_output() / "scores.csv").string();
  const std::string before = read_text(scores);
  const std::string q = (kDemo / "questionnaire.csv").string();
  TempDir dir;
  struct Case {
    std::string args, file;
  };
  const Case cases[] = {
      {shell_quote(scores) + " --figure error --compare adaptive,random --p-adjust holm", "e.pdf"},
      {shell_quote(scores) + " --figure confusion --width two --conf-level 0.9", "c.svg"},
      {shell_quote(scores) + " --figure error --metric error=0.4", "m.png"},
      {shell_quote(scores) + " --figure participants", "p.pdf"},
      {shell_quote(scores) + " --figure strategies", "s.svg"},
      {shell_quote(scores) + " --figure traces --logs " + shell_quote((kDemo / "logs").string()),
       "t.pdf"},
      {shell_quote(q) + " --figure likert --reference 3.5", "l.pdf"},
      {shell_quote(q) + " --figure likert-means", "lm.svg"},
  };
  for (const auto& c : cases) {
    const auto path = dir / c.file;
    const auto r = run_feint("plot " + c.args + " -o " + shell_quote(path.string()));
    ASSERT_EQ(r.exit_code, 0) << c.args << "\n" << r.err;
    const std::string bytes = read_text(path);
    const std::string magic = c.file.ends_with(".pdf")   ? "%PDF"
                              : c.file.ends_with(".svg") ? "<svg"
                                                         : "PNG";
    EXPECT_NE(bytes.substr(0, 200).find(magic), std::string::npos) << c.file;
  }
  EXPECT_EQ(read_text(scores), before);  // the input is never written
}

TEST(PlotCommand, BadRequestsAreUsageErrors) {
  const std::string scores = shell_quote((demo_output() / "scores.csv").string());
  TempDir dir;
  const std::string out = shell_quote((dir / "x.pdf").string());
  EXPECT_EQ(
      run_feint("plot " + scores + " --figure error -o " + shell_quote((dir / "x.jpg").string()))
          .exit_code,
      64);
  EXPECT_EQ(run_feint("plot " + scores + " --figure error").exit_code, 64);  // no -o
  EXPECT_EQ(run_feint("plot " + scores + " --figure nonsense -o " + out).exit_code, 64);
  EXPECT_EQ(run_feint("plot " + scores + " --figure traces -o " + out).exit_code, 64);
  EXPECT_EQ(run_feint("plot " + scores + " --figure error --width 3 -o " + out).exit_code, 64);
  EXPECT_EQ(run_feint("plot " + scores + " --figure error --compare adaptive -o " + out).exit_code,
            64);
  EXPECT_EQ(
      run_feint("plot " + scores + " --figure error --compare adaptive,nobody -o " + out).exit_code,
      64);  // a condition the data do not have: a usage error in every command
  EXPECT_EQ(run_feint("plot missing.csv --figure error -o " + out).exit_code, 74);
  EXPECT_FALSE(fs::exists(dir / "x.pdf"));
}
