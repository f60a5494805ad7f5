// "Files from other labs": each export that was read wrong or refused without a remedy
// is read right, or refused with a message naming the file, the row and column, and the option
// that fixes it. The files in tests/data/labs/ imitate each lab's export.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "feint/error.hpp"
#include "feint/io/csv.hpp"
#include "feint/io/participants.hpp"
#include "feint/io/questionnaire.hpp"
#include "feint/io/scores.hpp"
#include "feint/io/trace.hpp"

namespace fs = std::filesystem;
using feint::io::Diagnostic;
using feint::io::TraceOptions;
using feint::io::TraceReader;
using feint::io::Trial;

namespace {

std::string lab(const std::string& name) { return std::string(FEINT_TEST_DATA_DIR) + "/labs/" + name; }

fs::path dir() {
  const fs::path d = fs::temp_directory_path() / ("feint-test-labs-" + std::to_string(::getpid()));
  fs::create_directories(d);
  return d;
}

std::string write(const std::string& name, const std::string& content) {
  const fs::path p = dir() / name;
  fs::create_directories(p.parent_path());
  std::ofstream(p, std::ios::binary) << content;
  return p.string();
}

struct Read {
  std::vector<Trial> trials;
  std::vector<Diagnostic> diagnostics;
  std::uint64_t rows_read = 0, rows_in_trials = 0;
};

Read read_all(const std::vector<std::string>& files, TraceOptions opt = {}) {
  TraceReader r(files, std::move(opt));
  Read out;
  Trial t;
  while (r.next(t)) out.trials.push_back(t);
  out.diagnostics = r.diagnostics();
  out.rows_read = r.rows_read();
  out.rows_in_trials = r.rows_in_trials();
  return out;
}

std::string error_of(const std::vector<std::string>& files, TraceOptions opt = {}) {
  try {
    read_all(files, std::move(opt));
  } catch (const feint::InvalidData& e) {
    return e.what();
  }
  return {};
}

const Diagnostic* find(const std::vector<Diagnostic>& ds, const std::string& code) {
  for (const auto& d : ds) {
    if (d.code == code) return &d;
  }
  return nullptr;
}

}  // namespace

// ---- European CSV: ';', decimal comma, UTF-8 BOM, CRLF ----

TEST(OtherLabs, EuropeanCsvIsDetectedAndReadExactly) {
  const auto r = read_all({lab("european.csv")});
  ASSERT_EQ(r.trials.size(), 2U);
  EXPECT_EQ(r.trials[0].participant, "P01");  // the BOM is not part of the first column's name
  EXPECT_EQ(r.trials[0].times, (std::vector<double>{0, 0.033, 0.067, 4.3}));
  EXPECT_EQ(r.trials[0].pads, (std::vector<double>{0.5, 0.512, 0.538, 0.95}));
  EXPECT_EQ(r.trials[0].pad_speed, 0.8);
  const auto* d = find(r.diagnostics, "decimal-comma");
  ASSERT_NE(d, nullptr);
  EXPECT_EQ(d->line, 2U);
  EXPECT_NE(d->message.find("european.csv:2: numbers read with a decimal comma ('0,8'; the file "
                            "is ';'-delimited)"), std::string::npos) << d->message;
  EXPECT_NE(d->message.find("--decimal"), std::string::npos);
}

TEST(OtherLabs, EuropeanCsvWithExplicitOptionsGivesTheSameNumbersAndNoDetectionNote) {
  TraceOptions opt;
  opt.delimiter = ';';
  opt.decimal = ',';
  const auto r = read_all({lab("european.csv")}, opt);
  ASSERT_EQ(r.trials.size(), 2U);
  EXPECT_EQ(r.trials[1].times, (std::vector<double>{0, 1.25}));
  EXPECT_EQ(find(r.diagnostics, "decimal-comma"), nullptr);
}

