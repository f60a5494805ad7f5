// End-to-end tests of `feint analyze`: a study folder in, every table out, settings from
// feint.toml with the command line taking precedence.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "cli/cli_helpers.hpp"
#include "feint/io/csv.hpp"
#include "feint/io/number.hpp"

namespace fs = std::filesystem;
using feint::test::read_text;
using feint::test::run_feint;
using feint::test::shell_quote;
using feint::test::TempDir;
using feint::test::write_text;

namespace {

// A small study: two conditions x 5 participants x 3 iterations; each trace moves the pad toward
// a participant-dependent side, so error differs between participants (non-zero variance).
void make_study(const fs::path& dir, bool with_questionnaire = true) {
  std::ostringstream logs;
  logs << "participant,condition,iteration,strategy,variant,target,t,pad,pad_speed\n";
  const char* conditions[] = {"adaptive", "random"};
  for (int c = 0; c < 2; ++c) {
    for (int p = 1; p <= 5; ++p) {
      for (int it = 1; it <= 3; ++it) {
        const bool right = (p + it) % 2 == 0;
        double pad = 0.5;
        for (int k = 0; k <= 30; ++k) {
          logs << "P" << c << p << "," << conditions[c] << "," << it << ",switching,main,"
               << (right ? "right" : "left") << "," << k * 0.1 << "," << pad << ",0.5\n";
          // Moves toward the true target, but participant p starts the wrong way for p steps.
          const double step = (k < p + c ? -0.05 : 0.05) * (right ? 1 : -1);
          pad = std::min(1.0, std::max(0.0, pad + step));
        }
      }
    }
  }
  write_text(dir / "logs" / "session.csv", logs.str());
  if (with_questionnaire) {
    std::ostringstream q;
    q << "participant,condition,entertainment,deception,intelligence,trust\n";
    for (int c = 0; c < 2; ++c) {
      for (int p = 1; p <= 5; ++p) {
        q << "P" << c << p << "," << conditions[c] << "," << (p % 7) + 1 << "," << 7 - p << ","
          << 3 + c << "," << (p + c) % 5 + 1 << "\n";
      }
    }
    write_text(dir / "questionnaire.csv", q.str());
  }
}

// Rows of a CSV as column-name -> value maps.
std::vector<std::map<std::string, std::string>> read_rows(const fs::path& path) {
  feint::io::CsvReader r(path.string());
  std::vector<std::map<std::string, std::string>> rows;
  while (r.next()) {
    std::map<std::string, std::string> row;
    for (std::size_t i = 0; i < r.header().size(); ++i)
      row[r.header()[i]] = std::string(r.field(i));
    rows.push_back(std::move(row));
  }
  return rows;
}

}  // namespace

TEST(Analyze, WritesEveryTableAndTheTablesAgreeWithTheScores) {
  TempDir dir;
  make_study(dir.path());
  const auto out = dir / "out";
  const auto r = run_feint("analyze " + shell_quote(dir.path().string()) + " -o " +
                           shell_quote(out.string()) + " --compare adaptive,random");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("30 trials scored, 0 rejected"), std::string::npos) << r.err;
  for (const char* stem : {"table1", "table1_compare", "likert", "likert_compare"}) {
    for (const char* ext : {"txt", "md", "tex", "csv", "json"}) {
      EXPECT_TRUE(fs::exists(out / (std::string(stem) + "." + ext))) << stem << "." << ext;
    }
  }
  EXPECT_TRUE(fs::exists(out / "scores.csv"));
  EXPECT_TRUE(fs::exists(out / "scores.csv.meta.json"));
  EXPECT_TRUE(fs::exists(out / "likert_summary.csv"));

  // The one-sample table's mean for (adaptive, iteration 2, error) is the mean of the scores.
  const auto scores = read_rows(out / "scores.csv");
  ASSERT_EQ(scores.size(), 30u);
  double sum = 0;
  int n = 0;
  for (const auto& s : scores) {
    if (s.at("condition") == "adaptive" && s.at("iteration") == "2") {
      sum += *feint::io::parse_double(s.at("error"));
      ++n;
    }
  }
  ASSERT_EQ(n, 5);
  bool found = false;
  for (const auto& row : read_rows(out / "table1.csv")) {
    if (row.at("metric") == "error" && row.at("iteration") == "2" &&
        row.at("group1") == "adaptive") {
      found = true;
      EXPECT_EQ(row.at("test"), "one_sample_t");
      EXPECT_NEAR(*feint::io::parse_double(row.at("mean1")), sum / n, 1e-12);
      EXPECT_EQ(row.at("mu"), "0.5");
    }
  }
  EXPECT_TRUE(found);
  const auto compare = read_rows(out / "table1_compare.csv");
  ASSERT_FALSE(compare.empty());
  EXPECT_EQ(compare.front().at("test"), "welch_t");
  EXPECT_EQ(compare.front().at("group2"), "random");
}

