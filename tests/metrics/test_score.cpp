// The scoring library (score.hpp): score_each / score_to_file, accounting, sidecar, atomicity.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include <sys/stat.h>
#include <string>
#include <vector>

#include "feint/error.hpp"
#include "feint/io/csv.hpp"
#include "feint/io/number.hpp"
#include "feint/io/scores.hpp"
#include "feint/metrics/score.hpp"

namespace fs = std::filesystem;
using feint::metrics::OnError;
using feint::metrics::ScoreSettings;

namespace {

class ScoreLib : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("feint-test-score-" + std::to_string(::getpid()) + "-" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string write(const std::string& name, const std::string& content) {
    const auto p = dir_ / name;
    std::ofstream(p, std::ios::binary) << content;
    return p.string();
  }
  static std::string read(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::ostringstream ss;
    ss << in.rdbuf();
    return ss.str();
  }
  std::vector<std::string> listing() const {
    std::vector<std::string> out;
    for (const auto& e : fs::directory_iterator(dir_)) out.push_back(e.path().filename().string());
    std::sort(out.begin(), out.end());
    return out;
  }
  fs::path dir_;
};

const std::string kHeader = "participant,condition,iteration,target,t,pad,pad_speed\n";

// metrics.md example E (T = 1, v = 1): error 25/54, confusion 287/1440, t_rev 0.3.
std::string example_e(const std::string& key) {
  const double t[] = {0, 0.3, 1, 2, 4};
  const double mu[] = {0.5, 0.6, 0.4, 0.4, 0.9};
  std::string s;
  for (int i = 0; i < 5; ++i) {
    s += key + ",right," + feint::io::format_double(t[i]) + "," + feint::io::format_double(mu[i]) + ",1\n";
  }
  return s;
}

}  // namespace

TEST_F(ScoreLib, ScoreEachHandsOutEveryTrialWithItsScore) {
  const auto p = write("log.csv", kHeader + example_e("P1,adaptive,1") + example_e("P1,adaptive,2"));
  std::vector<double> errors, confusions;
  ScoreSettings speed;  // worked example E's `speed` value (raw is the default)
  speed.metrics.norm = feint::metrics::ConfusionNorm::speed;
  const auto summary = feint::metrics::score_each(
      {p}, speed, [&](const feint::io::Trial& t, const feint::metrics::TrialScore& s) {
        EXPECT_EQ(t.participant, "P1");
        errors.push_back(s.error);
        confusions.push_back(s.confusion);
      });
  ASSERT_EQ(errors.size(), 2U);
  EXPECT_NEAR(errors[1], 25.0 / 54, 1e-12);
  EXPECT_NEAR(confusions[0], 287.0 / 1440, 1e-12);
  EXPECT_EQ(summary.rows_read, 10U);
  EXPECT_EQ(summary.rows_scored, 10U);
  EXPECT_EQ(summary.trials_scored, 2U);
  EXPECT_TRUE(listing() == std::vector<std::string>{"log.csv"}) << "score_each must not write files";
}

TEST_F(ScoreLib, ScoreToFileWritesTableSidecarAndRejects) {
  const auto p = write("log.csv", kHeader + example_e("P1,adaptive,1") +
                                      "P2,adaptive,1,right,0,0.5,1\nP2,adaptive,1,right,1,-0.1,1\n");
  ScoreSettings s;
  s.on_error = OnError::skip;
  s.metrics.norm = feint::metrics::ConfusionNorm::raw;
  s.tool_version = "9.9.9";
  const auto out = (dir_ / "scores.csv").string();
  const auto summary = feint::metrics::score_to_file({p}, s, out);
  EXPECT_EQ(summary.rows_read, 7U);
  EXPECT_EQ(summary.rows_scored + summary.rows_rejected, summary.rows_read);
  EXPECT_EQ(summary.trials_rejected, 1U);
  EXPECT_EQ(summary.rejects_path, out + ".rejects.csv");
  EXPECT_EQ(summary.sidecar_path, out + ".meta.json");

  feint::io::CsvReader r(out);
  EXPECT_EQ(r.header(), feint::metrics::score_columns());
  ASSERT_TRUE(r.next());
  EXPECT_NEAR(*feint::io::parse_double(r.field(static_cast<std::size_t>(r.column("confusion")))),
              287.0 / 800, 1e-12);
  EXPECT_EQ(r.field(static_cast<std::size_t>(r.column("reversal_time"))), "0.3");
  EXPECT_FALSE(r.next());

  const auto meta = read(out + ".meta.json");
  EXPECT_NE(meta.find("\"feint_version\": \"9.9.9\""), std::string::npos) << meta;
  EXPECT_NE(meta.find("\"confusion_norm\": \"raw\""), std::string::npos) << meta;
  EXPECT_NE(meta.find("\"rows_rejected\": 2"), std::string::npos) << meta;
  const auto rejects = read(out + ".rejects.csv");
  EXPECT_NE(rejects.find("column 'pad': -0.1 is outside [0, 1] (trial P2/adaptive/1)"),
            std::string::npos) << rejects;
}

