// The pad-trace loader (formats.md): grouping, column mapping, and every rejection rule with its
// message (file, line, column, value, trial).
#include <gtest/gtest.h>
#include <zlib.h>

#include <filesystem>
#include <random>

#include <fmt/format.h>
#include <fstream>
#include <string>
#include <vector>

#include "feint/error.hpp"
#include "feint/io/number.hpp"
#include "feint/io/trace.hpp"

namespace fs = std::filesystem;
using feint::io::Rejection;
using feint::io::TraceOptions;
using feint::io::TraceReader;
using feint::io::Trial;

namespace {

const std::string kHeader = "participant,condition,iteration,strategy,variant,target,t,pad,pad_speed\n";

fs::path dir() {
  const fs::path d = fs::temp_directory_path() / ("feint-test-trace-" + std::to_string(::getpid()));
  fs::create_directories(d);
  return d;
}

std::string write(const std::string& name, const std::string& content) {
  const fs::path p = dir() / name;
  fs::create_directories(p.parent_path());
  std::ofstream(p, std::ios::binary) << content;
  return p.string();
}

std::vector<Trial> read_all(const std::vector<std::string>& files, TraceOptions opt = {}) {
  TraceReader r(files, std::move(opt));
  std::vector<Trial> out;
  Trial t;
  while (r.next(t)) out.push_back(t);
  return out;
}

// The message of the InvalidData that reading throws (strict mode); "" when none.
std::string strict_error(const std::string& content, TraceOptions opt = {}) {
  const auto p = write("strict.csv", content);
  try {
    read_all({p}, std::move(opt));
  } catch (const feint::InvalidData& e) {
    return e.what();
  }
  return {};
}

std::string row(const std::string& key, const std::string& target, const std::string& t,
                const std::string& pad, const std::string& speed = "0.5") {
  return key + ",s,main," + target + "," + t + "," + pad + "," + speed + "\n";
}

}  // namespace

TEST(TraceReader, GroupsContiguousRowsIntoTrials) {
  const auto p = write("ok.csv", kHeader + row("P01,adaptive,1", "right", "0", "0.5") +
                                     row("P01,adaptive,1", "right", "0.5", "0.6") +
                                     row("P01,adaptive,2", "LEFT", "0", "0.5") +
                                     row("P01,adaptive,2", "LEFT", "1", "0.25") +
                                     row("P02,random,1", "0.3", "0", "0.5") +
                                     row("P02,random,1", "0.3", "2", "1"));
  TraceReader r({p}, {});
  std::vector<Trial> trials;
  Trial t;
  while (r.next(t)) trials.push_back(t);
  ASSERT_EQ(trials.size(), 3U);
  EXPECT_EQ(trials[0].participant, "P01");
  EXPECT_EQ(trials[0].condition, "adaptive");
  EXPECT_EQ(trials[0].iteration, 1);
  EXPECT_EQ(trials[0].strategy, "s");
  EXPECT_EQ(trials[0].variant, "main");
  EXPECT_EQ(trials[0].target, 1);
  EXPECT_EQ(trials[0].pad_speed, 0.5);
  EXPECT_EQ(trials[0].times, (std::vector<double>{0, 0.5}));
  EXPECT_EQ(trials[0].pads, (std::vector<double>{0.5, 0.6}));
  EXPECT_EQ(trials[0].line, 2U);
  EXPECT_EQ(trials[0].file, p);
  EXPECT_EQ(trials[1].target, 0);
  EXPECT_EQ(trials[1].line, 4U);
  EXPECT_EQ(trials[2].target, 0.3);
  EXPECT_EQ(trials[2].label(), "P02/random/1");
  EXPECT_EQ(r.rows_read(), 6U);
  EXPECT_EQ(r.rows_in_trials(), 6U);
}

