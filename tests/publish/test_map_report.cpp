// The map figure in `feint analyze`: a study of K targets and a pointer (data/demo-k3) gets it in
// its figures and its report, the same bytes on every run; a pad study (data/demo) gets none.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <string>

#include "cli/cli_helpers.hpp"
#include "feint/analysis/analyze.hpp"
#include "feint/publish/study_report.hpp"

namespace fs = std::filesystem;
using feint::test::read_text;
using feint::test::shell_quote;
using feint::test::TempDir;

namespace {

// As the report was made (docs/many-targets.md): from the project's folder, the study named
// relatively, so that the report's Reproduce lines name it as reports/demo-k3 does.
int analyze_from_source(const std::string& study, const fs::path& out) {
  const std::string cmd = "cd " + shell_quote(FEINT_SOURCE_DIR) + " && " + shell_quote(FEINT_EXE) +
                          " analyze " + study + " -o " + shell_quote(out.string()) +
                          " >/dev/null 2>&1";
  const int status = std::system(cmd.c_str());
  return status != -1 && WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

}  // namespace

TEST(MapReport, AnalyzeOfAKTargetStudyWritesTheMapAndTheReportShowsIt) {
  TempDir dir;
  const fs::path a = dir.path() / "a", b = dir.path() / "b";
  ASSERT_EQ(analyze_from_source("data/demo-k3", a), 0);
  ASSERT_EQ(analyze_from_source("data/demo-k3", b), 0);
  for (const char* f : {"map-1col.pdf", "map-1col.svg", "map-2col.pdf", "map-2col.svg"}) {
    const std::string bytes = read_text(a / "figures" / f);
    ASSERT_FALSE(bytes.empty()) << f << " not written";
    EXPECT_EQ(bytes, read_text(b / "figures" / f)) << f << " differs between two runs";
  }
  const std::string html = read_text(a / "report.html");
  EXPECT_NE(html.find("<figure id=\"fig-map\">"), std::string::npos);
  EXPECT_NE(html.find("href=\"figures/map-2col.pdf\""), std::string::npos);
  EXPECT_NE(html.find("Robot paths and pointers on the map, per strategy"), std::string::npos);
  // The caption says how the per-round layouts were brought together.
  EXPECT_NE(html.find("its true target at (0, 1)"), std::string::npos);
  EXPECT_NE(html.find("(480 trials in all)"), std::string::npos);
  EXPECT_EQ(html.find("No map figure"), std::string::npos);
  EXPECT_NE(read_text(a / "report.md").find("(figures/map-2col.svg)"), std::string::npos);
}

TEST(MapReport, ThePanelsAreTheStrategiesAndVersionsOfTheScoredTrials) {
  feint::analysis::AnalysisSettings s;
  const auto study =
      feint::analysis::load_study(std::string(FEINT_SOURCE_DIR) + "/data/demo-k3", s);
  const auto r = feint::analysis::analyze(study, "test");
  TempDir dir;
  const auto drawn = feint::publish::draw_figures(r, {"svg"}, dir.path().string());
  const feint::publish::RenderedFigure* map = nullptr;
  for (const auto& f : drawn.figures) {
    if (f.name == "map") map = &f;
  }
  ASSERT_NE(map, nullptr);
  // Seven panels: ambiguous, exaggerating and switching in two versions, optimal in one.
  EXPECT_NE(map->alt.find("ambiguous/main, ambiguous/v2, exaggerating/main, exaggerating/v2, "
                          "optimal/main, switching/main and switching/v2"),
            std::string::npos)
      << map->alt;
  EXPECT_NE(map->caption.find("480 layouts of 3 targets"), std::string::npos) << map->caption;
  // No pad, so no pad-trace figure, and the note says why (not that the trials were not found).
  ASSERT_EQ(drawn.notes.size(), 1u);
  EXPECT_EQ(drawn.notes[0],
            "No pad-trace figure: the participants pointed on a map (no pad); the map figure shows their mean pointer.");
}

TEST(MapReport, APadStudyHasNoMapAndNoNoteAboutIt) {
  feint::analysis::AnalysisSettings s;
  s.compare = "adaptive,random";
  const auto study = feint::analysis::load_study(std::string(FEINT_SOURCE_DIR) + "/data/demo", s);
  const auto r = feint::analysis::analyze(study, "test");
  TempDir dir;
  const auto drawn = feint::publish::draw_figures(r, {"svg"}, dir.path().string());
  for (const auto& f : drawn.figures) EXPECT_NE(f.name, "map");
  for (const auto& n : drawn.notes) EXPECT_EQ(n.find("map"), std::string::npos) << n;
  EXPECT_FALSE(fs::exists(dir.path() / "figures" / "map-2col.svg"));
}
