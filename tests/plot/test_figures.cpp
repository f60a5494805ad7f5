// The figures' data are the tables' numbers (no statistic computed twice), marked iterations are
// exactly the significant ones, occurrence shares sum to 1, and the trace means are what the
// traces say.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>

#include "feint/error.hpp"
#include "feint/io/scores.hpp"
#include "feint/plot/figures.hpp"
#include "feint/tables/likert.hpp"
#include "feint/tables/table1.hpp"

using namespace feint;
namespace fs = std::filesystem;

namespace {

// The tests' files, removed when the test program ends.
struct TempFolder {
  fs::path path = fs::temp_directory_path() / ("feint-plot-" + std::to_string(::getpid()));
  ~TempFolder() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
};

fs::path temp_file(const std::string& name, const std::string& content) {
  static TempFolder folder;
  const fs::path& dir = folder.path;
  fs::create_directories(dir);
  const fs::path p = dir / name;
  std::ofstream(p, std::ios::binary) << content;
  return p;
}

// 2 conditions x 12 participants x 6 iterations. At iterations 2 and 5 condition A is far above
// B (a clear difference); elsewhere they overlap. Error is near 0.5 except at iteration 4, where
// both are far below it.
std::string scores_csv() {
  std::string s = "participant,condition,iteration,strategy,variant,error,confusion\n";
  const char* strategies[] = {"ambiguous", "optimal", "switching"};
  for (int c = 0; c < 2; ++c) {
    for (int p = 0; p < 12; ++p) {
      for (int it = 1; it <= 6; ++it) {
        const double noise = ((p * 37 + it * 11 + c * 5) % 13) / 100.0 - 0.06;
        double e = 0.5 + noise;
        if (c == 0 && (it == 2 || it == 5)) e += 0.25;
        if (it == 4) e -= 0.3;
        const double conf = 0.4 + noise / 2;
        s += "P" + std::to_string(c * 100 + p) + "," + (c == 0 ? "A" : "B") + "," +
             std::to_string(it) + "," + strategies[(p + it + c) % 3] + ",main," +
             std::to_string(e) + "," + std::to_string(conf) + "\n";
      }
    }
  }
  return s;
}

struct Tables {
  io::ScoresTable scores;
  tables::Table1 one, two;
};

Tables build(stats::PAdjustMethod adjust) {
  const fs::path p = temp_file("scores.csv", scores_csv());
  Tables t;
  t.scores = io::load_scores(p.string());
  tables::Table1Options o;
  o.p_adjust = adjust;
  t.one = tables::build_table1(t.scores, o);
  o.compare = std::pair<std::string, std::string>{"A", "B"};
  t.two = tables::build_table1(t.scores, o);
  return t;
}

bool is_difference(const std::string& label) {
  return label == "M>R" || label == "M<R" || label == "A>B" || label == "A<B";
}

}  // namespace

TEST(MetricFigure, PlotsTheOneSampleTablesMeansAndIntervals) {
  const Tables t = build(stats::PAdjustMethod::holm);
  for (const std::string metric : {"error", "confusion"}) {
    const plot::MetricFigureData d = plot::metric_figure_data(t.one, &t.two, metric);
    EXPECT_EQ(d.reference, metric == "error" ? 0.5 : 0.95);
    EXPECT_EQ(d.p_adjust, "holm");
    ASSERT_EQ(d.series.size(), 2u);
    std::size_t checked = 0;
    for (const auto& row : t.one.rows) {
      if (row.metric != metric) continue;
      const auto& s = row.group1 == "A" ? d.series[0] : d.series[1];
      EXPECT_EQ(s.condition, row.group1);
      const auto& pt = s.points.at(static_cast<std::size_t>(*row.iteration - 1));
      EXPECT_EQ(pt.iteration, *row.iteration);
      EXPECT_EQ(pt.mean, *row.result.mean1);
      EXPECT_EQ(pt.conf_low, *row.result.conf_low);
      EXPECT_EQ(pt.conf_high, *row.result.conf_high);
      EXPECT_EQ(pt.differs, is_difference(row.label)) << row.label;
      ++checked;
    }
    EXPECT_EQ(checked, 12u);
    // The drawing carries the same numbers.
    const plot::Figure f = plot::metric_figure(d);
    ASSERT_EQ(f.panels.size(), 1u);
    ASSERT_EQ(f.panels[0].lines.size(), 2u);
    for (std::size_t c = 0; c < 2; ++c) {
      for (std::size_t i = 0; i < 6; ++i) {
        EXPECT_EQ(f.panels[0].lines[c].y[i], d.series[c].points[i].mean);
        EXPECT_EQ(f.panels[0].lines[c].lo[i], d.series[c].points[i].conf_low);
        EXPECT_EQ(f.panels[0].lines[c].hi[i], d.series[c].points[i].conf_high);
        EXPECT_EQ(f.panels[0].lines[c].filled[i], d.series[c].points[i].differs);
      }
    }
    ASSERT_EQ(f.panels[0].refs.size(), 1u);
    EXPECT_EQ(f.panels[0].refs[0].value, d.reference);
  }
}