TEST(TraceReader, MapsColumnsAndReadsGzipAndOtherDelimiters) {
  const std::string content =
      "Subject;Block;Trial;Side;Time;Position\nA;x;3;1;0;0.5\nA;x;3;1;0.1;0.55\n";
  const auto plain = write("mapped.csv", content);
  const auto gz = (dir() / "mapped.csv.gz").string();
  gzFile f = gzopen(gz.c_str(), "wb");
  gzwrite(f, content.data(), static_cast<unsigned>(content.size()));
  gzclose(f);
  TraceOptions opt;
  opt.column_map = {{"participant", "subject"}, {"condition", "Block"}, {"iteration", "trial"},
                    {"target", "side"},         {"t", "time"},          {"pad", "position"}};
  for (const auto& path : {plain, gz}) {
    const auto trials = read_all({path}, opt);
    ASSERT_EQ(trials.size(), 1U);
    EXPECT_EQ(trials[0].label(), "A/x/3");
    EXPECT_EQ(trials[0].times.size(), 2U);
    EXPECT_FALSE(trials[0].pad_speed.has_value());
  }
}

TEST(TraceReader, NoConditionColumnMeansOneCondition) {
  const auto p = write("nocond.csv", "participant,iteration,target,t,pad\nP1,1,left,0,0.5\nP1,1,left,1,0.4\n");
  const auto trials = read_all({p});
  ASSERT_EQ(trials.size(), 1U);
  EXPECT_EQ(trials[0].condition, "");
  EXPECT_EQ(trials[0].label(), "P1/1");
}

TEST(TraceReader, PadSpeedOverrideReplacesTheColumn) {
  const auto p = write("ov.csv", kHeader + row("P1,a,1", "left", "0", "0.5", "junk") +
                                     row("P1,a,1", "left", "1", "0.4", "junk"));
  TraceOptions opt;
  opt.pad_speed = 2.0;
  const auto trials = read_all({p}, opt);
  ASSERT_EQ(trials.size(), 1U);
  EXPECT_EQ(trials[0].pad_speed, 2.0);
}

// ---- every rejection rule, with its message ----

TEST(TraceRejects, PadOutsideRange) {
  const auto msg = strict_error(kHeader + row("P07,adaptive,3", "right", "0", "0.5") +
                                row("P07,adaptive,3", "right", "0.1", "1.7"));
  EXPECT_NE(msg.find("strict.csv:3: column 'pad': 1.7 is outside [0, 1] (trial P07/adaptive/3)"),
            std::string::npos) << msg;
}

TEST(TraceRejects, NotANumberNanInfAndEmpty) {
  for (const std::string bad : {"abc", "nan", "inf", "1,5", ""}) {
    const std::string pad = bad == "1,5" ? "\"1,5\"" : bad;
    const auto msg = strict_error(kHeader + row("P1,a,1", "right", "0", "0.5") +
                                  row("P1,a,1", "right", "0.1", pad));
    EXPECT_NE(msg.find("strict.csv:3: column 'pad': "), std::string::npos) << bad << ": " << msg;
    EXPECT_NE(msg.find("(trial P1/a/1)"), std::string::npos) << msg;
    if (!bad.empty()) {
      EXPECT_NE(msg.find("'" + bad + "' is not a number"), std::string::npos) << msg;
    } else {
      EXPECT_NE(msg.find("empty"), std::string::npos) << msg;
    }
  }
  const auto t_msg = strict_error(kHeader + row("P1,a,1", "right", "x1", "0.5"));
  EXPECT_NE(t_msg.find("strict.csv:2: column 't': 'x1' is not a number"), std::string::npos) << t_msg;
}

TEST(TraceRejects, TimesMustStrictlyIncrease) {
  const auto msg = strict_error(kHeader + row("P1,a,1", "right", "0", "0.5") +
                                row("P1,a,1", "right", "1", "0.5") +
                                row("P1,a,1", "right", "1", "0.6"));
  EXPECT_NE(msg.find("strict.csv:4: column 't': 1 is not after the previous sample's 1 (line 3"),
            std::string::npos) << msg;
  const auto dec = strict_error(kHeader + row("P1,a,1", "right", "2", "0.5") +
                                row("P1,a,1", "right", "1.5", "0.5"));
  EXPECT_NE(dec.find("strict.csv:3: column 't': 1.5 is not after"), std::string::npos) << dec;
}