TEST_F(ScoreLib, AFailingRunLeavesNoOutputBehind) {
  const auto p = write("log.csv", kHeader + example_e("P1,adaptive,1") + "P2,adaptive,1,right,0,0.5,1\n");
  const auto out = (dir_ / "scores.csv").string();
  try {
    feint::metrics::score_to_file({p}, ScoreSettings{}, out);
    ADD_FAILURE() << "no throw";
  } catch (const feint::InvalidData& e) {
    EXPECT_NE(std::string(e.what()).find("log.csv:7: 1 valid sample(s); a trial needs at least 2 "
                                         "(metrics.md) (trial P2/adaptive/1)"), std::string::npos)
        << e.what();
  }
  EXPECT_TRUE(listing() == std::vector<std::string>{"log.csv"});
}

TEST_F(ScoreLib, ZeroValidTrialsIsAnError) {
  const auto p = write("log.csv", kHeader);
  EXPECT_THROW(feint::metrics::score_to_file({p}, ScoreSettings{}, (dir_ / "s.csv").string()),
               feint::InvalidData);
  EXPECT_TRUE(listing() == std::vector<std::string>{"log.csv"});
}

TEST_F(ScoreLib, SettingsAreCheckedBeforeAnythingIsRead) {
  const auto p = write("log.csv", kHeader + example_e("P1,adaptive,1"));
  ScoreSettings s;
  s.rejects_path = "r.csv";  // without skip
  EXPECT_THROW(feint::metrics::score_to_file({p}, s, (dir_ / "s.csv").string()), feint::UsageError);
  s = {};
  s.metrics.trim_start = 0.7;
  s.metrics.trim_end = 0.3;
  EXPECT_THROW(feint::metrics::score_to_file({p}, s, (dir_ / "s.csv").string()), feint::UsageError);
  s = {};
  EXPECT_THROW(feint::metrics::score_to_file({p}, s, p), feint::UsageError);  // output = input
  EXPECT_TRUE(listing() == std::vector<std::string>{"log.csv"});
}

TEST_F(ScoreLib, ASpecialFileIsWrittenInPlaceNeverReplaced) {
  // Renaming a temporary over /dev/null or a FIFO would replace the device: write into it instead,
  // and put no sidecar beside it. (A FIFO stands in for /dev/null here.)
  const auto p = write("log.csv", kHeader + example_e("P1,adaptive,1"));
  const auto fifo = dir_ / "pipe";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  std::string captured;
  std::thread reader([&] {
    std::ifstream in(fifo, std::ios::binary);
    std::ostringstream ss;
    ss << in.rdbuf();
    captured = ss.str();
  });
  const auto summary = feint::metrics::score_to_file({p}, ScoreSettings{}, fifo.string());
  reader.join();
  EXPECT_TRUE(fs::is_fifo(fifo));
  EXPECT_EQ(summary.sidecar_path, "");
  EXPECT_EQ(captured.substr(0, 24), "participant,condition,it");
  EXPECT_NE(captured.find("\nP1,adaptive,1,"), std::string::npos) << captured;
  EXPECT_TRUE((listing() == std::vector<std::string>{"log.csv", "pipe"}));
}