TEST(MetricFigure, MarksExactlyTheIterationsTheComparisonFoundDifferent) {
  for (const auto adjust : {stats::PAdjustMethod::none, stats::PAdjustMethod::bonferroni}) {
    const Tables t = build(adjust);
    const plot::MetricFigureData d = plot::metric_figure_data(t.one, &t.two, "error");
    std::vector<long long> expected;
    for (const auto& row : t.two.rows) {
      if (row.metric == "error" && is_difference(row.label)) expected.push_back(*row.iteration);
    }
    EXPECT_EQ(d.marked, expected);
    EXPECT_EQ(d.marked, (std::vector<long long>{2, 5}));  // the designed differences
    const plot::Figure f = plot::metric_figure(d);
    EXPECT_EQ(f.panels[0].marks, (std::vector<double>{2, 5}));
    EXPECT_EQ(d.group1, "A");
    EXPECT_EQ(d.group2, "B");
  }
  // Without a comparison nothing is marked.
  const Tables t = build(stats::PAdjustMethod::none);
  EXPECT_TRUE(plot::metric_figure_data(t.one, nullptr, "error").marked.empty());
  EXPECT_TRUE(plot::metric_figure(plot::metric_figure_data(t.one, nullptr, "error"))
                  .panels[0]
                  .marks.empty());
}

TEST(MetricFigure, FilledMarkersFollowTheAdjustedLabels) {
  // Iteration 4 is far below 0.5 in both conditions: filled whatever the adjustment.
  const Tables t = build(stats::PAdjustMethod::bonferroni);
  const plot::MetricFigureData d = plot::metric_figure_data(t.one, nullptr, "error");
  EXPECT_TRUE(d.series[0].points[3].differs);
  EXPECT_TRUE(d.series[1].points[3].differs);
  EXPECT_FALSE(d.series[1].points[0].differs);
}

TEST(MetricFigure, UnknownMetricIsInvalidData) {
  const Tables t = build(stats::PAdjustMethod::none);
  EXPECT_THROW(plot::metric_figure_data(t.one, nullptr, "speed"), InvalidData);
}

TEST(Occurrence, SharesPerIterationAndConditionSumToOne) {
  const fs::path p = temp_file("labels.csv", scores_csv());
  const auto labels = metrics::read_trial_labels(p.string());
  EXPECT_EQ(labels.size(), 2u * 12 * 6);
  const plot::Occurrence o = plot::strategy_occurrence(labels);
  EXPECT_EQ(o.conditions, (std::vector<std::string>{"A", "B"}));
  EXPECT_EQ(o.iterations, (std::vector<long long>{1, 2, 3, 4, 5, 6}));
  EXPECT_EQ(o.strategies, (std::vector<std::string>{"ambiguous", "optimal", "switching"}));
  std::size_t total = 0;
  for (std::size_t c = 0; c < 2; ++c) {
    for (std::size_t i = 0; i < 6; ++i) {
      double sum = 0;
      for (std::size_t s = 0; s < 3; ++s) {
        sum += o.share(c, i, s);
        total += o.counts[c][i][s];
      }
      EXPECT_NEAR(sum, 1.0, 1e-12);
    }
  }
  EXPECT_EQ(total, labels.size());
  // (p + it + c) % 3 over 12 participants: each strategy 4 times per iteration.
  EXPECT_EQ(o.counts[0][0][1], 4u);
  EXPECT_DOUBLE_EQ(o.share(1, 5, 2), 4.0 / 12.0);
  const plot::Figure f = plot::occurrence_figure(o);
  ASSERT_EQ(f.panels.size(), 2u);
  EXPECT_EQ(f.panels[1].bars->segments[5][2], o.share(1, 5, 2));
}