TEST(TraceRejects, TooFewSamples) {
  const auto msg = strict_error(kHeader + row("P1,a,1", "right", "0", "0.5") +
                                row("P1,a,2", "right", "0", "0.5") + row("P1,a,2", "right", "1", "0.5"));
  EXPECT_NE(msg.find("strict.csv:2: 1 valid sample(s); a trial needs at least 2"), std::string::npos)
      << msg;
  EXPECT_NE(msg.find("(trial P1/a/1)"), std::string::npos) << msg;
}

TEST(TraceRejects, TargetMustBeLeftRightOrInRange) {
  auto msg = strict_error(kHeader + row("P1,a,1", "up", "0", "0.5") + row("P1,a,1", "up", "1", "0.5"));
  EXPECT_NE(msg.find("strict.csv:2: column 'target': 'up' is not left, right, or a number in [0, 1] "
                     "(trial P1/a/1)"), std::string::npos) << msg;
  msg = strict_error(kHeader + row("P1,a,1", "1.5", "0", "0.5"));
  EXPECT_NE(msg.find("column 'target': 1.5 is outside [0, 1]"), std::string::npos) << msg;
  msg = strict_error(kHeader + row("P1,a,1", "", "0", "0.5"));
  EXPECT_NE(msg.find("column 'target': empty"), std::string::npos) << msg;
}

TEST(TraceRejects, TrialLevelFieldsMustBeConstant) {
  auto msg = strict_error(kHeader + row("P1,a,1", "right", "0", "0.5") +
                          row("P1,a,1", "left", "1", "0.5"));
  EXPECT_NE(msg.find("strict.csv:3: column 'target': 'left' differs from 'right' on the trial's first "
                     "row (line 2)"), std::string::npos) << msg;
  msg = strict_error(kHeader + row("P1,a,1", "right", "0", "0.5", "0.5") +
                     row("P1,a,1", "right", "1", "0.5", "0.8"));
  EXPECT_NE(msg.find("strict.csv:3: column 'pad_speed': '0.8' differs from '0.5'"), std::string::npos)
      << msg;
  // The same number written differently is the same value.
  EXPECT_EQ(strict_error(kHeader + row("P1,a,1", "1", "0", "0.5", "0.5") +
                         row("P1,a,1", "1.0", "1", "0.5", "0.50")), "");
  msg = strict_error(kHeader + "P1,a,1,s,main,right,0,0.5,0.5\nP1,a,1,t,main,right,1,0.5,0.5\n");
  EXPECT_NE(msg.find("column 'strategy': 't' differs from 's'"), std::string::npos) << msg;
  msg = strict_error(kHeader + "P1,a,1,s,main,right,0,0.5,0.5\nP1,a,1,s,alt,right,1,0.5,0.5\n");
  EXPECT_NE(msg.find("column 'variant': 'alt' differs from 'main'"), std::string::npos) << msg;
}

TEST(TraceRejects, KeyFieldsMustBeValid) {
  auto msg = strict_error(kHeader + row(",a,1", "right", "0", "0.5"));
  EXPECT_NE(msg.find("strict.csv:2: column 'participant': empty"), std::string::npos) << msg;
  msg = strict_error(kHeader + row("P1,a,one", "right", "0", "0.5"));
  EXPECT_NE(msg.find("strict.csv:2: column 'iteration': 'one' is not a whole number (trial P1/a/one)"),
            std::string::npos) << msg;
  msg = strict_error(kHeader + row("P1,,1", "right", "0", "0.5"));
  EXPECT_NE(msg.find("column 'condition': empty"), std::string::npos) << msg;
}

TEST(TraceRejects, WrongFieldCount) {
  const auto msg = strict_error(kHeader + row("P1,a,1", "right", "0", "0.5") + "P1,a,1,s,main,right,1\n");
  EXPECT_NE(msg.find("strict.csv:3: 7 fields where the header has 9 (trial P1/a/1)"), std::string::npos)
      << msg;
}

TEST(TraceRejects, PadSpeedInvalid) {
  TraceOptions opt;
  opt.require_pad_speed = true;
  auto msg = strict_error(kHeader + row("P1,a,1", "right", "0", "0.5", "-1"), opt);
  EXPECT_NE(msg.find("column 'pad_speed': '-1' is not a number > 0"), std::string::npos) << msg;
  msg = strict_error(kHeader + row("P1,a,1", "right", "0", "0.5", ""), opt);
  EXPECT_NE(msg.find("column 'pad_speed': empty"), std::string::npos) << msg;
}