TEST(OtherLabs, DecimalPointInADecimalCommaFileIsRefusedWithTheOption) {
  const auto p = write("eu_mixed.csv", "participant;iteration;target;t;pad\nP1;1;right;0,5;0,5\n"
                                       "P1;1;right;1.5;0,6\n");
  const auto msg = error_of({p});
  EXPECT_NE(msg.find("eu_mixed.csv:3: column 't': '1.5' is not a number (expected a time in "
                     "seconds, decimal comma); this file's numbers use a decimal comma "
                     "(detected), so a '.' is not allowed: give --decimal ."),
            std::string::npos) << msg;
  // A decimal comma where the point was declared (or detected) names --decimal ,.
  const auto q = write("eu_point.csv", "participant;iteration;target;t;pad\nP1;1;right;0.5;0.5\n"
                                       "P1;1;right;1,5;0.6\n");
  const auto m2 = error_of({q});
  EXPECT_NE(m2.find("eu_point.csv:3: column 't': '1,5' is not a number (expected a time in "
                    "seconds, decimal point); a decimal comma? give --delimiter ';' --decimal ,"),
            std::string::npos) << m2;
  TraceOptions bad;
  bad.decimal = ',';
  bad.delimiter = ',';
  EXPECT_THROW(TraceReader({p}, bad), feint::UsageError);
}

TEST(OtherLabs, ScoresTableInEuropeanFormat) {
  const auto p = write("scores_eu.csv", "\xEF\xBB\xBFparticipant;iteration;error;confusion\r\n"
                                        "P1;1;0,25;0,125\r\nP1;2;0,5;0,75\r\n");
  const auto t = feint::io::load_scores(p);
  ASSERT_EQ(t.records.size(), 2U);
  EXPECT_EQ(t.records[0].values[0], 0.25);
  EXPECT_EQ(t.records[1].values[1], 0.75);
  const auto q = write("scores_eu_bad.csv", "participant;iteration;error;confusion\n"
                                            "P1;1;0,25;0,125\nP1;2;0.5;0,75\n");
  try {
    feint::io::load_scores(q);
    FAIL() << "expected InvalidData";
  } catch (const feint::InvalidData& e) {
    EXPECT_NE(std::string(e.what()).find(":3: column 'error': '0.5' is not a number (P1/2; "
                                         "expected a finite number with a decimal comma, or an "
                                         "empty cell; give --decimal . if"),
              std::string::npos) << e.what();
  }
}

// ---- MATLAB: numbers only, no header ----

TEST(OtherLabs, HeaderlessFileIsRefusedWithHowToNameColumnsByPosition) {
  const auto msg = error_of({lab("matlab_noheader.csv")});
  EXPECT_NE(msg.find("matlab_noheader.csv:1: no column 'participant' (required)"), std::string::npos) << msg;
  EXPECT_NE(msg.find("the first row holds only numbers, so the file has no header: name its 5 "
                     "columns by position with --no-header --columns "
                     "participant,iteration,target,t,pad"), std::string::npos) << msg;
  EXPECT_NE(msg.find("--no-header --map t=3"), std::string::npos) << msg;
}

TEST(OtherLabs, HeaderlessFileReadWithColumnNamesOrPositions) {
  TraceOptions named;
  named.no_header = true;
  named.column_names = {"participant", "iteration", "target", "t", "pad"};
  const auto r = read_all({lab("matlab_noheader.csv")}, named);
  ASSERT_EQ(r.trials.size(), 2U);
  EXPECT_EQ(r.trials[0].line, 1U);  // the first row is data
  EXPECT_EQ(r.trials[0].label(), "7/1");
  EXPECT_EQ(r.trials[0].target, 1);
  EXPECT_EQ(r.trials[0].times, (std::vector<double>{0, 0.033, 0.066}));
  EXPECT_EQ(r.trials[1].target, 0);
  EXPECT_EQ(r.rows_read, 5U);

  TraceOptions by_number;
  by_number.no_header = true;
  by_number.column_map = {{"participant", "1"}, {"iteration", "2"}, {"target", "3"},
                          {"t", "4"},           {"pad", "5"}};
  const auto r2 = read_all({lab("matlab_noheader.csv")}, by_number);
  ASSERT_EQ(r2.trials.size(), 2U);
  EXPECT_EQ(r2.trials[0].times, r.trials[0].times);
  EXPECT_EQ(r2.trials[1].pads, r.trials[1].pads);

  // --no-header on a file that has one: said, not read as data.
  const auto msg = error_of({lab("fixed_length_nan.csv")}, named);
  EXPECT_NE(msg.find("fixed_length_nan.csv:1: --no-header, but the first row holds the column name "
                     "'participant': the file has a header; drop --no-header"), std::string::npos) << msg;

  TraceOptions nothing;
  nothing.no_header = true;
  EXPECT_THROW(TraceReader({lab("matlab_noheader.csv")}, nothing), feint::UsageError);
}

