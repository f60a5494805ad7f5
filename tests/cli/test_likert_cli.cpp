// End-to-end tests of `feint likert`: the binary's output, error messages and exit codes.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "cli_helpers.hpp"

using feint::test::read_text;
using feint::test::run_feint;
using feint::test::shell_quote;
using feint::test::TempDir;
using feint::test::write_text;

namespace {

std::string data(const std::string& name) {
  return shell_quote(std::string(FEINT_TEST_DATA_DIR) + "/likert/" + name);
}

std::size_t lines(const std::string& text) {
  std::size_t n = 0;
  for (const char c : text) n += c == '\n';
  return n;
}

/// Runs `likert` on a file holding `content`; returns the result with the file name replaced by
/// FILE in stderr.
feint::test::RunResult likert_on(const std::string& content, const std::string& options = "") {
  TempDir dir;
  const auto path = (dir / "q.csv").string();
  write_text(path, content);
  auto r = run_feint("likert " + shell_quote(path) + " " + options);
  for (auto pos = r.err.find(path); pos != std::string::npos; pos = r.err.find(path)) {
    r.err.replace(pos, path.size(), "FILE");
  }
  return r;
}

}  // namespace

TEST(LikertCli, ThePapersAnalysisIsOneCommand) {
  const auto r = run_feint("likert " + data("wide.csv") + " --paper --condition adaptive");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("Likert items against R = 3.5, scale 1-7"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("Wilcoxon signed-rank (primary)"), std::string::npos);
  EXPECT_NE(r.out.find("One-sample t-test (the paper's analysis)"), std::string::npos);
  EXPECT_NE(r.out.find("--paper: the paper's analysis"), std::string::npos);
  // intelligence: t(4) = 16.50 against 3.5, p = 7.9e-05 (R: t.test(c(7,7,6,7,7), mu = 3.5)).
  EXPECT_NE(r.out.find("16.50   4  7.9e-05"), std::string::npos) << r.out;
  EXPECT_EQ(r.err, "");
}

TEST(LikertCli, OutOfRangeResponseIsInvalidDataWithThePreciseMessage) {
  const auto r = likert_on("participant,trust\nP01,3\nP07,9\n");
  EXPECT_EQ(r.exit_code, 65);
  EXPECT_EQ(r.err,
            "feint: error: FILE:3: column 'trust': 9 is outside the scale 1-7 (participant P07)\n");
  // The same answer is fine on a 0-10 scale.
  EXPECT_EQ(likert_on("participant,trust\nP01,3\nP07,9\n", "--scale 0-10").exit_code, 0);
}

TEST(LikertCli, EveryInvalidDataErrorHasExitCode65AndAMessage) {
  struct Case {
    std::string content, options, message;
  };
  const Case cases[] = {
      {"participant,trust\nP07,4.5\n", "",
       "FILE:2: column 'trust': 4.5 is not a whole number on the scale 1-7 (participant P07)"},
      {"participant,trust\nP07,maybe\n", "",
       "FILE:2: column 'trust': 'maybe' is not a number or a known label (participant P07); "
       "expected a whole number 1-7 or a label of the built-in 7-point agree map"},
      {"participant,trust\nP07,Agree\n", "--scale 1-6",
       "FILE:2: column 'trust': 'Agree' is not a number or a known label (participant P07); "
       "expected a whole number 1-6 (use --labels to map text answers)"},
      {"participant,trust\nP01,3\nP01,4\n", "",
       "FILE:3: participant P01 has a second row (first at line 2); the wide layout has one row "
       "per respondent"},
      {"participant,item,response\nP01,trust,3\nP01,trust,4\n", "",
       "FILE:3: participant P01 answered item 'trust' twice (first at line 2)"},
      {"participant,item,response\nP01,trust,0\n", "",
       "FILE:2: column 'response': 0 is outside the scale 1-7 (participant P01, item trust)"},
      {"participant,trust\n,3\n", "", "FILE:2: column 'participant': empty respondent id"},
      {"participant,condition,trust\nP01,,3\n", "",
       "FILE:2: column 'condition': empty condition (participant P01)"},
      {"id,trust\nP01,3\n", "",
       "FILE: no column 'participant' (the respondent id); name the study's column with "
       "--id-column (columns: id, trust)"},
      {"participant,trust\n", "", "FILE: no responses (a header but no data rows)"},
      {"participant,trust\nP01,3,3\n", "", "FILE:2: 3 fields where the header has 2"},
      {"participant,condition,trust\nP01,a,3\nP01,b,4\n", "--compare a,b",
       "FILE: participant P01 answered in both conditions a and b; Mann-Whitney and Welch compare "
       "independent groups"},
  };
  for (const auto& c : cases) {
    const auto r = likert_on(c.content, c.options);
    EXPECT_EQ(r.exit_code, 65) << c.message;
    EXPECT_EQ(r.err, "feint: error: " + c.message + "\n");
  }
}