TEST(TraceRejects, MissingColumnsAndPadSpeed) {
  auto msg = strict_error("participant,iteration,target,t\nP1,1,left,0\n");
  EXPECT_NE(msg.find("strict.csv:1: no column 'pad' (required"), std::string::npos) << msg;
  EXPECT_NE(msg.find("--map pad=COLUMN"), std::string::npos) << msg;
  TraceOptions opt;
  opt.column_map = {{"condition", "block"}};
  msg = strict_error(kHeader + row("P1,a,1", "right", "0", "0.5"), opt);
  EXPECT_NE(msg.find("no column 'block' (given by --map condition=block) (the header has:"), std::string::npos) << msg;
  TraceOptions need;
  need.require_pad_speed = true;
  const auto p = write("nospeed.csv", "participant,iteration,target,t,pad\nP1,1,left,0,0.5\n");
  try {
    read_all({p}, need);
    ADD_FAILURE() << "no throw";
  } catch (const feint::UsageError& e) {
    EXPECT_NE(std::string(e.what()).find("--pad-speed"), std::string::npos) << e.what();
  }
  TraceOptions bad_map;
  bad_map.column_map = {{"time", "t"}};
  EXPECT_THROW(TraceReader({p}, bad_map), feint::UsageError);
}

TEST(TraceRejects, TrialThatReappearsNamesBothPlaces) {
  const auto msg = strict_error(kHeader + row("P1,a,1", "right", "0", "0.5") +
                                row("P1,a,1", "right", "1", "0.5") + row("P1,a,2", "right", "0", "0.5") +
                                row("P1,a,2", "right", "1", "0.5") + row("P1,a,1", "right", "2", "0.5"));
  EXPECT_NE(msg.find("strict.csv:6: rows of this trial already appeared at "), std::string::npos) << msg;
  EXPECT_NE(msg.find("strict.csv:2"), std::string::npos) << msg;
  EXPECT_NE(msg.find("--unsorted"), std::string::npos) << msg;
  EXPECT_NE(msg.find("(trial P1/a/1)"), std::string::npos) << msg;
}

TEST(TraceRejects, TrialSpanningTwoFilesNamesBoth) {
  const auto a = write("span_a.csv", kHeader + row("P1,a,1", "right", "0", "0.5") +
                                         row("P1,a,1", "right", "1", "0.5"));
  const auto b = write("span_b.csv", kHeader + row("P1,a,1", "right", "2", "0.5") +
                                         row("P1,a,1", "right", "3", "0.5"));
  try {
    read_all({a, b});
    ADD_FAILURE() << "no throw";
  } catch (const feint::InvalidData& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find(b + ":2: rows of this trial already appeared at " + a + ":2"),
              std::string::npos) << msg;
    EXPECT_NE(msg.find("spans two files"), std::string::npos) << msg;
  }
  TraceOptions unsorted;
  unsorted.unsorted = true;
  const auto trials = read_all({a, b}, unsorted);
  ASSERT_EQ(trials.size(), 1U);
  EXPECT_EQ(trials[0].times, (std::vector<double>{0, 1, 2, 3}));
  EXPECT_EQ(trials[0].file, a);
}

TEST(TraceReader, UnsortedGroupsScatteredRowsInOrderOfFirstAppearance) {
  const auto p = write("scattered.csv", kHeader + row("P2,a,1", "right", "0", "0.5") +
                                            row("P1,a,1", "left", "0", "0.5") +
                                            row("P2,a,1", "right", "1", "0.6") +
                                            row("P1,a,1", "left", "1", "0.4"));
  TraceOptions opt;
  opt.unsorted = true;
  const auto trials = read_all({p}, opt);
  ASSERT_EQ(trials.size(), 2U);
  EXPECT_EQ(trials[0].participant, "P2");
  EXPECT_EQ(trials[0].pads, (std::vector<double>{0.5, 0.6}));
  EXPECT_EQ(trials[1].participant, "P1");
  EXPECT_EQ(trials[1].line, 3U);
}