// ---- jsPsych: the trace as JSON in one cell ----

TEST(OtherLabs, JsPsychJsonCellIsRead) {
  TraceOptions opt;
  opt.samples_column = "pad_trace";
  opt.column_map = {{"participant", "subject"}, {"iteration", "trial_index"}};
  const auto r = read_all({lab("jspsych.csv")}, opt);
  ASSERT_EQ(r.trials.size(), 2U);
  EXPECT_EQ(r.trials[0].label(), "s01/adaptive/1");
  EXPECT_EQ(r.trials[0].times, (std::vector<double>{0, 0.5, 1.25}));  // array of objects
  EXPECT_EQ(r.trials[0].pads, (std::vector<double>{0.5, 0.6, 0.9}));
  EXPECT_EQ(r.trials[1].times, (std::vector<double>{0, 0.4, 0.9}));  // parallel arrays
  EXPECT_EQ(r.trials[1].pads, (std::vector<double>{0.5, 0.45, 0.2}));
  EXPECT_EQ(r.trials[1].target, 0);
}

TEST(OtherLabs, JsPsychWithoutTheOptionIsRefusedWithIt) {
  TraceOptions opt;
  opt.column_map = {{"participant", "subject"}, {"iteration", "trial_index"}};
  const auto msg = error_of({lab("jspsych.csv")}, opt);
  EXPECT_NE(msg.find("jspsych.csv:1: no column 't' (required), no column 'pad' (required)"),
            std::string::npos) << msg;
  EXPECT_NE(msg.find("samples stored as a JSON array in one cell (jsPsych): --samples-column "
                     "COLUMN"), std::string::npos) << msg;
}

// jsPsych's one row per trial with the trace as parallel JSON arrays in two cells (t and pad):
// the message says the cell holds a list and names the option that reads a whole trace from one
// cell, and never suggests a decimal comma (the commas are the list's).
TEST(OtherLabs, TraceAsArraysInSeparateCellsIsRefusedNamingArraysNotADecimalComma) {
  std::string long_t = "[0";
  for (int k = 1; k < 60; ++k) long_t += "," + std::to_string(17 * k);
  long_t += "]";
  const std::string p = write("arrays-in-cells.csv",
                              "participant,condition,iteration,target,t,pad\n"
                              "P1,adaptive,1,left,\"" + long_t + "\",\"[0.5,0.45,0.4]\"\n");
  const auto msg = error_of({p});
  EXPECT_NE(msg.find("arrays-in-cells.csv:2:"), std::string::npos) << msg;
  EXPECT_NE(msg.find("column 't'"), std::string::npos) << msg;
  EXPECT_NE(msg.find("the cell holds a list (a JSON array"), std::string::npos) << msg;
  EXPECT_NE(msg.find("--samples-column COLUMN"), std::string::npos) << msg;
  EXPECT_EQ(msg.find("decimal comma?"), std::string::npos) << msg;
  // The cell is shown cut to its first 40 characters, not the whole trace.
  EXPECT_NE(msg.find("'" + long_t.substr(0, 40) + "\u2026'"), std::string::npos) << msg;
  EXPECT_EQ(msg.find(long_t), std::string::npos) << msg;
}