TEST(LikertCli, BadOptionsAreUsageErrors) {
  const std::string wide = data("wide.csv");
  const char* bad[] = {
      "--scale 7-1",
      "--scale 1-x",
      "--layout diagonal",
      "--reverse honesty",
      "--items entertainment,honesty",
      "--compare adaptive",
      "--compare adaptive,placebo",
      "--compare adaptive,random --condition adaptive",
      "--paper --compare adaptive,random",
      "--condition placebo",
      "--composite fun",
      "--composite fun=entertainment,honesty",
      "--labels Agree",
      "--labels Agree=9",
      "--format pdf",
      "--alpha 2",
      "--p-adjust sometimes",
      "--reference x",
  };
  for (const char* options : bad) {
    const auto r = run_feint("likert " + wide + " " + options);
    EXPECT_EQ(r.exit_code, 64) << options << ": " << r.err;
    EXPECT_NE(r.err, "") << options;
  }
  EXPECT_NE(run_feint("likert " + wide + " --reverse honesty").err.find("no item 'honesty'"),
            std::string::npos);
}

TEST(LikertCli, UnreadableInputAndUnwritableOutputAreIoErrors) {
  EXPECT_EQ(run_feint("likert /nonexistent/q.csv").exit_code, 74);
  EXPECT_EQ(run_feint("likert " + data("wide.csv") + " -o /nonexistent/dir/out.txt").exit_code, 74);
}

TEST(LikertCli, InvalidDataLeavesNoOutputFile) {
  TempDir dir;
  write_text(dir / "q.csv", "participant,trust\nP01,3\nP07,9\n");
  const auto out = dir / "out.csv";
  const auto r = run_feint("likert " + shell_quote((dir / "q.csv").string()) + " --format csv -o " +
                           shell_quote(out.string()));
  EXPECT_EQ(r.exit_code, 65);
  EXPECT_FALSE(std::filesystem::exists(out));
}

TEST(LikertCli, QualtricsExportEndToEnd) {
  TempDir dir;
  const auto out = dir / "q.csv";
  const auto r = run_feint("likert " + data("qualtrics.csv") + " --format csv -o " +
                           shell_quote(out.string()));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto csv = read_text(out);
  EXPECT_EQ(lines(csv), 1u + 3u * 2u);  // header + 2 tests x 3 questions
  // Q1 = Strongly agree, Agree, Somewhat agree, STRONGLY AGREE = 7 6 5 7: n 4, mean 6.25.
  EXPECT_NE(csv.find("Q1,,wilcoxon_signed_rank,"), std::string::npos) << csv;
  EXPECT_NE(csv.find(",4,,6.25,"), std::string::npos) << csv;
  // Q3 has one empty answer: n 3.
  EXPECT_NE(csv.find("Q3,,one_sample_t,One Sample t-test,two.sided,4,,,3,"), std::string::npos)
      << csv;
  // The text table says what was mapped and skipped.
  const auto t = run_feint("likert " + data("qualtrics.csv"));
  EXPECT_NE(
      t.out.find("Qualtrics export: the question-text and ImportId header rows were skipped."),
      std::string::npos)
      << t.out;
  EXPECT_NE(t.out.find("11 text answers mapped to scale points by the built-in 7-point agree"),
            std::string::npos);
}

TEST(LikertCli, GoogleFormsTextAnswersWithAUserLabelMap) {
  const std::string forms =
      "Timestamp,Your id,I enjoyed it,I trusted the robot\n"
      "2026/05/01 10:00:00,S1,A lot,Not at all\n"
      "2026/05/01 10:05:00,S2,Very much,A little\n"
      "2026/05/01 10:09:00,S3,Somewhat,\n";
  const auto r = likert_on(forms,
                           "--id-column 'Your id' --scale 1-5 --labels 'Not at all=1,A little=2,"
                           "Somewhat=3,A lot=4,Very much=5' --format csv");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("I enjoyed it,,wilcoxon_signed_rank,"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("I trusted the robot,,one_sample_t,One Sample t-test,two.sided,3,,,2,,1.5,"),
            std::string::npos)
      << r.out;
}

