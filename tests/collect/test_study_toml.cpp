// The study's feint.toml that feint collect writes at its first start: the design feint analyze
// reads (the comparison, confusion and its reference on one scale), never over an existing file.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "cli/cli_helpers.hpp"
#include "feint/collect/options.hpp"

namespace fs = std::filesystem;
using feint::test::read_text;
using feint::test::run_feint;
using feint::test::shell_quote;
using feint::test::TempDir;
using feint::test::write_text;

TEST(CollectStudyToml, NamesTheComparisonAndOneScaleAndNeverReplacesAFile) {
  TempDir dir;
  const feint::collect::Settings s;  // the paper's study: adaptive and random
  ASSERT_TRUE(feint::collect::write_study_toml(dir.path(), s, "test"));
  const std::string toml = read_text(dir / "feint.toml");
  EXPECT_NE(toml.find("compare = \"adaptive,random\"\n"), std::string::npos) << toml;
  // collect gives each participant one condition: the design is declared, so that a participant id
  // reused in another condition is refused rather than paired.
  EXPECT_NE(toml.find("\ndesign = \"between\"\n"), std::string::npos) << toml;
  EXPECT_NE(toml.find("confusion-norm = \"raw\"\n"), std::string::npos) << toml;
  EXPECT_NE(toml.find("metric = [\"error=0.5\", \"confusion=0.95@raw\"]\n"), std::string::npos);
  EXPECT_NE(toml.find("likert-scale = \"1-7\"\n"), std::string::npos);
  EXPECT_FALSE(fs::exists(dir / ".feint.toml.feint-tmp"));
  // A second start, or a study with its own settings: the file stays as it is.
  write_text(dir / "feint.toml", "alpha = 0.01\n");
  EXPECT_FALSE(feint::collect::write_study_toml(dir.path(), s, "test"));
  EXPECT_EQ(read_text(dir / "feint.toml"), "alpha = 0.01\n");
  // Three conditions: no comparison of two by default.
  feint::collect::Settings three = s;
  three.conditions.push_back({"fixed-block", feint::sim::Algorithm::fixed_block, 0.5});
  EXPECT_EQ(feint::collect::study_toml(three, "test").find("\ncompare ="), std::string::npos);
}

// feint analyze reads the file as its settings: a study collected with the defaults is compared,
// with confusion scored on the scale of its reference.
TEST(CollectStudyToml, FeintAnalyzeReadsItAsTheStudysSettings) {
  TempDir dir;
  const auto study = dir / "study";
  ASSERT_EQ(run_feint("simulate study --participants 3 --iterations 3 --seed 2 --out " +
                      shell_quote(study.string()))
                .exit_code,
            0);
  write_text(study / "feint.toml", feint::collect::study_toml(feint::collect::Settings{}, "test"));
  const auto r = run_feint("analyze " + shell_quote(study.string()) + " -o " +
                           shell_quote((dir / "out").string()) + " --no-figures");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(fs::exists(dir / "out" / "table1_compare.csv"));
  const std::string settings = read_text(dir / "out" / "settings.toml");
  EXPECT_NE(settings.find("confusion-norm = \"raw\""), std::string::npos) << settings;
  EXPECT_NE(settings.find("compare = \"adaptive,random\""), std::string::npos) << settings;
}