TEST(OtherLabs, MalformedJsonCellNamesRowColumnAndSample) {
  TraceOptions opt;
  opt.samples_column = "trace";
  const auto p = write("js_bad.csv", "participant,iteration,target,trace\n"
                                     "P1,1,left,\"[{\"\"t\"\":0,\"\"pad\"\":0.5},{\"\"t\"\":1}]\"\n");
  auto msg = error_of({p}, opt);
  EXPECT_NE(msg.find("js_bad.csv:2: column 'trace': sample 2: no \"pad\" key"), std::string::npos) << msg;
  const auto q = write("js_bad2.csv", "participant,iteration,target,trace\nP1,1,left,[0.5\n");
  msg = error_of({q}, opt);
  EXPECT_NE(msg.find("js_bad2.csv:2: column 'trace': sample 1: expected an object"), std::string::npos) << msg;
  // The keys follow --map: jsPsych's own names.
  const auto k = write("js_keys.csv", "participant,iteration,target,trace\n"
                                      "P1,1,left,\"{\"\"time\"\":[0,1],\"\"x\"\":[0.5,0.4]}\"\n");
  opt.column_map = {{"t", "time"}, {"pad", "x"}};
  const auto r = read_all({k}, opt);
  ASSERT_EQ(r.trials.size(), 1U);
  EXPECT_EQ(r.trials[0].pads, (std::vector<double>{0.5, 0.4}));
}

// ---- fixed-length arrays padded with NaN ----

TEST(OtherLabs, TrailingNanRowsAreDroppedAndCounted) {
  const auto r = read_all({lab("fixed_length_nan.csv")});
  ASSERT_EQ(r.trials.size(), 2U);
  EXPECT_EQ(r.trials[0].times, (std::vector<double>{0, 0.5, 1.0}));
  EXPECT_EQ(r.trials[0].padding_rows, 2U);
  EXPECT_EQ(r.trials[0].rows, 5U);
  EXPECT_EQ(r.trials[1].padding_rows, 1U);
  EXPECT_EQ(r.rows_read, r.rows_in_trials);  // the account adds up: padding rows are not lost
  const auto* d = find(r.diagnostics, "nan-padding");
  ASSERT_NE(d, nullptr);
  EXPECT_NE(d->message.find("dropped 3 trailing row(s) without t and pad"), std::string::npos) << d->message;
  EXPECT_NE(d->message.find("end of 2 trial(s)"), std::string::npos) << d->message;
}

TEST(OtherLabs, NanInTheMiddleOfATrialStaysInvalid) {
  const std::string head = "participant,iteration,target,t,pad\n";
  auto msg = error_of({write("mid.csv", head + "P1,1,left,0,0.5\nP1,1,left,NaN,NaN\nP1,1,left,1,0.4\n")});
  EXPECT_NE(msg.find("mid.csv:3: columns 't' and 'pad': no value, but a sample follows at line 4"),
            std::string::npos) << msg;
  // Only t and pad both missing is padding: a NaN pad alone is invalid.
  msg = error_of({write("half.csv", head + "P1,1,left,0,0.5\nP1,1,left,1,0.4\nP1,1,left,2,NaN\n")});
  EXPECT_NE(msg.find("half.csv:4: column 'pad': 'NaN' is not a number"), std::string::npos) << msg;
  // Empty and NA cells pad too (pandas, R).
  const auto r = read_all({write("na.csv", head + "P1,1,left,0,0.5\nP1,1,left,1,0.4\nP1,1,left,NA,NA\n"
                                                  "P1,1,left,,\n")});
  ASSERT_EQ(r.trials.size(), 1U);
  EXPECT_EQ(r.trials[0].padding_rows, 2U);
  // A trial of padding only has fewer than 2 samples: invalid as before.
  msg = error_of({write("allnan.csv", head + "P1,1,left,0,0.5\nP1,1,left,NaN,NaN\n")});
  EXPECT_NE(msg.find("1 valid sample(s); a trial needs at least 2"), std::string::npos) << msg;
}

// ---- PsychoPy: 0-based iterations, id in the file name ----