TEST(TraceReader, LenientModeRejectsWholeTrialsAndAccountsForEveryRow) {
  const auto p = write("lenient.csv",
                       kHeader + row("P1,a,1", "right", "0", "0.5") + row("P1,a,1", "right", "1", "1.7") +
                           row("P1,a,1", "right", "2", "0.5") +                      // rejected: 3 rows
                           row("P1,a,2", "right", "0", "0.5") + row("P1,a,2", "right", "1", "0.5") +  // ok
                           row("P1,a,3", "right", "0", "0.5") +                      // 1 sample
                           row("P1,a,4", "right", "0", "0.5") + row("P1,a,4", "right", "1", "0.6"));
  std::vector<Rejection> rejects;
  TraceOptions opt;
  opt.on_reject = [&](const Rejection& r) { rejects.push_back(r); };
  TraceReader r({p}, opt);
  std::vector<Trial> trials;
  Trial t;
  while (r.next(t)) trials.push_back(t);
  ASSERT_EQ(trials.size(), 2U);
  EXPECT_EQ(trials[0].iteration, 2);
  EXPECT_EQ(trials[1].iteration, 4);
  ASSERT_EQ(rejects.size(), 2U);
  EXPECT_EQ(rejects[0].line, 3U);
  EXPECT_EQ(rejects[0].rows, 3U);
  EXPECT_EQ(rejects[0].iteration, "1");
  EXPECT_NE(rejects[0].reason.find("column 'pad': 1.7 is outside [0, 1] (trial P1/a/1)"),
            std::string::npos);
  EXPECT_EQ(rejects[1].rows, 1U);
  EXPECT_EQ(r.rows_read(), 8U);
  EXPECT_EQ(r.rows_in_trials(), 4U);
  EXPECT_EQ(r.rows_rejected(), 4U);
  EXPECT_EQ(r.trials_rejected(), 2U);
}

TEST(ExpandInputs, DirectoriesGlobsAndMissingFiles) {
  const auto d = dir() / "tree";
  write("tree/b.csv", "x\n");
  write("tree/sub/a.csv.gz", "x\n");
  write("tree/notes.md", "x\n");
  const auto files = feint::io::expand_inputs({d.string()});
  ASSERT_EQ(files.size(), 2U);
  EXPECT_NE(files[0].find("b.csv"), std::string::npos);
  EXPECT_NE(files[1].find("sub/a.csv.gz"), std::string::npos);
  const auto globbed = feint::io::expand_inputs({(d / "*.csv").string(), (d / "b.csv").string()});
  ASSERT_EQ(globbed.size(), 1U);  // the same file named twice is read once
  EXPECT_THROW(feint::io::expand_inputs({(d / "nothing-*.csv").string()}), feint::IoError);
  EXPECT_THROW(feint::io::expand_inputs({(d / "missing.csv").string()}), feint::IoError);
  fs::create_directories(dir() / "empty");
  EXPECT_THROW(feint::io::expand_inputs({(dir() / "empty").string()}), feint::IoError);
}

// A study folder as feint collect and feint simulate study write it (feint.toml, logs/, the
// questionnaires beside them) means its logs; a folder without feint.toml is read whole.
TEST(ExpandInputs, AStudyFolderMeansItsLogs) {
  write("study/feint.toml", "design = \"between\"\n");
  write("study/questionnaire.csv", "participant,trust\n");
  write("study/logs/P01.csv", "x\n");
  write("study/logs/P02.csv.gz", "x\n");
  const auto files = feint::io::expand_inputs({(dir() / "study").string()});
  ASSERT_EQ(files.size(), 2U);
  EXPECT_NE(files[0].find("logs/P01.csv"), std::string::npos);
  EXPECT_NE(files[1].find("logs/P02.csv.gz"), std::string::npos);
  write("plain/questionnaire.csv", "participant,trust\n");
  write("plain/logs/P01.csv", "x\n");
  EXPECT_EQ(feint::io::expand_inputs({(dir() / "plain").string()}).size(), 2U);  // no feint.toml: every file
}

