// End-to-end tests of `feint simulate study` (runs the feint binary, FEINT_EXE).
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "cli_helpers.hpp"
#include "feint/io/csv.hpp"
#include "feint/io/number.hpp"

using feint::test::read_text;
using feint::test::run_feint;
using feint::test::shell_quote;
using feint::test::TempDir;
using feint::test::write_text;

namespace {
/// All records of a (possibly gzipped) CSV file, header first, joined as text.
std::string slurp_csv(const std::filesystem::path& p) {
  feint::io::CsvReader r(p.string());
  std::string out;
  for (const auto& h : r.header()) out += h + ",";
  out += "\n";
  while (r.next()) {
    for (const auto& f : r.fields()) out += std::string(f) + ",";
    out += "\n";
  }
  return out;
}
}  // namespace

TEST(SimulateStudyCli, WritesOneGzippedLogPerParticipantAndAQuestionnaire) {
  TempDir dir;
  const auto out = dir / "study";
  const auto r = run_feint("simulate study --out " + shell_quote(out.string()) +
                           " --participants 2 --iterations 4 --seed 9");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("4 participants"), std::string::npos) << r.out;
  for (const char* id : {"P01", "P02", "P03", "P04"}) {
    const auto log = out / "logs" / (std::string(id) + ".csv.gz");
    ASSERT_TRUE(std::filesystem::exists(log)) << log;
    feint::io::CsvReader csv(log.string());
    EXPECT_TRUE(csv.compressed());
    ASSERT_EQ(csv.header().size(), 11u);
    EXPECT_EQ(csv.header()[7], "pad");
    EXPECT_EQ(csv.header()[9], "robot_x");  // the robot's path (formats.md "Robot path")
    EXPECT_EQ(csv.header()[10], "robot_y");
    std::vector<std::string> iterations;
    while (csv.next()) {
      EXPECT_EQ(csv.field(0), id);
      const std::string cond(csv.field(1));
      EXPECT_EQ(cond, std::string(id) <= "P02" ? "adaptive" : "random");
      if (iterations.empty() || iterations.back() != csv.field(2)) iterations.emplace_back(csv.field(2));
      EXPECT_EQ(csv.field(8), "0.8");
    }
    EXPECT_EQ(iterations, (std::vector<std::string>{"1", "2", "3", "4"}));
  }
  const std::string q = read_text(out / "questionnaire.csv");
  EXPECT_EQ(q.substr(0, q.find('\n')), "participant,condition,entertainment,deception,intelligence,trust");
  EXPECT_EQ(std::count(q.begin(), q.end(), '\n'), 5);
}

TEST(SimulateStudyCli, SameSeedSameDataDifferentSeedDifferentData) {
  TempDir dir;
  const auto a = dir / "a", b = dir / "b", c = dir / "c";
  for (const auto& [path, seed] : {std::pair{a, "1"}, std::pair{b, "1"}, std::pair{c, "2"}}) {
    const auto r = run_feint("simulate study --participants 1 --iterations 3 --seed " + std::string(seed) +
                             " --out " + shell_quote(path.string()));
    ASSERT_EQ(r.exit_code, 0) << r.err;
  }
  EXPECT_EQ(slurp_csv(a / "logs" / "P01.csv.gz"), slurp_csv(b / "logs" / "P01.csv.gz"));
  EXPECT_EQ(read_text(a / "questionnaire.csv"), read_text(b / "questionnaire.csv"));
  EXPECT_NE(slurp_csv(a / "logs" / "P01.csv.gz"), slurp_csv(c / "logs" / "P01.csv.gz"));
}

// --design within: each participant in both conditions, counterbalanced (P01 adaptive first, P02
// random first), one log per participant with a block column, the design in feint.toml, and the
// analysis reads it: paired comparisons with no flag.
TEST(SimulateStudyCli, AWithinDesignGivesEachParticipantBothConditionsInCounterbalancedBlocks) {
  TempDir dir;
  const auto out = dir / "study";
  const auto r = run_feint("simulate study --design within --out " + shell_quote(out.string()) +
                           " --participants 4 --iterations 3 --seed 9");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("4 participants, each in both conditions"), std::string::npos) << r.out;
  // A questionnaire answered after each condition: one row per participant and condition.
  const std::string q = read_text(out / "questionnaire.csv");
  EXPECT_EQ(std::count(q.begin(), q.end(), '\n'), 1 + 4 * 2) << q;
  EXPECT_NE(q.find("\nP02,random,"), std::string::npos) << q;
  EXPECT_NE(read_text(out / "feint.toml").find("\ndesign = \"within\"\n"), std::string::npos);
  for (const char* id : {"P01", "P02", "P03", "P04"}) {
    feint::io::CsvReader csv((out / "logs" / (std::string(id) + ".csv.gz")).string());
    ASSERT_EQ(csv.header()[2], "block");
    std::vector<std::string> seen;  // condition/block/iteration, one per trial
    while (csv.next()) {
      const std::string key = std::string(csv.field(1)) + "/" + std::string(csv.field(2)) + "/" + std::string(csv.field(3));
      if (seen.empty() || seen.back() != key) seen.push_back(key);
    }
    const bool adaptive_first = std::string(id) == "P01" || std::string(id) == "P03";
    const std::string first = adaptive_first ? "adaptive" : "random", second = adaptive_first ? "random" : "adaptive";
    EXPECT_EQ(seen, (std::vector<std::string>{first + "/1/1", first + "/1/2", first + "/1/3", second + "/2/1",
                                              second + "/2/2", second + "/2/3"}))
        << id;
  }
  const auto a = run_feint("analyze " + shell_quote(out.string()) + " -o " + shell_quote((dir / "out").string()) +
                           " --no-figures");
  ASSERT_EQ(a.exit_code, 0) << a.err;
  EXPECT_NE(read_text(dir / "out" / "table1_compare.txt").find("Paired t-tests"), std::string::npos);
  const auto bad = run_feint("simulate study --design crossed --out " + shell_quote((dir / "x").string()));
  EXPECT_EQ(bad.exit_code, 64);
  EXPECT_NE(bad.err.find("--design 'crossed': expected between"), std::string::npos) << bad.err;
}