TEST(Analyze, ReadsSettingsFromTheStudyAndTheCommandLineWins) {
  TempDir dir;
  make_study(dir.path());
  write_text(dir / "feint.toml",
             "# settings of this study\nformats = [\"csv\"]\nlikert-reference = 3.5\n"
             "[analyze]\nalternative = \"greater\"\n");
  const auto out = dir / "out";
  auto r =
      run_feint("analyze " + shell_quote(dir.path().string()) + " -o " + shell_quote(out.string()));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(fs::exists(out / "table1.csv"));
  EXPECT_FALSE(fs::exists(out / "table1.txt"));
  const auto table = read_rows(out / "table1.csv");
  ASSERT_FALSE(table.empty());
  EXPECT_EQ(table.front().at("alternative"), "greater");
  const auto likert = read_rows(out / "likert.csv");
  ASSERT_FALSE(likert.empty());
  EXPECT_EQ(likert.front().at("mu"), "3.5");

  const auto out2 = dir / "out2";
  r = run_feint("analyze " + shell_quote(dir.path().string()) + " -o " +
                shell_quote(out2.string()) + " --formats json --alternative less");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(fs::exists(out2 / "table1.json"));
  EXPECT_FALSE(fs::exists(out2 / "table1.csv"));
  EXPECT_NE(read_text(out2 / "table1.json").find("\"less\""), std::string::npos);
}

TEST(Analyze, ListOptionsBeforeTheStudyDoNotSwallowIt) {
  TempDir dir;
  make_study(dir.path(), false);
  const auto out = dir / "out";
  const auto r = run_feint("analyze --metric error=0.4 --formats csv,json " +
                           shell_quote(dir.path().string()) + " -o " + shell_quote(out.string()));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(fs::exists(out / "table1.json"));
  const auto table = read_rows(out / "table1.csv");
  ASSERT_FALSE(table.empty());
  for (const auto& row : table) EXPECT_EQ(row.at("mu"), "0.4");
}

TEST(Analyze, WorksWithoutAQuestionnaire) {
  TempDir dir;
  make_study(dir.path(), false);
  const auto out = dir / "out";
  const auto r = run_feint("analyze " + shell_quote(dir.path().string()) + " -o " +
                           shell_quote(out.string()) + " --formats text");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(fs::exists(out / "table1.txt"));
  EXPECT_FALSE(fs::exists(out / "likert.txt"));
}

TEST(Analyze, RejectsBadStudiesAndSettingsWithDistinctExitCodes) {
  TempDir dir;
  // No such folder: cannot read -> 74.
  auto r = run_feint("analyze " + shell_quote((dir / "missing").string()));
  EXPECT_EQ(r.exit_code, 74);
  EXPECT_NE(r.err.find("does not exist"), std::string::npos) << r.err;
  // A folder without logs/: invalid study -> 65.
  fs::create_directories(dir / "empty");
  r = run_feint("analyze " + shell_quote((dir / "empty").string()) + " -o " +
                shell_quote((dir / "o1").string()));
  EXPECT_EQ(r.exit_code, 65);
  EXPECT_NE(r.err.find("no logs/ folder"), std::string::npos) << r.err;
  // An unknown setting in feint.toml -> 65, naming the file and the key.
  make_study(dir / "s");
  write_text(dir / "s" / "feint.toml", "alpah = 0.01\n");
  r = run_feint("analyze " + shell_quote((dir / "s").string()) + " -o " +
                shell_quote((dir / "o2").string()));
  EXPECT_EQ(r.exit_code, 65);
  EXPECT_NE(r.err.find("feint.toml: unknown setting 'alpah'"), std::string::npos) << r.err;
  // A bad option value -> 64.
  fs::remove(dir / "s" / "feint.toml");
  r = run_feint("analyze " + shell_quote((dir / "s").string()) + " -o " +
                shell_quote((dir / "o3").string()) + " --formats pdf");
  EXPECT_EQ(r.exit_code, 64);
  r = run_feint("analyze " + shell_quote((dir / "s").string()) + " -o " +
                shell_quote((dir / "o4").string()) + " --compare adaptive");
  EXPECT_EQ(r.exit_code, 64);
  EXPECT_NE(r.err.find("expected two conditions A,B"), std::string::npos) << r.err;
}

// The JZS prior scale from feint.toml and the command line: recorded in settings.toml,
// applied to the tables' Bayes factors, and refused when it is not a positive number or a name.
TEST(Analyze, BayesFactorPriorScaleFromTheSettingsFileAndTheCommandLine) {
  TempDir dir;
  make_study(dir.path());
  write_text(dir / "feint.toml", "formats = [\"csv\"]\nbf-prior-scale = \"wide\"\n");
  const auto wide = dir / "wide";
  auto r = run_feint("analyze " + shell_quote(dir.path().string()) + " --no-figures -o " +
                     shell_quote(wide.string()));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(read_text(wide / "settings.toml").find("bf-prior-scale = \"wide\""), std::string::npos);
  const auto medium = dir / "medium";
  r = run_feint("analyze " + shell_quote(dir.path().string()) + " --no-figures --bf-prior-scale medium -o " +
                shell_quote(medium.string()));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(read_text(medium / "settings.toml").find("bf-prior-scale = \"medium\""), std::string::npos);
  // Same t, other prior: every Bayes factor changes, none of the t statistics.
  const auto a = read_rows(wide / "table1.csv"), b = read_rows(medium / "table1.csv");
  ASSERT_EQ(a.size(), b.size());
  int changed = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].at("statistic"), b[i].at("statistic"));
    if (!a[i].at("bf10").empty()) changed += a[i].at("bf10") != b[i].at("bf10");
  }
  EXPECT_GT(changed, 0);
  for (const std::string bad : {"0", "-2", "huge"}) {
    r = run_feint("analyze " + shell_quote(dir.path().string()) + " --bf-prior-scale " + bad + " -o " +
                  shell_quote((dir / ("bad" + bad)).string()));
    EXPECT_EQ(r.exit_code, 64) << bad;
    EXPECT_NE(r.err.find("--bf-prior-scale"), std::string::npos) << r.err;
  }
}