TEST(TraceReader, NumbersAreReadExactlyAsParseDouble) {
  // The loader's fast decimal path must give the same double as the strict parser, bit for bit.
  std::mt19937_64 rng(11);
  std::string content = "participant,iteration,target,t,pad\n";
  std::vector<std::string> texts;
  double t = 0;
  for (int i = 0; i < 3000; ++i) {
    const int decimals = static_cast<int>(rng() % 17);
    t += 0.5 + static_cast<double>(rng() % 1000) / 7.0;
    std::string ts = fmt::format("{:.{}f}", t, decimals);
    if (i % 50 == 0) ts = fmt::format("{:e}", t);  // exponent: the slow path
    if (!texts.empty() && !(*feint::io::parse_double(ts) > *feint::io::parse_double(texts.back()))) {
      continue;
    }
    texts.push_back(ts);
    content += "P1,1,left," + ts + ",0." + std::to_string(rng() % 1000000000) + "\n";
  }
  const auto p = write("numbers.csv", content);
  const auto trials = read_all({p});
  ASSERT_EQ(trials.size(), 1U);
  ASSERT_EQ(trials[0].times.size(), texts.size());
  for (std::size_t i = 0; i < texts.size(); ++i) {
    ASSERT_EQ(trials[0].times[i], *feint::io::parse_double(texts[i])) << texts[i];
  }
}

// The iteration is a number, so `1` and `01` (and `+1`) are the same trial.
TEST(TraceReader, IterationKeysAreNumbersSoOneAndZeroOneAreOneTrial) {
  const auto p = write("iter.csv", kHeader + row("P1,a,1", "right", "0", "0.5") +
                                       row("P1,a,01", "right", "1", "0.6") +
                                       row("P1,a,+1", "right", "2", "0.7"));
  const auto trials = read_all({p});
  ASSERT_EQ(trials.size(), 1U);
  EXPECT_EQ(trials[0].iteration, 1);
  EXPECT_EQ(trials[0].times.size(), 3U);
  TraceOptions unsorted;
  unsorted.unsorted = true;
  const auto q = write("iter2.csv", kHeader + row("P1,a,1", "right", "0", "0.5") +
                                        row("P1,a,2", "right", "0", "0.5") +
                                        row("P1,a,2", "right", "1", "0.5") +
                                        row("P1,a,01", "right", "1", "0.6"));
  const auto grouped = read_all({q}, unsorted);
  ASSERT_EQ(grouped.size(), 2U);
  EXPECT_EQ(grouped[0].iteration, 1);
  EXPECT_EQ(grouped[0].times.size(), 2U);
}

TEST(TraceRejects, AnIterationWrittenDifferentlyThatReappearsIsTheSameTrialReappearing) {
  const auto msg = strict_error(kHeader + row("P1,a,1", "right", "0", "0.5") +
                                row("P1,a,1", "right", "1", "0.5") + row("P1,a,2", "right", "0", "0.5") +
                                row("P1,a,2", "right", "1", "0.5") + row("P1,a,01", "right", "2", "0.5") +
                                row("P1,a,01", "right", "3", "0.5"));
  EXPECT_NE(msg.find("strict.csv:6: rows of this trial already appeared at "), std::string::npos) << msg;
}

// Blank lines before the header are skipped; the delimiter is still detected.
TEST(TraceReader, BlankLinesBeforeTheHeaderAreSkipped) {
  const auto p = write("blank.csv", "\n\r\n\nparticipant;iteration;target;t;pad\nP1;1;left;0;0.5\n"
                                    "P1;1;left;1;0.25\n");
  const auto trials = read_all({p});
  ASSERT_EQ(trials.size(), 1U);
  EXPECT_EQ(trials[0].line, 5U);
  EXPECT_EQ(trials[0].pads[1], 0.25);
}

TEST(TraceRejects, IterationsOutsideWhatTheTablesReadAreInvalid) {
  auto msg = strict_error(kHeader + row("P1,a,-1", "right", "0", "0.5"));
  EXPECT_NE(msg.find("strict.csv:2: column 'iteration': -1 is outside 0 to 1e9"), std::string::npos)
      << msg;
  msg = strict_error(kHeader + row("P1,a,1000000001", "right", "0", "0.5"));
  EXPECT_NE(msg.find("is outside 0 to 1e9"), std::string::npos) << msg;
}