// Extreme trial durations. Scores do not depend on the unit of time (metrics.md), so a
// trace stretched to 1e263 s or squeezed to 1e-300 s scores as the original; a score that cannot
// be represented (a speed beyond the largest double) rejects the trial with the reason.
TEST_F(ScoreLib, ExtremeDurationsScoreAsTheUnscaledTrace) {
  for (const double scale : {1e-300, 1e-250, 1e263, 1e300}) {
    const double t[] = {0, 0.3, 1, 2, 4};
    const double mu[] = {0.5, 0.6, 0.4, 0.4, 0.9};
    std::string s = kHeader;
    for (int i = 0; i < 5; ++i) {
      s += "P1,A,1,right," + feint::io::format_double(t[i] * scale) + "," +
           feint::io::format_double(mu[i]) + "," + feint::io::format_double(1 / scale) + "\n";
    }
    const auto in = write("extreme.csv", s);
    for (const auto norm : {feint::metrics::ConfusionNorm::speed, feint::metrics::ConfusionNorm::raw}) {
      ScoreSettings st;
      st.metrics.norm = norm;
      st.check_durations = false;  // no round of the game lasts 1e263 s: this checks the numerics
      std::vector<feint::metrics::TrialScore> got;
      feint::metrics::score_each({in}, st, [&](const feint::io::Trial&,
                                               const feint::metrics::TrialScore& sc) {
        got.push_back(sc);
      });
      ASSERT_EQ(got.size(), 1u);
      SCOPED_TRACE(scale);
      EXPECT_NEAR(got[0].error, 25.0 / 54, 1e-12);
      // Speed: metrics.md's 287/1440. Raw confusion is in pad units, the same for every unit of
      // time too: metrics.md gives 287/800 for example E.
      EXPECT_NEAR(got[0].confusion,
                  norm == feint::metrics::ConfusionNorm::speed ? 287.0 / 1440 : 287.0 / 800, 1e-12);
      EXPECT_NEAR(got[0].reversal_time / scale, 0.3, 1e-12);
      EXPECT_TRUE(std::isfinite(got[0].duration));
    }
  }
}

TEST_F(ScoreLib, AScoreThatIsNotFiniteRejectsTheTrialNeverWritesIt) {
  // A pad moving 0.5 in 1e-310 s: its speed (5e309 pad units/s) is beyond the largest double, so
  // the raw confusion cannot be represented.
  const std::string log = kHeader + "P1,A,1,right,0,0.5,1\nP1,A,1,right,1e-310,1,1\n"
                          "P1,A,1,right,2e-310,0.5,1\nP1,A,1,right,3e-310,0.6,1\n" + example_e("P2,A,1");
  const auto in = write("tiny.csv", log);
  ScoreSettings st;
  st.metrics.norm = feint::metrics::ConfusionNorm::raw;
  try {
    feint::metrics::score_to_file({in}, st, (dir_ / "s.csv").string());
    FAIL() << "a non-finite score was written";
  } catch (const feint::InvalidData& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(in + ":2:"), std::string::npos) << what;
    EXPECT_NE(what.find("(trial P1/A/1)"), std::string::npos) << what;
    EXPECT_NE(what.find("not a finite number"), std::string::npos) << what;
  }
  EXPECT_FALSE(fs::exists(dir_ / "s.csv"));
  st.on_error = OnError::skip;
  const auto summary = feint::metrics::score_to_file({in}, st, (dir_ / "s.csv").string());
  EXPECT_EQ(summary.trials_scored, 1u);
  EXPECT_EQ(summary.trials_rejected, 1u);
  EXPECT_EQ(summary.rows_rejected, 4u);
  EXPECT_EQ(summary.rows_scored, 5u);
  const std::string scores = read(dir_ / "s.csv");
  EXPECT_EQ(scores.find("P1,"), std::string::npos) << scores;
  EXPECT_EQ(scores.find("nan"), std::string::npos);
  EXPECT_EQ(scores.find("inf"), std::string::npos);
  const std::string rejects = read(dir_ / "s.csv.rejects.csv");
  EXPECT_NE(rejects.find("not a finite number"), std::string::npos) << rejects;
  EXPECT_NE(rejects.find(",P1,A,1,4,"), std::string::npos) << rejects;
}