TEST(OtherLabs, ZeroBasedIterationsAreDetectedAndCanBeDeclared) {
  const auto asis = read_all({lab("psychopy/P03_deception_2026-11-20.csv")});
  ASSERT_EQ(asis.trials.size(), 2U);
  EXPECT_EQ(asis.trials[0].iteration, 0);
  const auto* d = find(asis.diagnostics, "iteration-base-0");
  ASSERT_NE(d, nullptr);
  EXPECT_NE(d->message.find("iterations start at 0 ("), std::string::npos) << d->message;
  EXPECT_NE(d->message.find("P03_deception_2026-11-20.csv:2; iterations 0 to 1)"), std::string::npos) << d->message;
  EXPECT_NE(d->message.find("--iteration-base 0"), std::string::npos);

  TraceOptions zero;
  zero.iteration_base = 0;
  const auto shifted = read_all({lab("psychopy/P03_deception_2026-11-20.csv")}, zero);
  ASSERT_EQ(shifted.trials.size(), 2U);
  EXPECT_EQ(shifted.trials[0].iteration, 1);
  EXPECT_EQ(shifted.trials[1].iteration, 2);
  EXPECT_EQ(find(shifted.diagnostics, "iteration-base-0"), nullptr);

  TraceOptions one;
  one.iteration_base = 1;
  const auto msg = error_of({lab("psychopy/P03_deception_2026-11-20.csv")}, one);
  EXPECT_NE(msg.find("P03_deception_2026-11-20.csv:2: column 'iteration': iteration 0 with "
                     "--iteration-base 1 (give --iteration-base 0"), std::string::npos) << msg;
  // 1-based data: no note.
  EXPECT_EQ(find(read_all({lab("fixed_length_nan.csv")}).diagnostics, "iteration-base-0"), nullptr);
}

TEST(OtherLabs, ParticipantFromPath) {
  // Without an id column the message names the option.
  const auto msg = error_of({lab("by-folder/sub-07/trials.csv")});
  EXPECT_NE(msg.find("trials.csv:1: no column 'participant' (required)"), std::string::npos) << msg;
  EXPECT_NE(msg.find("ids only in the file or folder name: --participant-from-path filename (or "
                     "dirname, or a regular expression"), std::string::npos) << msg;

  TraceOptions folder;
  folder.participant_from_path = "dirname";
  auto r = read_all({lab("by-folder/sub-07/trials.csv")}, folder);
  ASSERT_EQ(r.trials.size(), 2U);
  EXPECT_EQ(r.trials[0].participant, "sub-07");

  TraceOptions rx;
  rx.participant_from_path = "sub-([0-9]+)";
  r = read_all({lab("by-folder/sub-07/trials.csv")}, rx);
  EXPECT_EQ(r.trials[1].participant, "07");

  TraceOptions name;
  name.participant_from_path = "filename";
  r = read_all({lab("by-folder/sub-07/trials.csv")}, name);
  EXPECT_EQ(r.trials[0].participant, "trials");

  // The option replaces an id column; a regex that does not match names the file.
  TraceOptions psy;
  psy.participant_from_path = "/(P[0-9]+)_[^/]*$";
  r = read_all({lab("psychopy/P03_deception_2026-11-20.csv")}, psy);
  EXPECT_EQ(r.trials[0].participant, "P03");
  TraceOptions nomatch;
  nomatch.participant_from_path = "subject([0-9]+)";
  const auto m2 = error_of({lab("by-folder/sub-07/trials.csv")}, nomatch);
  EXPECT_NE(m2.find("trials.csv: --participant-from-path 'subject([0-9]+)' does not match this path"),
            std::string::npos) << m2;
  TraceOptions nogroup;
  nogroup.participant_from_path = "sub-[0-9]+";
  EXPECT_THROW(TraceReader({lab("by-folder/sub-07/trials.csv")}, nogroup), feint::UsageError);
  TraceOptions badrx;
  badrx.participant_from_path = "sub-([0-9]+";
  EXPECT_THROW(TraceReader({lab("by-folder/sub-07/trials.csv")}, badrx), feint::UsageError);
}

// ---- columns that differ only in case ----

TEST(OtherLabs, ExactCaseMatchWinsOverAMillisecondTimer) {
  // `T` is a millisecond timer, `t` the trial time in seconds: the trial lasts 4.301 s.
  TraceOptions mapped;
  mapped.column_map = {{"t", "t"}};
  for (const auto& opt : {TraceOptions{}, mapped}) {
    const auto r = read_all({lab("timer_T_and_t.csv")}, opt);
    ASSERT_EQ(r.trials.size(), 1U);
    EXPECT_EQ(r.trials[0].times.back(), 4.301);
  }
  TraceOptions upper;
  upper.column_map = {{"t", "T"}};
  EXPECT_EQ(read_all({lab("timer_T_and_t.csv")}, upper).trials[0].times.back(), 124301);
}

