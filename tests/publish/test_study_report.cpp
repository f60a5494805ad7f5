// The study report's words and links (plurals, CSV downloads, relative paths, alt text).
#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <string>

#include "feint/analysis/analyze.hpp"
#include "feint/plot/figures.hpp"
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

TEST(StudyReport, TheNewFiguresAreDrawnWithTheAltTextOfTheirData) {
  analysis::AnalysisSettings s;
  s.compare = "adaptive,random";
  const auto study = analysis::load_study(std::string(FEINT_SOURCE_DIR) + "/data/demo", s);
  const auto r = analysis::analyze(study, "test");
  const auto dir = std::filesystem::temp_directory_path() / "feint-test-publish-figures";
  std::filesystem::remove_all(dir);
  const publish::DrawnFigures drawn = publish::draw_figures(r, {"svg"}, dir.string());
  std::map<std::string, const publish::RenderedFigure*> by_name;
  for (const auto& f : drawn.figures) by_name[f.name] = &f;
  ASSERT_TRUE(by_name.count("exposure-error"));
  ASSERT_TRUE(by_name.count("model-confusion"));
  ASSERT_TRUE(by_name.count("error"));
  // The alt text is the plot module's, from the same data the figure is drawn from.
  EXPECT_EQ(by_name["exposure-error"]->alt, plot::alt_text(r.figures.exposure[0]));
  const plot::ModelFitFigureData md{
      plot::metric_figure_data(r.table1, &*r.comparison, "confusion"),
      r.figures.model_trends[1].trend, r.figures.model_trends[1].model};
  EXPECT_EQ(by_name["model-confusion"]->alt, plot::alt_text(md));
  EXPECT_EQ(by_name["error"]->alt,
            plot::alt_text(plot::metric_figure_data(r.table1, &*r.comparison, "error")));
  EXPECT_EQ(by_name["traces"]->alt,
            plot::alt_text(plot::TracesFigureData{r.figures.traces, 0.95}));
  for (const auto& f : drawn.figures) {
    EXPECT_FALSE(f.alt.empty()) << f.name;
    EXPECT_NE(f.svg.find("<svg"), std::string::npos) << f.name;
    for (const auto& file : f.files) EXPECT_TRUE(std::filesystem::exists(dir / file)) << file;
  }
  std::filesystem::remove_all(dir);
}