TEST_F(ScoreLib, HeaderOnlyInputNamesTheFile) {
  const auto p = write("only_header.csv", kHeader);
  try {
    feint::metrics::score_to_file({p}, ScoreSettings{}, (dir_ / "s.csv").string());
    FAIL();
  } catch (const feint::InvalidData& e) {
    EXPECT_EQ(std::string(e.what()), p + ": no data rows (a header only; expected one row per pad "
                                         "sample after it), so no valid trial to score");
  }
}

// Times in milliseconds. --time-unit ms converts them to seconds (the scores equal the
// seconds log's), is recorded in the sidecar, and a seconds reading of a ms log warns once.
TEST_F(ScoreLib, TimeUnitMsConvertsToSecondsAndIsRecorded) {
  const double t[] = {0, 300, 1000, 2000, 4000};  // example E in ms
  const double mu[] = {0.5, 0.6, 0.4, 0.4, 0.9};
  std::string log = kHeader;
  for (int i = 0; i < 5; ++i) {
    log += "P1,A,1,right," + feint::io::format_double(t[i]) + "," + feint::io::format_double(mu[i]) +
           ",1\n";
  }
  const auto in = write("ms.csv", log);
  ScoreSettings st;
  st.metrics.norm = feint::metrics::ConfusionNorm::speed;  // example E's `speed` value
  st.time_unit = feint::metrics::TimeUnit::ms;
  std::vector<std::string> warnings;
  st.on_warning = [&](const std::string& w) { warnings.push_back(w); };
  std::vector<feint::metrics::TrialScore> got;
  auto collect = [&](const feint::io::Trial&, const feint::metrics::TrialScore& s) { got.push_back(s); };
  feint::metrics::score_each({in}, st, collect);
  ASSERT_EQ(got.size(), 1u);
  EXPECT_NEAR(got[0].error, 25.0 / 54, 1e-12);
  EXPECT_NEAR(got[0].confusion, 287.0 / 1440, 1e-12);
  EXPECT_EQ(got[0].duration, 4.0);
  EXPECT_NEAR(got[0].reversal_time, 0.3, 1e-15);
  EXPECT_TRUE(warnings.empty());

  const auto out = (dir_ / "s.csv").string();
  const auto summary = feint::metrics::score_to_file({in}, st, out);
  EXPECT_EQ(summary.median_duration, 4.0);
  EXPECT_NE(read(out + ".meta.json").find("\"time_unit\": \"ms\""), std::string::npos);

  // The same log read as seconds: a 4000 s trial cannot be seconds (over 20 minutes): refused,
  // naming the file, line, column and the option.
  got.clear();
  ScoreSettings secs;
  secs.metrics.norm = feint::metrics::ConfusionNorm::speed;
  secs.on_warning = st.on_warning;
  try {
    feint::metrics::score_each({in}, secs, collect);
    FAIL() << "expected InvalidData";
  } catch (const feint::InvalidData& e) {
    EXPECT_NE(std::string(e.what()).find("ms.csv:2: column 't': the median trial lasts 4000 s (1 "
                                         "trials; the longest, trial P1/A/1, 4000 s): these times "
                                         "cannot be seconds"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("give --time-unit ms"), std::string::npos) << e.what();
  }
  EXPECT_TRUE(warnings.empty());

  // A 600 "s" trial (600 ms read as seconds) is implausible, not impossible: one warning, also
  // as a structured diagnostic.
  std::string slow = kHeader;
  for (int i = 0; i < 5; ++i) {  // example E slowed down 150 times: 0.6 s read as 600 s
    slow += "P1,A,1,right," + feint::io::format_double(t[i] * 0.15) + "," +
            feint::io::format_double(mu[i]) + ",1\n";
  }
  const auto slow_in = write("slow.csv", slow);
  got.clear();
  const auto summary2 = feint::metrics::score_each({slow_in}, secs, collect);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("the median trial lasts 600 s (1 trials, longest 600 s)"),
            std::string::npos) << warnings[0];
  EXPECT_NE(warnings[0].find("--time-unit ms"), std::string::npos) << warnings[0];
  ASSERT_EQ(summary2.diagnostics.size(), 1u);
  EXPECT_EQ(summary2.diagnostics[0].code, "time-unit-ms-suspected");
  EXPECT_EQ(summary2.diagnostics[0].column, "t");
  EXPECT_EQ(summary2.diagnostics[0].message, warnings[0]);
  // The pad speed is in pad units per second: read 150 times too slow, every movement looks 150
  // times slower than it was, and the confusion is 150 times too small (what the warning prevents).
  ASSERT_EQ(got.size(), 1u);
  EXPECT_NEAR(got[0].confusion, 287.0 / 1440 / 150, 1e-15);
}

