// The study report's words and links (plurals, CSV downloads, relative paths, alt text).
#include <gtest/gtest.h>

#include <string>

#include "feint/analysis/analyze.hpp"
#include "feint/publish/study_report.hpp"

using namespace feint;

TEST(StudyReport, PluralsAreRight) {
  EXPECT_EQ(publish::count(1, "log file"), "1 log file");
  EXPECT_EQ(publish::count(0, "log file"), "0 log files");
  EXPECT_EQ(publish::count(2, "trial"), "2 trials");
  EXPECT_EQ(publish::count(3, "analysis", "analyses"), "3 analyses");
}

TEST(StudyReport, TablesDownloadAsCsvAndFiguresHaveAltText) {
  analysis::AnalysisSettings s;
  s.compare = "adaptive,random";
  const auto study = analysis::load_study(std::string(FEINT_SOURCE_DIR) + "/data/demo", s);
  const auto r = analysis::analyze(study, "test");
  publish::RenderedFigure f{"error", "Mean error", "Caption.", "Line chart of the mean error.",
                            "<svg width=\"10pt\" height=\"5pt\" viewBox=\"0 0 10 5\"></svg>",
                            {"figures/error-2col.svg"}};
  publish::ReportContext c;
  c.study_folder = "data/demo";
  c.csv_beside = true;
  const std::string html = publish::study_report_html(r, {f}, {}, c);
  for (const char* csv : {"table1.csv", "table1_compare.csv", "anova.csv", "model.csv"}) {
    EXPECT_NE(html.find(std::string("href=\"") + csv + "\" download"), std::string::npos) << csv;
  }
  EXPECT_NE(html.find("<title id=\"f1-title\">Line chart of the mean error.</title>"),
            std::string::npos);
  EXPECT_NE(html.find("of 60 log files"), std::string::npos);
  // Without CSV files beside the report, the CSV travels in the link itself.
  c.csv_beside = false;
  const std::string inline_csv = publish::study_report_html(r, {}, {}, c);
  EXPECT_NE(inline_csv.find("href=\"data:text/csv;charset=utf-8,metric,iteration"),
            std::string::npos);
  const std::string md = publish::study_report_markdown(r, {f}, c);
  EXPECT_NE(md.find("![Line chart of the mean error.](figures/error-2col.svg)"), std::string::npos);
}
