// `feint analyze` reads a real survey export: the questionnaire options of feint likert
// are settings of feint.toml and options of feint analyze, and preview/unfinished rows are not
// participants.
#include <gtest/gtest.h>

#include <filesystem>
#include <sstream>
#include <string>

#include "cli/cli_helpers.hpp"

namespace fs = std::filesystem;
using feint::test::read_text;
using feint::test::run_feint;
using feint::test::RunResult;
using feint::test::shell_quote;
using feint::test::TempDir;
using feint::test::write_text;

namespace {

std::string q(const fs::path& p) { return shell_quote(p.string()); }

void make_logs(const fs::path& study) {
  std::ostringstream logs;
  logs << "participant,condition,iteration,target,t,pad,pad_speed\n";
  for (int p = 1; p <= 3; ++p) {
    for (int k = 0; k <= 5; ++k) {
      logs << "P" << p << ",adaptive,1,right," << k * 0.2 << "," << 0.5 + 0.05 * k * p / 3.0
           << ",0.5\n";
    }
  }
  write_text(study / "logs" / "s.csv", logs.str());
}

// A Qualtrics export: text answers, a preview, an unfinished response, items Q5_1 and Q5_2.
const char* kExport =
    "StartDate,Status,Progress,Finished,ResponseId,PROLIFIC_PID,grp,Q5_1,Q5_2\n"
    "Start Date,Response Type,Progress,Finished,Response ID,PID,grp,I trusted it.,It was fun.\n"
    "\"{\"\"ImportId\"\":\"\"startDate\"\"}\",\"{\"\"ImportId\"\":\"\"status\"\"}\","
    "\"{\"\"ImportId\"\":\"\"progress\"\"}\",\"{\"\"ImportId\"\":\"\"finished\"\"}\","
    "\"{\"\"ImportId\"\":\"\"_recordId\"\"}\",\"{\"\"ImportId\"\":\"\"pid\"\"}\","
    "\"{\"\"ImportId\"\":\"\"grp\"\"}\",\"{\"\"ImportId\"\":\"\"QID5_1\"\"}\","
    "\"{\"\"ImportId\"\":\"\"QID5_2\"\"}\"\n"
    "d,IP Address,100,True,R_1,p1,A,Sehr gut,Gut\n"
    "d,Survey Preview,100,True,R_2,,A,Schlecht,Schlecht\n"
    "d,IP Address,100,True,R_3,p3,B,Gut,Sehr gut\n"
    "d,IP Address,50,False,R_4,p4,B,Gut,\n"
    "d,IP Address,100,True,R_5,p5,A,Gut,Gut\n"
    "d,IP Address,100,True,R_6,p6,B,Sehr gut,Schlecht\n";

const char* kSettings =
    "id-column = \"PROLIFIC_PID\"\n"
    "condition-column = \"grp\"\n"
    "items = [\"trust=Q5_1\", \"fun=Q5_2\"]\n"
    "labels = \"Schlecht=1,Gut=2,Sehr gut=3\"\n"
    "likert-scale = \"1-3\"\n"
    "reverse = [\"fun\"]\n";

}  // namespace

TEST(AnalyzeQuestionnaire, ReadsASurveyExportWithSettingsFromFeintToml) {
  TempDir dir;
  const auto study = dir / "study";
  make_logs(study);
  write_text(study / "questionnaire.csv", kExport);
  write_text(study / "feint.toml", kSettings);
  const RunResult r = run_feint("analyze " + q(study) + " -o " + q(dir / "out"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string summary = read_text(dir / "out" / "likert_summary.csv");
  // Four participants (R_2 is a preview, R_4 unfinished), items renamed, fun reversed.
  EXPECT_NE(summary.find("A,trust,item,2,"), std::string::npos) << summary;
  EXPECT_NE(summary.find("B,trust,item,2,"), std::string::npos) << summary;
  EXPECT_NE(summary.find("A,fun,item,2,"), std::string::npos) << summary;
  // The note is wrapped: compare it as one line.
  std::string text;
  for (const char c : read_text(dir / "out" / "likert.txt")) {
    const char d = c == '\n' ? ' ' : c;
    if (!(d == ' ' && !text.empty() && text.back() == ' ')) text += d;
  }
  EXPECT_NE(text.find("fun (reversed)"), std::string::npos) << text;
  EXPECT_NE(text.find("2 responses of the survey export excluded"), std::string::npos) << text;
  // Named by the id column (PROLIFIC_PID), by line when it is empty.
  EXPECT_NE(text.find("line 5 (Survey Preview)"), std::string::npos) << text;
  EXPECT_NE(text.find("p4 (unfinished (Finished False, Progress 50))"), std::string::npos) << text;
}

TEST(AnalyzeQuestionnaire, TheSameOptionsWorkOnTheCommandLineAndKeepUnfinished) {
  TempDir dir;
  const auto study = dir / "study";
  make_logs(study);
  write_text(study / "questionnaire.csv", kExport);
  const RunResult r =
      run_feint("analyze " + q(study) + " -o " + q(dir / "out") +
                " --id-column PROLIFIC_PID --condition-column grp --items trust=Q5_1,fun=Q5_2"
                " --labels 'Schlecht=1,Gut=2,Sehr gut=3' --likert-scale 1-3 --keep-unfinished");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string summary = read_text(dir / "out" / "likert_summary.csv");
  EXPECT_NE(summary.find("B,trust,item,3,"), std::string::npos) << summary;  // R_4 kept
  // And on feint likert itself.
  const RunResult l = run_feint("likert " + q(study / "questionnaire.csv") +
                                " --id-column PROLIFIC_PID --condition-column grp --items "
                                "trust=Q5_1 --labels 'Schlecht=1,Gut=2,Sehr gut=3' --scale 1-3");
  ASSERT_EQ(l.exit_code, 0) << l.err;
  EXPECT_NE(l.out.find("2 responses of the survey export excluded"), std::string::npos) << l.out;
}
