// The LaTeX tables must compile as fragments of a paper. Needs pdflatex with booktabs
// (Debian: texlive-latex-base, texlive-latex-recommended); skips with a message where TeX is
// absent, as it is on CI (TeX is not a dependency of feint).
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <string>

#include "cli/cli_helpers.hpp"

namespace fs = std::filesystem;
using feint::test::read_text;
using feint::test::run_feint;
using feint::test::shell_quote;
using feint::test::TempDir;
using feint::test::write_text;

namespace {

bool have_latex() {
  return std::system(
             "command -v pdflatex >/dev/null 2>&1 && kpsewhich booktabs.sty >/dev/null 2>&1") == 0;
}

}  // namespace

TEST(LatexTables, CompileAsFragmentsOfAPaper) {
  if (!have_latex())
    GTEST_SKIP() << "pdflatex with booktabs not installed: LaTeX compile check skipped";
  const fs::path demo = fs::path(FEINT_SOURCE_DIR) / "data" / "demo";
  TempDir dir;
  const auto out = dir / "out";
  auto r = run_feint("analyze " + shell_quote(demo.string()) + " -o " + shell_quote(out.string()) +
                     " --formats latex --apa --equivalence 0.1");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* table : {"table1", "table1_compare", "likert", "likert_compare"}) {
    const auto doc = dir / (std::string("paper_") + table + ".tex");
    write_text(doc, std::string("\\documentclass{article}\n\\usepackage[T1]{fontenc}\n"
                                "\\usepackage{booktabs}\n\\usepackage{graphicx}\n"
                                "\\usepackage{amsmath}\n\\begin{document}\n"
                                "Some text of the paper.\n\\input{") +
                        (out / (std::string(table) + ".tex")).string() + "}\n\\end{document}\n");
    const std::string cmd = "cd " + shell_quote(dir.path().string()) +
                            " && pdflatex -interaction=nonstopmode -halt-on-error " +
                            shell_quote(doc.filename().string()) + " > " +
                            shell_quote((dir / (std::string(table) + ".out")).string()) + " 2>&1";
    const int rc = std::system(cmd.c_str());
    EXPECT_EQ(rc, 0) << table << ":\n" << read_text(dir / (std::string(table) + ".out"));
    // Wide tables are scaled to the line, so nothing runs off the page.
    EXPECT_EQ(read_text(dir / (std::string("paper_") + table + ".log")).find("Overfull \\hbox"),
              std::string::npos)
        << table;
  }
}

namespace {

// Compiles `body` twice (so references resolve) in a two-column paper; returns the second log.
std::string compile_two_column_paper(const fs::path& dir, const std::string& body, int* rc) {
  write_text(dir / "paper.tex",
             "\\documentclass[twocolumn]{article}\n\\usepackage[T1]{fontenc}\n"
             "\\usepackage{booktabs}\n\\usepackage{graphicx}\n\\usepackage{amsmath}\n"
             "\\begin{document}\n" + body + "\\end{document}\n");
  const std::string cmd = "cd " + shell_quote(dir.string()) +
                          " && pdflatex -interaction=nonstopmode -halt-on-error paper.tex "
                          ">/dev/null 2>&1 && pdflatex -interaction=nonstopmode -halt-on-error "
                          "paper.tex >/dev/null 2>&1";
  *rc = std::system(cmd.c_str());
  return read_text(dir / "paper.log");
}

}  // namespace

// Every table of the demo study in one two-column paper, referenced by its label: no LaTeX warning
// (no multiply-defined or undefined label, no overfull box), in the column and across both columns.
// With analyze's tables: the linear mixed model of its scores (`feint model --format latex`).
TEST(LatexTables, AllDemoTablesCompileInOneTwoColumnPaperWithoutWarnings) {
  if (!have_latex())
    GTEST_SKIP() << "pdflatex with booktabs not installed: LaTeX compile check skipped";
  const fs::path demo = fs::path(FEINT_SOURCE_DIR) / "data" / "demo";
  for (const bool wide : {false, true}) {
    TempDir dir;
    const auto out = dir / "out";
    const auto r = run_feint("analyze " + shell_quote(demo.string()) + " -o " +
                             shell_quote(out.string()) +
                             " --formats latex --equivalence 0.1 --compare adaptive,random" +
                             (wide ? " --latex-wide" : ""));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto m =
        run_feint("model " + shell_quote((out / "scores.csv").string()) + " --format latex -o " +
                  shell_quote((out / "model.tex").string()) + (wide ? " --latex-wide" : ""));
    ASSERT_EQ(m.exit_code, 0) << m.err;
    std::string body = "Some text of the paper.\n";
    std::size_t labels = 0;
    for (const char* table :
         {"table1", "table1_compare", "likert", "likert_compare", "anova", "model"}) {
      const std::string tex = read_text(out / (std::string(table) + ".tex"));
      EXPECT_EQ(tex.find(wide ? "\\begin{table*}" : "\\begin{table}"), tex.find("\\begin{table"))
          << table;
      // Each table's labels are referenced, so an undefined one would warn.
      for (std::size_t k = tex.find("\\label{"); k != std::string::npos;
           k = tex.find("\\label{", k + 1)) {
        const auto end = tex.find('}', k);
        body += "See Table~\\ref{" + tex.substr(k + 7, end - k - 7) + "}.\n";
        ++labels;
      }
      body += "\\input{" + (out / (std::string(table) + ".tex")).string() + "}\n";
      // No absolute path leaks into the paper.
      EXPECT_EQ(tex.find(out.string()), std::string::npos) << table;
      EXPECT_EQ(tex.find(demo.string()), std::string::npos) << table;
    }
    // table1 1 + 1, likert 2 + 2 (main and responses), anova 1, model 3 per metric x 2.
    EXPECT_EQ(labels, 13u) << body;
    EXPECT_NE(body.find("\\ref{tab:feint-anova}"), std::string::npos) << body;
    EXPECT_NE(body.find("\\ref{tab:feint-model-contrasts-confusion}"), std::string::npos) << body;
    int rc = 0;
    const std::string log = compile_two_column_paper(dir.path(), body, &rc);
    ASSERT_EQ(rc, 0) << log;
    EXPECT_EQ(log.find("Warning"), std::string::npos) << (wide ? "wide: " : "") << log;
    EXPECT_EQ(log.find("Overfull"), std::string::npos) << log;
    EXPECT_EQ(log.find("Underfull"), std::string::npos) << log;
  }
}