TEST(Occurrence, ScoresWithoutStrategyAreInvalidData) {
  const fs::path p = temp_file("nostrategy.csv", "participant,iteration,error\nP1,1,0.5\n");
  EXPECT_THROW(metrics::read_trial_labels(p.string()), InvalidData);
}

namespace {

tables::LikertAnalysis likert_analysis() {
  // 7-point items: q1 mostly agrees, q2 spread around neutral (4).
  std::string s = "participant,condition,q1,q2\n";
  const int q1[] = {6, 7, 5, 6, 6, 7, 5, 4, 6, 7};
  const int q2[] = {1, 2, 4, 4, 4, 5, 6, 7, 3, 4};
  for (int c = 0; c < 2; ++c) {
    for (int i = 0; i < 10; ++i) {
      s += "P" + std::to_string(c * 10 + i) + "," + (c == 0 ? "A" : "B") + "," +
           std::to_string(c == 0 ? q1[i] : q1[9 - i] - (i % 2)) + "," + std::to_string(q2[i]) +
           "\n";
    }
  }
  const fs::path p = temp_file("q.csv", s);
  tables::LikertSettings l;
  l.reference = 3.5;
  return tables::analyze_likert_file(p.string(), l);
}

}  // namespace

TEST(LikertFigures, MeansAreTheOneSampleTTestRows) {
  const tables::LikertAnalysis a = likert_analysis();
  const auto means = plot::likert_means_data(a).means;
  std::size_t rows = 0;
  for (const auto& row : a.rows) {
    if (row.result.test != "one_sample_t") continue;
    const auto it = std::find_if(means.begin(), means.end(), [&](const plot::LikertMean& m) {
      return m.name == row.metric && m.group == row.group1;
    });
    ASSERT_NE(it, means.end());
    EXPECT_EQ(it->mean, *row.result.mean1);
    EXPECT_EQ(it->conf_low, *row.result.conf_low);
    EXPECT_EQ(it->conf_high, *row.result.conf_high);
    EXPECT_EQ(it->differs, is_difference(row.label));
    ++rows;
  }
  EXPECT_EQ(rows, 4u);
  EXPECT_EQ(means.size(), 4u);
  const plot::Figure f = plot::likert_means_figure(a);
  EXPECT_EQ(f.panels[0].refs[0].value, 3.5);
  EXPECT_EQ(f.panels[0].lines[0].x[0], means[0].mean);
}

TEST(LikertFigures, DistributionIsCentredOnTheNeutralPoint) {
  const tables::LikertAnalysis a = likert_analysis();
  const auto bars = plot::likert_distribution_data(a).bars;
  ASSERT_EQ(bars.size(), 4u);
  for (const auto& b : bars) {
    double sum = 0;
    for (double v : b.percent) sum += v;
    EXPECT_NEAR(sum, 100.0, 1e-9);
  }
  // q2 in A: 1, 2, 3 below 4 (30%), four 4s (40%), 5, 6, 7 above: starts at -(30 + 40 / 2).
  const auto q2 = std::find_if(bars.begin(), bars.end(), [](const plot::LikertBar& b) {
    return b.name == "q2" && b.group == "A";
  });
  ASSERT_NE(q2, bars.end());
  EXPECT_DOUBLE_EQ(q2->start, -50.0);
  EXPECT_DOUBLE_EQ(q2->percent[3], 40.0);
  // The bars' summaries are the Likert table's counts.
  for (const auto& s : a.summaries) {
    if (s.name == "q2" && s.group == "A") {
      EXPECT_EQ(s.counts[3], 4u);
    }
  }
}