TEST(SimulateStudyCli, BadOptionsAndAFileInTheWayAreUsageErrors) {
  TempDir dir;
  for (const std::string args : {"simulate study", "simulate study --out x --participants 0",
                                 "simulate study --out x --lambda 2", "simulate study --out x --iterations 0",
                                 "simulate study --out x --sample-rate 0"}) {
    const auto r = run_feint(args);
    EXPECT_EQ(r.exit_code, 64) << args << "\n" << r.err;
  }
  const auto blocker = dir / "file";
  write_text(blocker, "not a directory");
  const auto r = run_feint("simulate study --participants 1 --iterations 1 --out " + shell_quote(blocker.string()));
  // As feint analyze -o says of a file in the way: the command line names a file, not a folder.
  EXPECT_EQ(r.exit_code, 64) << r.err;
  EXPECT_NE(r.err.find("exists and is not a folder"), std::string::npos) << r.err;
  EXPECT_EQ(read_text(blocker), "not a directory");
}

namespace {
std::size_t logs_in(const std::filesystem::path& study) {
  std::size_t n = 0;
  for (const auto& e : std::filesystem::directory_iterator(study / "logs")) n += e.is_regular_file();
  return n;
}
}  // namespace

// A second run into the same folder never mixes with the first: it is refused unless --replace is
// given, and then the folder is replaced whole (no log of the first run is left beside the new
// questionnaire). --replace never deletes a file that feint simulate study did not write.
TEST(SimulateStudyCli, ANonEmptyFolderIsRefusedUnlessReplacedAndThenReplacedWhole) {
  TempDir dir;
  const auto sim = dir / "sim";
  const std::string out = " --iterations 2 --seed 3 --out " + shell_quote(sim.string());
  ASSERT_EQ(run_feint("simulate study --participants 3" + out).exit_code, 0);
  ASSERT_EQ(logs_in(sim), 6u);
  const std::string first_questionnaire = read_text(sim / "questionnaire.csv");

  auto r = run_feint("simulate study --participants 1" + out);
  EXPECT_EQ(r.exit_code, 64) << r.err;
  EXPECT_NE(r.err.find("is not empty"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("--replace"), std::string::npos) << r.err;
  EXPECT_EQ(logs_in(sim), 6u);  // untouched
  EXPECT_EQ(read_text(sim / "questionnaire.csv"), first_questionnaire);

  r = run_feint("simulate study --participants 1 --replace" + out);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(logs_in(sim), 2u);  // the first run's P03..P06 are gone
  const std::string q = read_text(sim / "questionnaire.csv");
  EXPECT_EQ(std::count(q.begin(), q.end(), '\n'), 3);
  EXPECT_TRUE(std::filesystem::exists(sim / ".feint-simulate.json"));

  // A file the user put there is never deleted, even with --replace.
  write_text(sim / "notes.txt", "my notes");
  r = run_feint("simulate study --participants 2 --replace" + out);
  EXPECT_EQ(r.exit_code, 64) << r.err;
  EXPECT_NE(r.err.find("'notes.txt'"), std::string::npos) << r.err;
  EXPECT_EQ(read_text(sim / "notes.txt"), "my notes");
  EXPECT_EQ(logs_in(sim), 2u);

  // Nor is a folder of data that feint did not write (no manifest, other names).
  const auto data = dir / "data";
  write_text(data / "logs" / "participant-a.csv", "t,pad\n");
  r = run_feint("simulate study --participants 1 --replace --iterations 1 --out " +
                shell_quote(data.string()));
  EXPECT_EQ(r.exit_code, 64) << r.err;
  EXPECT_EQ(read_text(data / "logs" / "participant-a.csv"), "t,pad\n");
}

// A simulated study carries its design: `feint analyze DIR` with no flag compares its two
// conditions and scores confusion on the scale of its reference (raw, the paper's 0.95).
TEST(SimulateStudyCli, TheStudyCarriesItsDesignAndIsAnalysedWithNoFlag) {
  TempDir dir;
  const auto sim = dir / "sim";
  ASSERT_EQ(run_feint("simulate study --participants 3 --iterations 3 --seed 5 --out " +
                      shell_quote(sim.string()))
                .exit_code,
            0);
  const std::string toml = read_text(sim / "feint.toml");
  EXPECT_NE(toml.find("compare = \"adaptive,random\""), std::string::npos) << toml;
  EXPECT_NE(toml.find("confusion-norm = \"raw\""), std::string::npos) << toml;
  EXPECT_NE(toml.find("metric = [\"error=0.5\", \"confusion=0.95@raw\"]"), std::string::npos) << toml;
  const auto out = dir / "out";
  const auto r = run_feint("analyze " + shell_quote(sim.string()) + " -o " +
                           shell_quote(out.string()) + " --no-figures");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(std::filesystem::exists(out / "table1_compare.csv"));
  const std::string md = read_text(out / "report.md");
  EXPECT_NE(md.find("- Comparison: adaptive against random\n"), std::string::npos) << md.substr(0, 1500);
  EXPECT_NE(md.find("- Settings file: feint.toml"), std::string::npos);
  EXPECT_NE(read_text(out / "settings.toml").find("confusion-norm = \"raw\""), std::string::npos);
}

// Three conditions (data/demo-three, made by `feint simulate study --conditions
// adaptive,random,fixed-block`): analysed with no flag, the conditions are compared by the omnibus
// tests and their pairs, never by an arbitrary two of them (docs/analysis.md "Three or more
// conditions").
TEST(SimulateStudyCli, ThreeConditionsAreComparedByOmnibusTestsAndTheirPairsWithNoFlag) {
  TempDir dir;
  const auto out = dir / "out";
  const auto r = run_feint("analyze " + shell_quote(std::string(FEINT_SOURCE_DIR) + "/data/demo-three") + " -o " +
                           shell_quote(out.string()) + " --no-figures");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // No Table 1 comparison of two of the three, and no exposure table of two of them: said why.
  EXPECT_FALSE(std::filesystem::exists(out / "table1_compare.csv"));
  EXPECT_FALSE(std::filesystem::exists(out / "exposure_by_condition.csv"));
  EXPECT_NE(r.err.find("no condition x exposure table: it compares two conditions and the study has 3"),
            std::string::npos)
      << r.err;
  const std::string findings = read_text(out / "findings.json");
  for (const char* id :
       {"\"H1-model-condition-error\"", "\"H1-model-pair-error-adaptive-fixed-block\"",
        "\"H1-model-pair-confusion-fixed-block-random\"", "\"H1-model-trend-error-random\"",
        "\"H2-conditions-deception\"", "\"H2-pair-trust-adaptive-random\"", "\"H1-exposure-error\""})
    EXPECT_NE(findings.find(id), std::string::npos) << id;
  EXPECT_EQ(findings.find("\"H2-compare-"), std::string::npos);
  // The questionnaire across the conditions: Kruskal-Wallis per item, then the pairs.
  const std::string q = read_text(out / "likert_conditions.csv");
  EXPECT_EQ(std::count(q.begin(), q.end(), '\n'), 1 + 4 + 3 * 4 * 2) << q.substr(0, 400);
  EXPECT_NE(q.find("kruskal_wallis"), std::string::npos);
  const std::string md = read_text(out / "report.md");
  EXPECT_NE(md.find("Questionnaire across the conditions"), std::string::npos);
  EXPECT_NE(md.find("- Design: conditions between participants"), std::string::npos) << md.substr(0, 2000);
  EXPECT_NE(md.find("- Comparison: all 3 conditions: the omnibus tests, then each pair"), std::string::npos);
  // The Results answer the hypotheses across the conditions with the omnibus tests, not a pair.
  EXPECT_NE(md.find("**H1** (exploratory): Error and confusion differ among the conditions adaptive, random and "
                    "fixed-block. Error: partial *η*² = "),
            std::string::npos)
      << md.substr(0, 3000);
  EXPECT_NE(md.find("Deception: rank *ε*² = "), std::string::npos);
  EXPECT_EQ(md.find("No hypothesis was tested"), std::string::npos);
}

TEST(SimulateStudyCli, ConditionsNameTheAlgorithmsOrGiveThemNames) {
  TempDir dir;
  const auto sim = dir / "sim";
  const auto ok = run_feint("simulate study -p 2 -n 3 --conditions a=random,b=random,c=fixed-block --out " +
                            shell_quote(sim.string()));
  ASSERT_EQ(ok.exit_code, 0) << ok.err;
  EXPECT_NE(ok.out.find("6 participants (2 per condition: a, b, c)"), std::string::npos) << ok.out;
  const std::string q = read_text(sim / "questionnaire.csv");
  EXPECT_NE(q.find("P05,c,"), std::string::npos) << q;
  const auto bad = run_feint("simulate study --conditions adaptive --out " + shell_quote((dir / "x").string()));
  EXPECT_EQ(bad.exit_code, 64);
  EXPECT_NE(bad.err.find("1 condition(s) given; a study compares two or more"), std::string::npos) << bad.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "x"));
}