TEST(OtherLabs, ColumnsDifferingOnlyInCaseWithoutExactMatchAreAmbiguous) {
  const auto p = write("case.csv", "participant,iteration,target,t,Pad,PAD\nP1,1,left,0,0.5,0.1\n");
  const auto msg = error_of({p});
  EXPECT_NE(msg.find("case.csv:1: columns 'Pad' (column 5) and 'PAD' (column 6) differ only in "
                     "case and none is exactly 'pad': ambiguous; name one exactly with --map "
                     "pad=COLUMN"), std::string::npos) << msg;
  TraceOptions opt;
  opt.column_map = {{"pad", "PAD"}};
  EXPECT_EQ(read_all({write("case2.csv", "participant,iteration,target,t,Pad,PAD\n"
                                         "P1,1,left,0,0.5,0.1\nP1,1,left,1,0.5,0.2\n")}, opt)
                .trials[0].pads, (std::vector<double>{0.1, 0.2}));
  // The scores loader too.
  const auto s = write("case_scores.csv", "participant,iteration,Error,ERROR,confusion\nP1,1,0.1,0.2,0.3\n");
  try {
    feint::io::load_scores(s);
    FAIL();
  } catch (const feint::InvalidData& e) {
    EXPECT_NE(std::string(e.what()).find("columns 'Error' (column 3) and 'ERROR' (column 4) differ "
                                         "only in case"), std::string::npos) << e.what();
  }
}

// ---- conditions not pooled silently ----

TEST(OtherLabs, AConditionLookalikeColumnIsRefusedNotPooled) {
  const auto msg = error_of({lab("group_column.csv")});
  EXPECT_NE(msg.find("group_column.csv:1: column 'group' (column 2) looks like the condition, but "
                     "the condition is read from a column named 'condition': name it with --map "
                     "condition=group, or give --single-condition"), std::string::npos) << msg;
  TraceOptions mapped;
  mapped.column_map = {{"condition", "group"}};
  const auto r = read_all({lab("group_column.csv")}, mapped);
  ASSERT_EQ(r.trials.size(), 2U);
  EXPECT_EQ(r.trials[1].condition, "random");
  TraceOptions pooled;
  pooled.single_condition = true;
  EXPECT_EQ(read_all({lab("group_column.csv")}, pooled).trials[1].condition, "");
}

TEST(OtherLabs, NoConditionColumnWhileTheStudyHasTwoIsRefused) {
  TraceOptions opt;
  opt.expected_conditions = {"adaptive", "random"};
  const auto msg = error_of({lab("fixed_length_nan.csv")}, opt);
  EXPECT_NE(msg.find("fixed_length_nan.csv:1: no condition column 'condition', but the study has 2 "
                     "conditions (adaptive, random): name the column with --map condition=COLUMN"),
            std::string::npos) << msg;
  const auto s = write("nocond_scores.csv", "participant,iteration,error,confusion\nP1,1,0.1,0.2\n");
  feint::io::ScoresOptions so;
  so.expected_conditions = {"adaptive", "random"};
  try {
    feint::io::load_scores(s, so);
    FAIL();
  } catch (const feint::InvalidData& e) {
    EXPECT_NE(std::string(e.what()).find(":1: no condition column 'condition', but the study has 2 "
                                         "conditions (adaptive, random): name it with "
                                         "--condition-column COLUMN"), std::string::npos) << e.what();
  }
  EXPECT_EQ(feint::io::load_scores(s).records.size(), 1U);  // one condition when none is expected
}

// ---- messages ----

TEST(OtherLabs, TimeUnitInTheMessageIsTheGivenUnit) {
  TraceOptions ms;
  ms.time_divisor = 1000;
  const auto msg = error_of({write("ms_bad.csv", "participant,iteration,target,t,pad\nP1,1,left,abc,0.5\n")}, ms);
  EXPECT_NE(msg.find("column 't': 'abc' is not a number (expected a time in milliseconds, decimal point)"),
            std::string::npos) << msg;
  EXPECT_EQ(msg.find("time in seconds"), std::string::npos) << msg;
  const auto empty = error_of({write("ms_empty.csv", "participant,iteration,target,t,pad\nP1,1,left,,0.5\n")}, ms);
  EXPECT_NE(empty.find("column 't': empty (expected a time in milliseconds)"), std::string::npos) << empty;
}