TEST(LikertFigures, TwoSampleAnalysisHasNoMeansFigure) {
  tables::LikertAnalysis a = likert_analysis();
  a.two_sample = true;
  EXPECT_THROW(plot::likert_means_data(a), InvalidData);
}

TEST(Participants, OneLinePerParticipantAndTheTablesMean) {
  const Tables t = build(stats::PAdjustMethod::none);
  const plot::Figure f = plot::participants_figure(t.scores, "error", &t.one);
  ASSERT_EQ(f.panels.size(), 2u);
  ASSERT_EQ(f.panels[0].lines.size(), 13u);  // 12 participants + the mean
  const auto d = plot::metric_figure_data(t.one, nullptr, "error");
  for (std::size_t i = 0; i < 6; ++i) {
    EXPECT_EQ(f.panels[1].lines.back().y[i], d.series[1].points[i].mean);
  }
}

TEST(Traces, MeanOfMirroredResampledTraces) {
  // Two trials of one strategy for P1 (iterations 1 and 3), one for P2. Target right (1): the
  // pad itself; target left (0): 1 - pad.
  const std::string logs =
      "participant,condition,iteration,strategy,variant,target,t,pad\n"
      "P1,A,1,s,main,right,0,0.5\nP1,A,1,s,main,right,1,0.7\nP1,A,1,s,main,right,2,0.9\n"
      "P1,A,2,o,main,left,0,0.5\nP1,A,2,o,main,left,4,0.1\n"
      "P1,A,3,s,main,right,0,0.5\nP1,A,3,s,main,right,3,0.5\n"
      "P2,A,1,s,main,left,0,0.5\nP2,A,1,s,main,left,1,0.3\nP2,A,1,s,main,left,2,0.1\n";
  const fs::path log = temp_file("log.csv", logs);
  const std::vector<plot::TrialLabel> labels = {{"P1", "A", 1, "s", "main"},
                                                {"P1", "A", 2, "o", "main"},
                                                {"P1", "A", 3, "s", "main"},
                                                {"P2", "A", 1, "s", "main"}};
  const auto curves = metrics::mean_traces({log.string()}, io::TraceOptions{}, labels);
  ASSERT_EQ(curves.size(), 3u);  // o first; s first; s later
  EXPECT_EQ(curves[0].strategy, "o");
  EXPECT_TRUE(curves[1].first_exposure);
  EXPECT_EQ(curves[1].strategy, "s");
  EXPECT_EQ(curves[1].trials, 2u);
  EXPECT_FALSE(curves[2].first_exposure);
  EXPECT_EQ(curves[2].trials, 1u);
  const std::size_t mid = (metrics::kTracePoints - 1) / 2, end = metrics::kTracePoints - 1;
  // First exposures: both move linearly to the true target (0.5 -> 0.9 mirrored).
  EXPECT_NEAR(curves[1].mean[0], 0.5, 1e-12);
  EXPECT_NEAR(curves[1].mean[mid], 0.7, 1e-12);
  EXPECT_NEAR(curves[1].mean[end], 0.9, 1e-12);
  // Identical traces: a zero-width interval.
  EXPECT_NEAR(curves[1].conf_low[mid], 0.7, 1e-12);
  EXPECT_NEAR(curves[1].conf_high[mid], 0.7, 1e-12);
  // The later exposure stayed in the middle; one trial has no interval.
  EXPECT_NEAR(curves[2].mean[mid], 0.5, 1e-12);
  EXPECT_TRUE(std::isnan(curves[2].conf_low[mid]));
  // Target left: pad 0.1 at the end is 0.9 towards the true target.
  EXPECT_NEAR(curves[0].mean[end], 0.9, 1e-12);
  const plot::Figure f = plot::traces_figure(curves);
  EXPECT_EQ(f.panels.size(), 2u);
  EXPECT_EQ(f.panels[1].lines.size(), 2u);
}