TEST_F(ScoreLib, TimeUnitMsOnALogInSecondsWarns) {
  const auto in = write("s.csv", kHeader + example_e("P1,A,1") + example_e("P2,A,1"));
  ScoreSettings st;
  st.metrics.norm = feint::metrics::ConfusionNorm::speed;  // example E's `speed` value
  st.time_unit = feint::metrics::TimeUnit::ms;
  std::vector<std::string> warnings;
  st.on_warning = [&](const std::string& w) { warnings.push_back(w); };
  const auto summary = feint::metrics::score_each({in}, st, [](const auto&, const auto&) {});
  EXPECT_EQ(summary.median_duration, 0.004);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("median trial lasts 0.004 s (2 trials"), std::string::npos) << warnings[0];
}

// The output and its sidecar are replaced as one unit. Two runs writing the same output
// at once (threads here; the lock is flock(2) on the folder, so processes behave the same) must
// always leave one run's scores beside the same run's sidecar.
TEST_F(ScoreLib, ConcurrentRunsNeverPairOneRunsScoresWithTheOthersSidecar) {
  const auto a = write("a.csv", kHeader + example_e("PA,A,1"));
  const auto b = write("b.csv", kHeader + example_e("PB,A,1") + example_e("PB,A,2"));
  const auto out = (dir_ / "s.csv").string();
  for (int round = 0; round < 25; ++round) {
    std::thread ta([&] { feint::metrics::score_to_file({a}, ScoreSettings{}, out); });
    std::thread tb([&] { feint::metrics::score_to_file({b}, ScoreSettings{}, out); });
    ta.join();
    tb.join();
    const std::string scores = read(out), sidecar = read(out + ".meta.json");
    const bool is_a = scores.find("\nPA,") != std::string::npos;
    ASSERT_NE(sidecar.find(is_a ? "a.csv" : "b.csv"), std::string::npos)
        << "round " << round << ": scores of run " << (is_a ? "a" : "b") << " beside\n" << sidecar;
    ASSERT_EQ(sidecar.find(is_a ? "b.csv" : "a.csv"), std::string::npos);
    ASSERT_TRUE(feint::io::read_scores_provenance(out).ignored.empty());
  }
  std::vector<std::string> left = listing();
  EXPECT_EQ(left, (std::vector<std::string>{"a.csv", "b.csv", "s.csv", "s.csv.meta.json"}))
      << "temporary files left behind";
}

TEST_F(ScoreLib, ASidecarThatDoesNotDescribeTheTableIsIgnored) {
  const auto in = write("log.csv", kHeader + example_e("P1,A,1"));
  const auto out = (dir_ / "s.csv").string();
  feint::metrics::score_to_file({in}, ScoreSettings{}, out);
  const auto good = feint::io::read_scores_provenance(out);
  EXPECT_EQ(good.sidecar_path, out + ".meta.json");
  EXPECT_TRUE(good.ignored.empty());
  EXPECT_NE(read(out + ".meta.json").find("\"output_check\": {\"bytes\": "), std::string::npos);
  std::ofstream(out, std::ios::app) << "P9,A,1,,,1,5,4,0.5,0.5,,0,0.9,0\n";  // edited since
  const auto bad = feint::io::read_scores_provenance(out);
  EXPECT_TRUE(bad.sidecar_path.empty());
  EXPECT_TRUE(bad.confusion_normalisation.empty());
  EXPECT_NE(bad.ignored.find("s.csv.meta.json ignored: it describes a table of "), std::string::npos)
      << bad.ignored;
}
