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
  const auto summary = feint::metrics::score_each(
      {p}, ScoreSettings{}, [&](const feint::io::Trial& t, const feint::metrics::TrialScore& s) {
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
