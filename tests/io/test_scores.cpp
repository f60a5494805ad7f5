// Scores tables (input of `feint table`): loading, and every invalid-data error.
#include "feint/io/scores.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "feint/error.hpp"

using namespace feint;
using namespace feint::io;

namespace {

class ScoresFile : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("feint-scores-" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) +
            "-" + ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ec;
    std::filesystem::remove_all(dir_, ec);
  }
  std::string write(const std::string& name, const std::string& text) {
    const auto p = dir_ / name;
    std::ofstream(p, std::ios::binary) << text;
    return p.string();
  }
  // The message of the InvalidData thrown by `f`, or "" if none.
  template <class F>
  static std::string invalid_message(F&& f) {
    try {
      f();
    } catch (const InvalidData& e) {
      return e.what();
    }
    return {};
  }
  std::filesystem::path dir_;
};

}  // namespace

TEST_F(ScoresFile, LoadsParticipantConditionIterationAndMetrics) {
  const auto p = write("s.csv",
                       "participant,condition,iteration,error,confusion,extra\n"
                       "P01,adaptive,1,0.5,0.9,x\n"
                       "P01,adaptive,2,0.25,,y\n"
                       "P02,random,1,1e-3,1,z\n");
  const auto t = load_scores(p);
  ASSERT_EQ(t.records.size(), 3u);
  EXPECT_TRUE(t.has_condition);
  EXPECT_EQ(t.records[1].participant, "P01");
  EXPECT_EQ(t.records[1].iteration, 2);
  EXPECT_EQ(t.records[1].values[0], 0.25);
  EXPECT_FALSE(t.records[1].values[1].has_value());  // empty cell = missing
  EXPECT_EQ(t.records[2].values[0], 1e-3);
  EXPECT_EQ(t.records[2].line, 4u);
  EXPECT_EQ(t.conditions(), (std::vector<std::string>{"adaptive", "random"}));
  EXPECT_EQ(t.iterations(), (std::vector<long long>{1, 2}));
  EXPECT_EQ(t.metric_index("CONFUSION"), 1);
  EXPECT_EQ(t.metric_index("pad"), -1);
}

TEST_F(ScoresFile, ConditionColumnIsOptionalAndNamesAreCaseInsensitive) {
  const auto p = write("s.csv", "Participant;Iteration;Error;Confusion\nP1;1;0.5;0.5\nP2;1;0.6;0.4\n");
  const auto t = load_scores(p);
  EXPECT_FALSE(t.has_condition);
  EXPECT_EQ(t.conditions(), std::vector<std::string>{""});
  EXPECT_EQ(t.records.size(), 2u);
}

TEST_F(ScoresFile, AnyNumericColumnCanBeAMetric) {
  const auto p = write("s.csv", "participant,iteration,reversal_time\nP1,1,2.5\n");
  ScoresOptions o;
  o.metrics = {"reversal_time"};
  EXPECT_EQ(load_scores(p, o).records[0].values[0], 2.5);
}

TEST_F(ScoresFile, MissingRequiredColumn) {
  const auto p = write("s.csv", "participant,condition,error,confusion\nP1,a,0.5,0.5\n");
  const auto msg = invalid_message([&] { load_scores(p); });
  EXPECT_EQ(msg, p + ":1: column 'iteration' (iteration) is missing; the header has: "
                     "participant, condition, error, confusion");
}

TEST_F(ScoresFile, MissingMetricColumn) {
  const auto p = write("s.csv", "participant,iteration,error\nP1,1,0.5\n");
  const auto msg = invalid_message([&] { load_scores(p); });
  EXPECT_EQ(msg, p + ":1: metric column 'confusion' is missing; the header has: "
                     "participant, iteration, error");
}

TEST_F(ScoresFile, NonNumericMetricNamesLineColumnValueAndTrial) {
  const auto p = write("s.csv",
                       "participant,condition,iteration,error,confusion\n"
                       "P01,adaptive,1,0.5,0.9\n"
                       "P07,adaptive,3,abc,0.9\n");
  const auto msg = invalid_message([&] { load_scores(p); });
  EXPECT_EQ(msg, p + ":3: column 'error': 'abc' is not a number (P07/adaptive/3; expected a finite "
                     "number with a decimal point, or an empty cell)");
  const auto q = write("q.csv", "participant,iteration,error,confusion\nP1,1,0.5,nan\n");
  EXPECT_NE(invalid_message([&] { load_scores(q); }).find(":2: column 'confusion': 'nan' is not a number (P1/1;"),
            std::string::npos);
  const auto r = write("r.csv", "participant,iteration,error,confusion\nP1,1,\"0,5\",0.5\n");
  EXPECT_NE(invalid_message([&] { load_scores(r); }).find("'0,5' is not a number"), std::string::npos);
}

TEST_F(ScoresFile, NonIntegerIteration) {
  const auto p = write("s.csv", "participant,condition,iteration,error,confusion\nP01,a,3.5,0.5,0.5\n");
  EXPECT_EQ(invalid_message([&] { load_scores(p); }),
            p + ":2: column 'iteration': '3.5' is not an iteration number (participant P01/a; "
                "expected a whole number from 0 to 1e9)");
  const auto q = write("q.csv", "participant,iteration,error,confusion\nP01,99999999999,0.5,0.5\n");
  EXPECT_NE(invalid_message([&] { load_scores(q); }).find("'99999999999' is not an iteration number"),
            std::string::npos);
}