TEST(LikertCli, LongAndWideLayoutsGiveTheSameTable) {
  const auto wide = run_feint("likert " + data("wide.csv") + " --format csv");
  const auto lng = run_feint("likert " + data("long.csv") + " --format csv");
  ASSERT_EQ(wide.exit_code, 0) << wide.err;
  ASSERT_EQ(lng.exit_code, 0) << lng.err;
  EXPECT_EQ(wide.out, lng.out);
  // Forcing the wrong layout is an error that says what the long layout needs.
  const auto forced = run_feint("likert " + data("wide.csv") + " --layout long");
  EXPECT_EQ(forced.exit_code, 65);
  EXPECT_NE(forced.err.find("the long layout needs columns 'item' and 'response'"),
            std::string::npos);
}

TEST(LikertCli, ReverseAndCompositeEndToEnd) {
  const auto r = run_feint("likert " + data("golden_input.csv") +
                           " --reverse boring --composite enjoyment=entertainment,boring,fun "
                           "--condition adaptive --format json --apa --alpha-missing complete");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // psych::alpha(na.omit(...)) raw alpha of the adaptive condition (tests/golden/likert/golden.csv).
  EXPECT_NE(r.out.find("\"cronbach_alpha\": 0.9146884272997"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\"apa\": \"V = "), std::string::npos);
}

TEST(LikertCli, SummaryFileAndStdin) {
  TempDir dir;
  const auto summary = dir / "summary.csv";
  const std::string stdin_text = read_text(std::string(FEINT_TEST_DATA_DIR) + "/likert/wide.csv");
  const auto r = run_feint("likert - --summary " + shell_quote(summary.string()), stdin_text);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto csv = read_text(summary);
  EXPECT_EQ(lines(csv), 1u + 4u * 2u);
  EXPECT_NE(csv.find("random,intelligence,item,4,1,4.75,0.5,5,4.75,5,0.25,0,25,75,0,0,0,1,3,0,0,"),
            std::string::npos)
      << csv;
}

TEST(LikertCli, PaperModeOnAFileWithoutThePapersItemsSaysWhy) {
  const auto r = likert_on("participant,fun,trust\nP1,3,4\n", "--paper");
  EXPECT_EQ(r.exit_code, 64);
  EXPECT_EQ(
      r.err.rfind("feint: error: --paper analyses the paper's items (entertainment, deception, "
                  "intelligence, trust; name others with --items): --items: no column "
                  "'entertainment'",
                  0),
      0u)
      << r.err;
  // With --items the paper's settings (reference 3.5) apply to the study's own items.
  const auto ok = likert_on("participant,fun,trust\nP1,3,4\nP2,5,2\n", "--paper --items fun,trust");
  EXPECT_EQ(ok.exit_code, 0) << ok.err;
  EXPECT_NE(ok.out.find("against R = 3.5"), std::string::npos);
}

TEST(LikertCli, ListOptionsAreRepeatableAndDoNotSwallowTheFile) {
  // A list option before the file, and options after it: the file stays the positional argument.
  const auto r = run_feint(
      "likert --reverse trust --reverse deception --items entertainment,trust "
      "--items deception " +
      data("wide.csv") + " --condition adaptive --format csv");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(lines(r.out), 1u + 3u * 2u);
  EXPECT_EQ(r.out.find("intelligence"), std::string::npos);
  // trust reversed: adaptive 2 3 2 1 2 -> 6 5 6 7 6, mean 6.
  EXPECT_NE(r.out.find("trust,,one_sample_t,One Sample t-test,two.sided,4,adaptive,,5,,6,"),
            std::string::npos)
      << r.out;
}

// --bf-prior-scale: accepted by name or number, stated in the note, and changes the
// t-tests' Bayes factors (the values themselves: tests/tables/test_likert.cpp, against the exact
// JZS integral); bad scales are usage errors that name the option.
TEST(LikertCli, BayesFactorPriorScaleIsSettable) {
  const auto medium = run_feint("likert " + data("wide.csv") + " --format csv");
  const auto wide = run_feint("likert " + data("wide.csv") + " --format csv --bf-prior-scale wide");
  const auto one = run_feint("likert " + data("wide.csv") + " --format csv --bf-prior-scale 1");
  ASSERT_EQ(medium.exit_code, 0) << medium.err;
  ASSERT_EQ(wide.exit_code, 0) << wide.err;
  EXPECT_EQ(wide.out, one.out);
  EXPECT_NE(wide.out, medium.out);
  const auto text = run_feint("likert " + data("wide.csv") + " --bf-prior-scale ultrawide");
  EXPECT_NE(text.out.find("scale r = 1.414 (ultrawide)"), std::string::npos) << text.out;
  for (const std::string bad : {"0", "-0.5", "broad", "inf"}) {
    const auto r = run_feint("likert " + data("wide.csv") + " --bf-prior-scale " + bad);
    EXPECT_EQ(r.exit_code, 64) << bad;
    EXPECT_NE(r.err.find("--bf-prior-scale '" + bad + "'"), std::string::npos) << r.err;
  }
}