TEST(OtherLabs, AllMissingColumnsInOneMessage) {
  const auto msg = error_of({write("few.csv", "subject,time,x\nP1,0,0.5\n")});
  EXPECT_NE(msg.find("few.csv:1: no column 'participant' (required), no column 'iteration' "
                     "(required), no column 'target' (required), no column 't' (required), no "
                     "column 'pad' (required) (the header has: subject, time, x); name the "
                     "study's columns with --map participant=COLUMN --map iteration=COLUMN --map "
                     "target=COLUMN --map t=COLUMN --map pad=COLUMN"), std::string::npos) << msg;
  const auto s = write("few_scores.csv", "id,error\nP1,0.5\n");
  try {
    feint::io::load_scores(s);
    FAIL();
  } catch (const feint::InvalidData& e) {
    EXPECT_NE(std::string(e.what()).find(":1: columns 'participant' (participant), "
                                         "'iteration' (iteration), 'confusion' (metric) are "
                                         "missing; the header has: id, error"), std::string::npos) << e.what();
  }
}

// ---- the questionnaire's ids against the logs' ----

TEST(OtherLabs, CompareParticipantsListsMissingOnEitherSide) {
  const auto c = feint::io::compare_participants({"P01", "P02", "P03", "P02"}, {"P02", "P03", "P04", "p01"});
  EXPECT_EQ(c.only_in_logs, (std::vector<std::string>{"P01"}));
  EXPECT_EQ(c.only_in_questionnaire, (std::vector<std::string>{"P04", "p01"}));
  EXPECT_EQ(c.in_both, 2U);
  EXPECT_FALSE(c.matches());
  EXPECT_EQ(c.message(), "participant ids differ between the logs and the questionnaire: 1 in the "
                         "logs only (P01); 2 in the questionnaire only (P04, p01); 2 in both "
                         "(ids are compared exactly: P01 and p01 are two people)");
  const auto same = feint::io::compare_participants({"A", "B"}, {"B", "A"});
  EXPECT_TRUE(same.matches());
  EXPECT_EQ(same.message(), "");
}

TEST(OtherLabs, QuestionnaireColumnsDifferingOnlyInCase) {
  // Exact case wins; two case-variants without an exact match are refused, naming both.
  const auto ok = write("q_exact.csv", "participant,PARTICIPANT,q1,q2\nP1,1,3,4\nP2,2,5,6\n");
  const auto q = feint::io::load_questionnaire(ok);
  ASSERT_EQ(q.participants.size(), 2U);
  EXPECT_EQ(q.participants[0], "P1");
  const auto bad = write("q_case.csv", "Participant,PARTICIPANT,q1,q2\nP1,1,3,4\nP2,2,5,6\n");
  try {
    feint::io::load_questionnaire(bad);
    FAIL();
  } catch (const feint::InvalidData& e) {
    EXPECT_NE(std::string(e.what()).find("q_case.csv:1: columns 'Participant' (column 1) and "
                                         "'PARTICIPANT' (column 2) differ only in case"),
              std::string::npos) << e.what();
  }
}

TEST(OtherLabs, ParticipantFromPathCannotNameStandardInput) {
  TraceOptions opt;
  opt.participant_from_path = "filename";
  EXPECT_THROW(TraceReader({"-"}, opt), feint::UsageError);
}

TEST(OtherLabs, RobotColumnsUseTheFilesDecimalMark) {
  const auto p = write("eu_robot.csv", "participant;iteration;target;t;pad;robot_x;robot_y\n"
                                       "P1;1;left;0,0;0,5;0,0;0,0\nP1;1;left;0,5;0,4;-0,0179;0,0358\n");
  TraceOptions opt;
  opt.read_robot_path = true;
  const auto r = read_all({p}, opt);
  ASSERT_EQ(r.trials.size(), 1U);
  EXPECT_EQ(r.trials[0].robot_x, (std::vector<double>{0, -0.0179}));
  EXPECT_EQ(r.trials[0].robot_y, (std::vector<double>{0, 0.0358}));
}