TEST_F(ScoresFile, EmptyParticipantOrCondition) {
  const auto p = write("s.csv", "participant,condition,iteration,error,confusion\n,a,1,0.5,0.5\n");
  EXPECT_EQ(invalid_message([&] { load_scores(p); }),
            p + ":2: column 'participant': empty participant (expected an id)");
  const auto q = write("q.csv", "participant,condition,iteration,error,confusion\nP1,a,1,0.5,0.5\n"
                                "P1,,2,0.5,0.5\n");
  EXPECT_EQ(invalid_message([&] { load_scores(q); }),
            q + ":3: column 'condition': empty condition (participant P1; line 2 has one: every row "
                "needs its condition, or none does)");
}

// `feint score` on logs without a condition column writes an empty condition column;
// the tables read it as one condition for everybody (the score -> table round trip).
TEST_F(ScoresFile, AConditionColumnEmptyOnEveryRowMeansNoConditions) {
  const auto p = write("s.csv", "participant,condition,iteration,error,confusion\nP1,,1,0.5,0.5\n"
                                "P2,,1,0.25,0.5\nP1,,2,0.5,\n");
  const auto t = load_scores(p);
  EXPECT_FALSE(t.has_condition);
  ASSERT_EQ(t.records.size(), 3u);
  EXPECT_EQ(t.conditions(), std::vector<std::string>{""});
  EXPECT_EQ(t.records[1].values[0], 0.25);
}

TEST_F(ScoresFile, DuplicateParticipantIterationNamesBothLines) {
  const auto p = write("s.csv",
                       "participant,condition,iteration,error,confusion\n"
                       "P01,adaptive,3,0.5,0.5\n"
                       "P01,random,3,0.5,0.5\n"  // another condition: fine
                       "P01,adaptive,3,0.6,0.5\n");
  EXPECT_EQ(invalid_message([&] { load_scores(p); }),
            p + ":4: duplicate participant/condition/iteration P01/adaptive/3: already on line 2 "
                "(one value per participant and iteration is expected)");
}

TEST_F(ScoresFile, NoDataRowsIsAnError) {
  const auto p = write("s.csv", "participant,iteration,error,confusion\n");
  EXPECT_EQ(invalid_message([&] { load_scores(p); }),
            p + ": no data rows (expected one row per participant and iteration after the header)");
}

TEST_F(ScoresFile, UnreadableFileIsAnIoError) {
  EXPECT_THROW(load_scores((dir_ / "absent.csv").string()), IoError);
}

TEST_F(ScoresFile, ReadsTheSidecarOfFeintScore) {
  const auto p = write("out.csv", "participant,iteration,error,confusion\nP1,1,0.5,0.5\n");
  write("out.csv.meta.json",
        "{\n  \"tool\": \"feint score\",\n  \"settings\": {\n    \"trim_start\": 0.1,\n"
        "    \"confusion_norm\": \"speed\",\n    \"pad_speed\": {\"source\": \"none\"},\n"
        "    \"column_map\": {}\n  },\n  \"inputs\": [\"a.csv\", \"b.csv\"],\n"
        "  \"units\": {\"duration\": \"s\", \"confusion\": \"fraction of full-speed movement, "
        "[0, 1]\"}\n}\n");
  const auto prov = read_scores_provenance(p);
  EXPECT_EQ(prov.sidecar_path, (dir_ / "out.csv.meta.json").string());
  EXPECT_EQ(prov.confusion_normalisation,
            "speed (confusion in fraction of full-speed movement, [0, 1])");
}

TEST_F(ScoresFile, SidecarGivesTheConfusionNormalisation) {
  const auto p = write("scores.csv", "participant,iteration,error,confusion\nP1,1,0.5,0.5\n");
  EXPECT_TRUE(read_scores_provenance(p).sidecar_path.empty());
  write("scores.csv.json",
        "{\"tool\": \"feint score\", \"settings\": {\"trim\": [0.1, 0.1], "
        "\"confusion_normalization\": \"max_possible\", \"dead_band\": 0.02}}\n");
  const auto prov = read_scores_provenance(p);
  EXPECT_EQ(prov.sidecar_path, (dir_ / "scores.csv.json").string());
  EXPECT_EQ(prov.confusion_normalisation, "max_possible");
  ASSERT_GE(prov.settings.size(), 3u);
  EXPECT_EQ(prov.settings[0].first, "tool");
  EXPECT_EQ(prov.settings[1].first, "settings.trim");
  EXPECT_EQ(prov.settings[1].second, "[0.1, 0.1]");
}

TEST_F(ScoresFile, NumericColumnByGroupCountsMissing) {
  const auto p = write("d.csv", "g,x\na,1\nb,2\na,\na,3.5\n");
  const auto c = load_numeric_column(p, "x", "g");
  EXPECT_EQ(c.groups, (std::vector<std::string>{"a", "b"}));
  EXPECT_EQ(c.values[0], (std::vector<double>{1, 3.5}));
  EXPECT_EQ(c.missing[0], 1u);
  EXPECT_EQ(c.values[1], (std::vector<double>{2}));
  EXPECT_EQ(invalid_message([&] { load_numeric_column(p, "y"); }),
            p + ":1: column 'y' (--column) is missing; the header has: g, x");
  const auto q = write("e.csv", "g,x\na,1\nb,two\n");
  EXPECT_EQ(invalid_message([&] { load_numeric_column(q, "x", "g"); }),
            q + ":3: column 'x': 'two' is not a number (g b; expected a finite number with a "
                "decimal point, or an empty cell)");
}
