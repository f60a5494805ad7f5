// `feint simulate study --targets K --layout fixed|random` end to end: K = 2 with a fixed layout
// is today's study byte for byte (data/demo-three was written by the same command), and a study of
// 3 targets goes through `feint analyze` with no flag.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "cli_helpers.hpp"
#include "feint/io/csv.hpp"

namespace fs = std::filesystem;
using feint::test::read_text;
using feint::test::run_feint;
using feint::test::shell_quote;
using feint::test::TempDir;

TEST(SimulateKTargetsCli, TwoTargetsFixedIsTodaysStudyByteForByte) {
  TempDir dir;
  const auto out = dir / "study";
  const auto r = run_feint("simulate study --targets 2 --layout fixed --participants 12 --iterations 20 --seed 2026 "
                           "--conditions adaptive,random,fixed-block -o " +
                           shell_quote(out.string()));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const fs::path demo = fs::path(FEINT_SOURCE_DIR) / "data" / "demo-three";
  std::size_t files = 0;
  for (const auto& e : fs::recursive_directory_iterator(demo)) {
    if (!e.is_regular_file()) continue;
    const auto rel = fs::relative(e.path(), demo);
    EXPECT_EQ(read_text(out / rel), read_text(e.path())) << rel;
    ++files;
  }
  EXPECT_GE(files, 39U);  // 36 logs, the questionnaires, feint.toml
}

TEST(SimulateKTargetsCli, ThreeTargetsPlacedPerRoundThenAnalyze) {
  TempDir dir;
  const auto study = dir / "study";
  const auto report = dir / "report";
  auto r = run_feint("simulate study --targets 3 --layout random --participants 4 --iterations 6 --seed 5 -o " +
                     shell_quote(study.string()));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  feint::io::CsvReader log((study / "logs" / "P01.csv.gz").string());
  EXPECT_GE(log.column("target2_y"), 0);
  EXPECT_LT(log.column("target3_x"), 0);
  EXPECT_LT(log.column("pad"), 0);
  EXPECT_NE(read_text(study / "feint.toml").find("# 3 targets, placed per round"), std::string::npos);

  r = run_feint("analyze " + shell_quote(study.string()) + " -o " + shell_quote(report.string()));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string md = read_text(report / "report.md");
  EXPECT_NE(md.find("3 targets and a pointer"), std::string::npos) << md.substr(0, 3000);
  EXPECT_NE(md.find("placed per round (48 layouts)"), std::string::npos);
  // Every trial scored, targets 0..2 named by index.
  feint::io::CsvReader scores((report / "scores.csv").string());
  const int target = scores.column("target");
  ASSERT_GE(target, 0);
  int rows = 0, highest = 0;
  while (scores.next()) {
    ++rows;
    highest = std::max(highest, std::stoi(std::string(scores.field(static_cast<std::size_t>(target)))));
  }
  EXPECT_EQ(rows, 48);
  EXPECT_EQ(highest, 2);
}

TEST(SimulateKTargetsCli, BadTargetsOrLayoutIsAUsageError) {
  TempDir dir;
  auto r = run_feint("simulate study --targets 1 -o " + shell_quote((dir / "a").string()));
  EXPECT_EQ(r.exit_code, 64) << r.err;
  EXPECT_NE(r.err.find("--targets 1"), std::string::npos) << r.err;
  r = run_feint("simulate study --layout circle -o " + shell_quote((dir / "b").string()));
  EXPECT_EQ(r.exit_code, 64) << r.err;
  EXPECT_NE(r.err.find("--layout 'circle'"), std::string::npos) << r.err;
}
