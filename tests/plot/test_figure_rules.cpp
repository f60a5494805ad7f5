// Rules for figures: figure data equal what they are computed from, axes fitted to the
// data and the metric's range (never stretched by a far reference, which becomes an edge arrow),
// bands clipped, one colour code for conditions (distinct in greyscale by dash and marker), faint
// participants under the means, Likert answer labels, the exposure and model-fit figures, alt
// text, and every figure of the demo study rendered to PDF, SVG and PNG at both widths.
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>

#include "feint/error.hpp"
#include "feint/io/scores.hpp"
#include "feint/metrics/exposure_trend.hpp"
#include "feint/metrics/mean_trace.hpp"
#include "feint/metrics/score.hpp"
#include "feint/models/fitted_trend.hpp"
#include "feint/plot/figures.hpp"
#include "feint/tables/likert.hpp"
#include "feint/tables/model.hpp"
#include "feint/tables/table1.hpp"

using namespace feint;
namespace fs = std::filesystem;

namespace {

struct Folder {
  fs::path path = fs::temp_directory_path() / ("feint-figrules-" + std::to_string(::getpid()));
  Folder() { fs::create_directories(path); }
  ~Folder() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
};
const fs::path& folder() {
  static Folder f;
  return f.path;
}
fs::path write(const std::string& name, const std::string& content) {
  const fs::path p = folder() / name;
  std::ofstream(p, std::ios::binary) << content;
  return p;
}

// Two conditions x 10 participants x 8 iterations; confusion near 0.35 (far below its reference
// 0.95), error near 0.45 (near its reference 0.5), with values close to 0 and 1 so that the
// intervals reach beyond [0, 1].
std::string scores_csv() {
  std::string s = "participant,condition,iteration,strategy,variant,error,confusion\n";
  const char* strategies[] = {"ambiguous", "optimal"};
  for (int c = 0; c < 2; ++c) {
    for (int p = 0; p < 10; ++p) {
      for (int it = 1; it <= 8; ++it) {
        const double noise = ((p * 37 + it * 11 + c * 5) % 13) / 100.0 - 0.06;
        double e = 0.45 + noise;
        if (it == 8) e = (p % 5 == 0) ? 0.0 : 0.98;  // an interval beyond 1 at iteration 8
        const double conf = 0.35 + noise / 2 + (it == 1 ? 0.3 * (p % 2) : 0);
        s += fmt::format("P{},{},{},{},main,{},{}\n", c * 100 + p, c == 0 ? "adaptive" : "random",
                         it, strategies[(p + it) % 2], e, conf);
      }
    }
  }
  return s;
}

struct Study {
  io::ScoresTable scores;
  tables::Table1 one, two;
  std::vector<metrics::TrialLabel> labels;
};

const Study& study() {
  static const Study s = [] {
    Study st;
    const fs::path p = write("scores.csv", scores_csv());
    st.scores = io::load_scores(p.string());
    tables::Table1Options o;
    o.metrics = {tables::parse_metric_spec("error=0.5"),
                 tables::parse_metric_spec("confusion=0.95")};
    st.one = tables::build_table1(st.scores, o);
    o.compare = std::pair<std::string, std::string>{"adaptive", "random"};
    st.two = tables::build_table1(st.scores, o);
    st.labels = metrics::read_trial_labels(p.string());
    return st;
  }();
  return s;
}

double luminance(const plot::Colour& c) { return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b; }
bool same(const plot::Colour& a, const plot::Colour& b) {
  return a.r == b.r && a.g == b.g && a.b == b.b;
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// Axes and references

TEST(Axes, FarReferenceDoesNotStretchTheAxisAndBecomesAnEdgeArrow) {
  const auto d = plot::metric_figure_data(study().one, &study().two, "confusion");
  const plot::Figure f = plot::metric_figure(d);
  const auto axes = plot::axis_ranges(f);
  ASSERT_EQ(axes.size(), 1u);
  double hi = 0;
  for (const auto& s : d.series) {
    for (const auto& pt : s.points) hi = std::max(hi, std::min(1.0, pt.conf_high));
  }
  EXPECT_LT(axes[0].y.max, 0.95);  // 0.95 is far above the data
  EXPECT_GE(axes[0].y.max, hi);    // every (clipped) interval is inside the axis
  EXPECT_LE(axes[0].y.max, hi + 0.05 * (hi - axes[0].y.min) + 1e-12);
  ASSERT_EQ(axes[0].off_axis.size(), 1u);
  EXPECT_EQ(axes[0].off_axis[0].value, 0.95);
  for (double t : axes[0].y.ticks) EXPECT_LE(t, axes[0].y.max + 1e-12);
}

TEST(Axes, NearReferenceIsDrawnAsALine) {
  const plot::Figure f =
      plot::metric_figure(plot::metric_figure_data(study().one, nullptr, "error"));
  const auto axes = plot::axis_ranges(f);
  EXPECT_TRUE(axes[0].off_axis.empty());
  EXPECT_LE(axes[0].y.min, 0.5);
  EXPECT_GE(axes[0].y.max, 0.5);
}

TEST(Axes, ReferenceReachIsAQuarterOfTheDataSpan) {
  plot::Figure f;
  plot::Panel p;
  plot::Line l;
  l.x = {1, 2};
  l.y = {0.0, 1.0};
  p.lines.push_back(l);
  p.refs.push_back({1.24, false, "in"});
  p.refs.push_back({-0.26, false, "out"});
  f.panels.push_back(p);
  const auto a = plot::axis_ranges(f)[0];
  EXPECT_GE(a.y.max, 1.24);
  EXPECT_LT(a.y.min, 0.0);
  EXPECT_GT(a.y.min, -0.26);
  ASSERT_EQ(a.off_axis.size(), 1u);
  EXPECT_EQ(a.off_axis[0].label, "out");
}

// ---------------------------------------------------------------------------------------------
// Bands clipped to the metric's range

TEST(Bands, ClippedToTheMetricsRangeButTheDataKeepTheTablesInterval) {
  const auto d = plot::metric_figure_data(study().one, nullptr, "error");
  EXPECT_EQ(d.range.lo, 0.0);
  EXPECT_EQ(d.range.hi, 1.0);
  // Iteration 8's interval reaches beyond [0, 1] in the table; the data keep it.
  const auto& row = d.series[0].points.back();
  ASSERT_EQ(row.iteration, 8);
  ASSERT_TRUE(row.conf_low < 0 || row.conf_high > 1) << row.conf_low << " " << row.conf_high;
  const plot::Figure f = plot::metric_figure(d);
  for (const auto& l : f.panels[0].lines) {
    for (std::size_t i = 0; i < l.lo.size(); ++i) {
      EXPECT_GE(l.lo[i], 0.0);
      EXPECT_LE(l.hi[i], 1.0);
    }
  }
  EXPECT_EQ(f.panels[0].y.bound_min, 0.0);
  EXPECT_EQ(f.panels[0].y.bound_max, 1.0);
  const auto axes = plot::axis_ranges(f);
  EXPECT_GE(axes[0].y.min, 0.0);
  EXPECT_LE(axes[0].y.max, 1.0);
}

TEST(Bands, AnUnboundedMetricIsNotClipped) {
  const auto d =
      plot::metric_figure_data(study().one, nullptr, "error", plot::MetricRange{});  // unbounded
  const plot::Figure f = plot::metric_figure(d);
  const auto& last = d.series[0].points.back();
  EXPECT_EQ(f.panels[0].lines[0].lo.back(), last.conf_low);
  EXPECT_EQ(f.panels[0].lines[0].hi.back(), last.conf_high);
  EXPECT_FALSE(f.panels[0].y.bound_min.has_value());
  EXPECT_TRUE(std::isinf(plot::metric_range("raw_confusion").hi));
}

TEST(Bands, CanvasClipsIntervalsToTheAxisBounds) {
  plot::Figure f;
  plot::Panel p;
  plot::Line l;
  l.band = true;
  l.x = {1, 2, 3};
  l.y = {0.1, 0.5, 0.9};
  l.lo = {-0.4, 0.3, 0.6};
  l.hi = {0.5, 0.7, 1.6};
  p.lines.push_back(l);
  p.y.bound_min = 0;
  p.y.bound_max = 1;
  f.panels.push_back(p);
  const auto a = plot::axis_ranges(f)[0];
  EXPECT_EQ(a.y.min, 0.0);
  EXPECT_EQ(a.y.max, 1.0);
}

// ---------------------------------------------------------------------------------------------
// One colour code

TEST(Colours, ConditionsDifferInColourLightnessDashAndMarker) {
  const plot::Style a = plot::condition_style(0), b = plot::condition_style(1);
  EXPECT_NE(a.dash, b.dash);
  EXPECT_NE(a.marker, b.marker);
  EXPECT_GT(std::fabs(luminance(a.colour) - luminance(b.colour)), 0.2);  // greyscale
  for (std::size_t i = 0; i < 4; ++i) {
    for (std::size_t j = i + 1; j < 4; ++j) {
      EXPECT_NE(plot::condition_style(i).dash, plot::condition_style(j).dash);
      EXPECT_NE(plot::condition_style(i).marker, plot::condition_style(j).marker);
    }
  }
}

TEST(Colours, StrategyPaletteAvoidsTheConditionsColoursAndDiffersInGrey) {
  for (std::size_t s = 0; s < 6; ++s) {
    EXPECT_FALSE(same(plot::strategy_colour(s), plot::condition_style(0).colour)) << s;
    EXPECT_FALSE(same(plot::strategy_colour(s), plot::condition_style(1).colour)) << s;
  }
  for (std::size_t i = 0; i < 4; ++i) {
    for (std::size_t j = i + 1; j < 4; ++j) {
      EXPECT_GT(
          std::fabs(luminance(plot::strategy_colour(i)) - luminance(plot::strategy_colour(j))),
          0.08)
          << i << " " << j;
    }
  }
  const plot::Figure f = plot::occurrence_figure(plot::strategy_occurrence(study().labels));
  ASSERT_FALSE(f.legend.empty());
  EXPECT_EQ(f.legend[0].kind, plot::LegendEntry::Kind::text);
  EXPECT_EQ(f.legend[0].label, "Strategy:");
}

TEST(Colours, AConditionHasTheSameStyleInEveryFigure) {
  const auto& st = study();
  const plot::Figure metric =
      plot::metric_figure(plot::metric_figure_data(st.one, nullptr, "error"));
  const plot::Figure people = plot::participants_figure(st.scores, "error", &st.one);
  const auto trend = metrics::exposure_trend(st.scores, st.labels, "error");
  const plot::Figure exposure = plot::exposure_figure(trend);
  // metric: one line per condition in the table's order (adaptive, random).
  for (std::size_t c = 0; c < 2; ++c) {
    const plot::Style want = plot::condition_style(c);
    EXPECT_TRUE(same(metric.panels[0].lines[c].style.colour, want.colour));
    EXPECT_EQ(metric.panels[0].lines[c].style.dash, want.dash);
    // participants: panel c's mean line (last) and its faint lines.
    EXPECT_TRUE(same(people.panels[c].lines.back().style.colour, want.colour));
    EXPECT_TRUE(same(people.panels[c].lines.front().style.colour, want.colour));
    // exposure: the fit and the means of condition c in each strategy panel.
    for (const auto& p : exposure.panels) {
      std::size_t found = 0;
      for (const auto& l : p.lines) found += same(l.style.colour, want.colour) ? 1 : 0;
      EXPECT_GE(found, 1u);
    }
  }
  // Order does not matter: the style follows the sorted names.
  EXPECT_TRUE(same(plot::style_of_condition({"random", "adaptive"}, "random").colour,
                   plot::condition_style(1).colour));
}

// ---------------------------------------------------------------------------------------------
// Participants: faint lines under the means

TEST(Participants, FaintLinesUnderTheMeansWithTheirBand) {
  const auto& st = study();
  const auto d = plot::participants_data(st.scores, "error", &st.one);
  ASSERT_EQ(d.panels.size(), 2u);
  EXPECT_EQ(d.panels[0].participants.size(), 10u);
  // The data are the scores' values and the table's means.
  const auto m = plot::metric_figure_data(st.one, nullptr, "error");
  for (std::size_t i = 0; i < m.series[1].points.size(); ++i) {
    EXPECT_EQ(d.panels[1].means[i].mean, m.series[1].points[i].mean);
  }
  EXPECT_EQ(d.panels[0].participants[0].values[0], *st.scores.records[0].values[0]);
  const plot::Figure f = plot::participants_figure(d);
  const auto& lines = f.panels[0].lines;
  ASSERT_EQ(lines.size(), 11u);
  for (std::size_t i = 0; i + 1 < lines.size(); ++i) {
    EXPECT_LE(lines[i].opacity, 0.4);
    EXPECT_FALSE(lines[i].band);
  }
  EXPECT_EQ(lines.back().opacity, 1.0);
  EXPECT_TRUE(lines.back().band);
  EXPECT_TRUE(lines.back().halo);
  EXPECT_GT(lines.back().line_width, 3 * lines.front().line_width);
}

// ---------------------------------------------------------------------------------------------
// Exposure

TEST(ExposureTrend, MeansAndTheFittedLineAreRsLmWithClusteredErrors) {
  // One strategy s in one condition: P1 sees it at iterations 1-3 (exposures 1, 2, 3), P2 at 1-2
  // (then o), P3 at 1-4.
  const fs::path p = write("exposure.csv",
                           "participant,condition,iteration,strategy,error,confusion\n"
                           "P1,A,1,s,0.1,0.5\nP1,A,2,s,0.3,0.5\nP1,A,3,s,0.2,0.5\n"
                           "P2,A,1,s,0.2,0.5\nP2,A,2,s,0.4,0.5\nP2,A,3,o,0.9,0.5\n"
                           "P3,A,1,s,0.5,0.5\nP3,A,2,s,0.45,0.5\nP3,A,3,s,0.3,0.5\n"
                           "P3,A,4,s,0.35,0.5\n");
  const io::ScoresTable scores = io::load_scores(p.string());
  const auto labels = metrics::read_trial_labels(p.string());
  const auto t = metrics::exposure_trend(scores, labels, "error");
  ASSERT_EQ(t.strategies.size(), 2u);
  EXPECT_EQ(t.strategies[0].strategy, "o");
  const auto& s = t.strategies[1].series[0];
  ASSERT_EQ(s.points.size(), 4u);
  EXPECT_EQ(s.points[0].exposure, 1);
  EXPECT_EQ(s.points[0].n, 3u);
  EXPECT_NEAR(s.points[0].mean, (0.1 + 0.2 + 0.5) / 3, 1e-12);
  EXPECT_NEAR(s.points[1].mean, (0.3 + 0.4 + 0.45) / 3, 1e-12);
  EXPECT_EQ(s.points[3].n, 1u);
  EXPECT_TRUE(std::isnan(s.points[3].conf_low));
  // R: lm(y ~ x) with the CR1 cluster-robust covariance (tests/golden/plot/exposure_ols.R).
  ASSERT_TRUE(s.fit.fitted);
  EXPECT_EQ(s.fit.participants, 3u);
  EXPECT_NEAR(s.fit.intercept, 0.29, 1e-12);
  EXPECT_NEAR(s.fit.slope, 0.01, 1e-12);
  EXPECT_NEAR(s.fit.slope_low, -0.15918373035071859, 1e-9);
  EXPECT_NEAR(s.fit.slope_high, 0.17918373035071861, 1e-9);
  const double low[] = {-0.1726977172233140068, -0.0036296768098073029, 0.1452708218004628016,
                        0.1887793694833634350};
  const double high[] = {0.77269771722331404, 0.62362967680980730, 0.49472917819953721,
                         0.47122063051663660};
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_NEAR(s.fit.fit[i], 0.3 + 0.01 * static_cast<double>(i), 1e-12);
    EXPECT_NEAR(s.fit.low[i], low[i], 1e-9);
    EXPECT_NEAR(s.fit.high[i], high[i], 1e-9);
  }
  // The single trial of "o" cannot be fitted.
  EXPECT_FALSE(t.strategies[0].series[0].fit.fitted);
  // The figure clips the band at 0 (error's range); the means of fewer than min_trials trials
  // are not drawn.
  const plot::Figure f = plot::exposure_figure(t, plot::metric_range("error"), 2);
  ASSERT_EQ(f.panels.size(), 2u);
  const auto& band = f.panels[1].lines[0];
  ASSERT_TRUE(band.band);
  EXPECT_EQ(band.lo[0], 0.0);
  EXPECT_EQ(band.lo[1], 0.0);
  EXPECT_NEAR(band.lo[2], low[2], 1e-9);
  EXPECT_EQ(f.panels[1].lines[1].x.size(), 3u);  // exposure 4 has one trial
  EXPECT_THROW(metrics::exposure_trend(scores, labels, "speed"), InvalidData);
}

// ---------------------------------------------------------------------------------------------
// Model fit

TEST(ModelFit, FittedCellMeansOfABalancedFactorModelAreTheObservedMeans) {
  const auto& st = study();
  tables::ModelOptions o;
  o.metrics = {"error"};
  const auto analysis = tables::build_model_analysis(st.scores, o);
  const auto& fit = analysis.models[0].fit;
  const auto trend = models::fitted_trend(fit, 0.95);
  ASSERT_EQ(trend.size(), 2u);
  const auto means = plot::metric_figure_data(st.one, nullptr, "error");
  for (std::size_t g = 0; g < 2; ++g) {
    ASSERT_EQ(trend[g].group, means.series[g].condition);
    ASSERT_EQ(trend[g].points.size(), 8u);
    for (std::size_t i = 0; i < 8; ++i) {
      // Complete balanced data, iteration as a factor: the fixed-effect cell means are the cell
      // means of the data.
      EXPECT_NEAR(trend[g].points[i].fit, means.series[g].points[i].mean, 1e-9);
      EXPECT_LT(trend[g].points[i].low, trend[g].points[i].fit);
      EXPECT_GT(trend[g].points[i].high, trend[g].points[i].fit);
      const auto c = models::contrast(fit, fit.cell_row(g, trend[g].points[i].time), 0.95);
      EXPECT_EQ(trend[g].points[i].low, *c.test.conf_low);
    }
  }
  plot::ModelFitFigureData d{means, trend, "iteration as a factor"};
  const plot::Figure f = plot::model_fit_figure(d);
  ASSERT_EQ(f.panels.size(), 1u);
  ASSERT_EQ(f.panels[0].lines.size(), 4u);  // 2 fits (bands), 2 sets of means
  EXPECT_TRUE(f.panels[0].lines[0].band);
  for (double v : f.panels[0].lines[0].lo) EXPECT_GE(v, 0.0);
  const std::string alt = plot::alt_text(d);
  EXPECT_TRUE(contains(alt, "error"));
  EXPECT_TRUE(contains(alt, "adaptive"));
  EXPECT_TRUE(contains(alt, "random"));
}

// ---------------------------------------------------------------------------------------------
// Likert answer labels

TEST(LikertLabels, BuiltInAgreeLabelsOrTheQuestionnairesMap) {
  std::string q = "participant,condition,q1,q2\n";
  for (int i = 0; i < 10; ++i) {
    q += fmt::format("P{},{},{},{}\n", i, i % 2 ? "B" : "A", 1 + i % 7, 7 - i % 7);
  }
  const fs::path p = write("q.csv", q);
  tables::LikertSettings l;
  const auto d = plot::likert_distribution_data(tables::analyze_likert_file(p.string(), l));
  ASSERT_EQ(d.answer_labels.size(), 7u);
  EXPECT_EQ(d.answer_labels.front(), "Strongly disagree");
  EXPECT_EQ(d.answer_labels[3], "Neither agree nor disagree");
  EXPECT_EQ(d.answer_labels.back(), "Strongly agree");
  const plot::Figure f = plot::likert_distribution_figure(d);
  EXPECT_EQ(f.legend.front().label, "1 Strongly disagree");
  l.load.labels =
      io::parse_label_map("Never=1,Rarely=2,Sometimes=3,Often=4,Mostly=5,Usually=6,Always=7");
  const auto u = plot::likert_distribution_data(tables::analyze_likert_file(p.string(), l));
  EXPECT_EQ(u.answer_labels.front(), "Never");
  EXPECT_EQ(u.answer_labels.back(), "Always");
  l.load.labels.clear();
  l.load.scale_min = 0;
  l.load.scale_max = 10;
  const auto n = plot::likert_distribution_data(tables::analyze_likert_file(p.string(), l));
  EXPECT_EQ(n.answer_labels.front(), "0");  // no built-in labels for 11 points
  EXPECT_EQ(n.answer_labels.size(), 11u);
}

// ---------------------------------------------------------------------------------------------
// Alt text

TEST(AltText, NamesTheMetricAndTheConditions) {
  const auto& st = study();
  const auto m = plot::metric_figure_data(st.one, &st.two, "confusion");
  for (const std::string& alt :
       {plot::alt_text(m), plot::alt_text(plot::participants_data(st.scores, "confusion", &st.one)),
        plot::alt_text(metrics::exposure_trend(st.scores, st.labels, "confusion"))}) {
    EXPECT_TRUE(contains(alt, "confusion")) << alt;
    EXPECT_TRUE(contains(alt, "adaptive")) << alt;
    EXPECT_TRUE(contains(alt, "random")) << alt;
    EXPECT_LT(alt.size(), 700u) << alt;
  }
  const std::string occ = plot::alt_text(plot::strategy_occurrence(st.labels));
  EXPECT_TRUE(contains(occ, "adaptive") && contains(occ, "random") && contains(occ, "optimal"))
      << occ;
  // The metric's numbers: adaptive's mean over the iterations.
  double sum = 0;
  for (const auto& pt : m.series[0].points) sum += pt.mean;
  EXPECT_TRUE(contains(plot::alt_text(m), fmt::format("Adaptive averages {:.2f}", sum / 8)))
      << plot::alt_text(m);
}

// ---------------------------------------------------------------------------------------------
// The demo study: every figure in every format at both widths

namespace {

bool have_xmllint() { return std::system("xmllint --version >/dev/null 2>&1") == 0; }

struct Demo {
  std::vector<std::pair<std::string, plot::Figure>> figures;
  std::vector<std::pair<std::string, std::string>> alt;
};

Demo demo_figures() {
  // FEINT_DEMO_DIR=DIR: another study folder with logs/ and questionnaire.csv (default the
  // repository's data/demo).
  const char* demo = std::getenv("FEINT_DEMO_DIR");
  const std::string dir = demo != nullptr ? demo : std::string(FEINT_SOURCE_DIR) + "/data/demo";
  const std::string logs = dir + "/logs";
  const std::vector<std::string> log_files = io::expand_inputs({logs});
  const fs::path scores_path = folder() / "demo-scores.csv";
  metrics::ScoreSettings ss;
  ss.on_warning = [](const std::string&) {};
  metrics::score_to_file({logs}, ss, scores_path.string());
  Demo d;
  const io::ScoresTable scores = io::load_scores(scores_path.string());
  const auto labels = metrics::read_trial_labels(scores_path.string());
  tables::Table1Options o;
  o.metrics = {tables::parse_metric_spec("error=0.5"), tables::parse_metric_spec("confusion=0.95")};
  const tables::Table1 one = tables::build_table1(scores, o);
  o.compare = std::pair<std::string, std::string>{"adaptive", "random"};
  const tables::Table1 two = tables::build_table1(scores, o);
  tables::ModelOptions mo;
  mo.metrics = {"error", "confusion"};
  mo.trend = true;
  const auto models = tables::build_model_analysis(scores, mo);
  for (const std::string metric : {"error", "confusion"}) {
    const auto m = plot::metric_figure_data(one, &two, metric);
    d.figures.emplace_back(metric, plot::metric_figure(m));
    d.alt.emplace_back(metric, plot::alt_text(m));
    const auto p = plot::participants_data(scores, metric, &one);
    d.figures.emplace_back("participants-" + metric, plot::participants_figure(p));
    d.alt.emplace_back("participants-" + metric, plot::alt_text(p));
    const auto e = metrics::exposure_trend(scores, labels, metric);
    d.figures.emplace_back("exposure-" + metric, plot::exposure_figure(e));
    d.alt.emplace_back("exposure-" + metric, plot::alt_text(e));
    for (const auto& mm : models.models) {
      if (mm.metric != metric) continue;
      plot::ModelFitFigureData fd{m, models::fitted_trend(mm.fit, 0.95), "linear trend"};
      d.figures.emplace_back("model-" + metric, plot::model_fit_figure(fd));
      d.alt.emplace_back("model-" + metric, plot::alt_text(fd));
    }
  }
  const auto occ = plot::strategy_occurrence(labels);
  d.figures.emplace_back("strategies", plot::occurrence_figure(occ));
  d.alt.emplace_back("strategies", plot::alt_text(occ));
  plot::TracesFigureData traces{metrics::mean_traces(log_files, io::TraceOptions{}, labels), 0.95};
  d.figures.emplace_back("traces", plot::traces_figure(traces.curves, traces.conf_level));
  d.alt.emplace_back("traces", plot::alt_text(traces));
  tables::LikertSettings ls;
  ls.reference = 3.5;
  const auto likert = tables::analyze_likert_file(dir + "/questionnaire.csv", ls);
  const auto dist = plot::likert_distribution_data(likert);
  d.figures.emplace_back("likert", plot::likert_distribution_figure(dist));
  d.alt.emplace_back("likert", plot::alt_text(dist));
  const auto means = plot::likert_means_data(likert);
  d.figures.emplace_back("likert-means", plot::likert_means_figure(means));
  d.alt.emplace_back("likert-means", plot::alt_text(means));
  return d;
}

// The demo's figures, made once for the tests below.
const Demo& demo() {
  static const Demo d = demo_figures();
  return d;
}

}  // namespace

TEST(DemoFigures, EveryFigureRendersInThreeFormatsAtBothWidths) {
  const Demo& d = demo();
  ASSERT_EQ(d.figures.size(), 12u);
  // FEINT_FIGURES_OUT=DIR keeps the files (docs/figures/*.png are made this way).
  const char* keep = std::getenv("FEINT_FIGURES_OUT");
  for (const auto& [name, figure] : d.figures) {
    for (const auto width : {plot::Width::one_column, plot::Width::two_column}) {
      for (const auto format :
           {plot::FileFormat::pdf, plot::FileFormat::svg, plot::FileFormat::png}) {
        const std::string bytes = plot::render(figure, width, format);
        const std::string file = fmt::format(
            "{}-{}col.{}", name, width == plot::Width::one_column ? 1 : 2, plot::extension(format));
        ASSERT_GT(bytes.size(), 500u) << file;
        if (format == plot::FileFormat::pdf) {
          EXPECT_EQ(bytes.substr(0, 5), "%PDF-") << file;
        }
        if (format == plot::FileFormat::png) {
          EXPECT_EQ(bytes.substr(1, 3), "PNG") << file;
        }
        if (format == plot::FileFormat::svg) {
          EXPECT_NE(bytes.find("<svg"), std::string::npos) << file;  // parsed as XML below
        }
        if (keep != nullptr) {
          std::ofstream(fs::path(keep) / file, std::ios::binary) << bytes;
        }
      }
    }
  }
  for (const auto& [name, alt] : d.alt) {
    EXPECT_FALSE(alt.empty()) << name;
    if (name.find("likert") == std::string::npos && name != "strategies" && name != "traces") {
      EXPECT_TRUE(contains(alt, "adaptive") && contains(alt, "random")) << name << ": " << alt;
    }
    if (keep != nullptr) std::ofstream(fs::path(keep) / (name + ".alt.txt")) << alt << "\n";
  }
}

// Every SVG of the demo parses as XML (xmllint). Without xmllint the test is skipped, visibly.
TEST(DemoFigures, EverySvgIsWellFormedXml) {
  if (!have_xmllint()) GTEST_SKIP() << "xmllint not installed (Debian: libxml2-utils): the SVGs were not parsed";
  const Demo& d = demo();
  ASSERT_EQ(d.figures.size(), 12u);
  for (const auto& [name, figure] : d.figures) {
    for (const auto width : {plot::Width::one_column, plot::Width::two_column}) {
      const std::string file = fmt::format("{}-{}col.svg", name, width == plot::Width::one_column ? 1 : 2);
      const fs::path svg = write(file, plot::render(figure, width, plot::FileFormat::svg));
      EXPECT_EQ(std::system(("xmllint --noout '" + svg.string() + "' 2>/dev/null").c_str()), 0) << file;
    }
  }
}

// ---------------------------------------------------------------------------------------------
// Mean traces from loaded trials (metrics, upstream of plot)

TEST(MeanTraces, LoadedTrialsGiveTheSameCurvesAsTheStreamedLogs) {
  const fs::path log = write("traces.csv",
                             "participant,condition,iteration,strategy,variant,target,t,pad\n"
                             "P1,A,1,s,main,right,0,0.5\nP1,A,1,s,main,right,1,0.7\n"
                             "P1,A,2,s,main,left,0,0.5\nP1,A,2,s,main,left,2,0.2\n"
                             "P2,A,1,s,main,left,0,0.5\nP2,A,1,s,main,left,1,0.4\n"
                             "P3,A,1,s,main,right,0,0.5\nP3,A,1,s,main,right,1,0.9\n");
  const std::vector<metrics::TrialLabel> labels = {
      {"P1", "A", 1, "s", "main"}, {"P1", "A", 2, "s", "main"}, {"P2", "A", 1, "s", "main"}};
  std::vector<io::Trial> trials;
  io::TraceReader reader({log.string()}, io::TraceOptions{});
  io::Trial t;
  while (reader.next(t)) trials.push_back(t);
  ASSERT_EQ(trials.size(), 4u);
  metrics::MeanTraceAccumulator acc(labels);
  EXPECT_TRUE(acc.add(trials[0]));
  EXPECT_FALSE(acc.add(trials[3]));  // P3 is not in the scores: skipped
  const auto loaded = metrics::mean_traces(trials, labels);
  const auto streamed = metrics::mean_traces({log.string()}, io::TraceOptions{}, labels);
  ASSERT_EQ(loaded.size(), 2u);  // first (P1 it 1, P2), later (P1 it 2)
  ASSERT_EQ(streamed.size(), loaded.size());
  for (std::size_t c = 0; c < loaded.size(); ++c) {
    EXPECT_EQ(loaded[c].trials, streamed[c].trials);
    EXPECT_EQ(loaded[c].mean, streamed[c].mean);
  }
  EXPECT_TRUE(loaded[0].first_exposure);
  EXPECT_EQ(loaded[0].trials, 2u);
  // At the end: P1 0.7 (right), P2 1 - 0.4 = 0.6 (left): mean 0.65.
  EXPECT_NEAR(loaded[0].mean.back(), 0.65, 1e-12);
  // Later exposure: P1 at iteration 2, target left, pad 0.2: 0.8.
  EXPECT_NEAR(loaded[1].mean.back(), 0.8, 1e-12);
  // The figure clips the band at [0, 1]; the alt text says first against later.
  const plot::Figure f = plot::traces_figure(loaded);
  EXPECT_EQ(f.panels[0].y.bound_max, 1.0);
  const std::string alt = plot::alt_text(plot::TracesFigureData{loaded, 0.95});
  EXPECT_TRUE(contains(alt, "s/main")) << alt;
  EXPECT_TRUE(contains(alt, "first exposures average 0.65 and the later ones 0.80")) << alt;
}

// ---------------------------------------------------------------------------------------------
// Edge cases: no data, one condition

TEST(EdgeCases, EmptyDataRenderAndHaveAltText) {
  const metrics::ExposureTrend none{"error", 0.95, {}, {}, 0};
  const plot::ModelFitFigureData no_fit{plot::MetricFigureData{}, {}, ""};
  const plot::TracesFigureData no_traces{};
  for (const plot::Figure& f :
       {plot::exposure_figure(none), plot::model_fit_figure(no_fit),
        plot::traces_figure(no_traces.curves), plot::metric_figure(plot::MetricFigureData{})}) {
    for (const auto format :
         {plot::FileFormat::pdf, plot::FileFormat::svg, plot::FileFormat::png}) {
      EXPECT_FALSE(plot::render(f, plot::Width::one_column, format).empty());
    }
  }
  EXPECT_FALSE(plot::alt_text(none).empty());
  EXPECT_EQ(plot::alt_text(plot::MetricFigureData{}), "Line chart of the mean : no data.");
  EXPECT_FALSE(plot::alt_text(no_fit).empty());
  EXPECT_FALSE(plot::alt_text(no_traces).empty());
}

TEST(EdgeCases, OneConditionIsAllParticipantsInTheFirstStyle) {
  const fs::path p = write("onecond.csv",
                           "participant,iteration,strategy,error,confusion\n"
                           "P1,1,s,0.2,0.3\nP1,2,s,0.3,0.3\nP2,1,s,0.4,0.5\nP2,2,s,0.6,0.4\n"
                           "P3,1,s,0.5,0.2\nP3,2,s,0.5,0.6\n");
  const io::ScoresTable scores = io::load_scores(p.string());
  const tables::Table1 one = tables::build_table1(scores, tables::Table1Options{});
  const auto d = plot::metric_figure_data(one, nullptr, "error");
  const plot::Figure f = plot::metric_figure(d);
  EXPECT_EQ(f.panels[0].lines[0].label, "all participants");
  EXPECT_TRUE(same(f.panels[0].lines[0].style.colour, plot::condition_style(0).colour));
  EXPECT_TRUE(contains(plot::alt_text(d), "all participants")) << plot::alt_text(d);
  const auto e =
      metrics::exposure_trend(scores, metrics::read_trial_labels(p.string()), "confusion");
  ASSERT_EQ(e.strategies.size(), 1u);
  EXPECT_EQ(e.strategies[0].series[0].points.size(), 2u);
  EXPECT_TRUE(e.strategies[0].series[0].fit.fitted);
  EXPECT_TRUE(contains(plot::alt_text(e), "all participants")) << plot::alt_text(e);
}

// ---------------------------------------------------------------------------------------------
// Figures take data, never files: no reader in the plot module's sources.

TEST(Architecture, PlotReadsNoFile) {
  const fs::path root = FEINT_SOURCE_DIR;
  const char* forbidden[] = {"feint/io/trace.hpp",  "feint/io/csv.hpp", "TraceReader",
                             "CsvReader",           "expand_inputs",    "load_scores(",
                             "analyze_likert_file", "std::ifstream",    "read_trial_labels("};
  std::size_t files = 0;
  for (const fs::path& dir : {root / "src/plot", root / "include/feint/plot"}) {
    for (const auto& entry : fs::directory_iterator(dir)) {
      std::ifstream in(entry.path());
      const std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
      ++files;
      for (const char* word : forbidden) {
        EXPECT_EQ(text.find(word), std::string::npos) << entry.path() << " uses " << word;
      }
    }
  }
  EXPECT_GE(files, 4u);
}
