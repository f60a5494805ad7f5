// Pointer-trace measures (docs/pointer-measures.md) against mousetrap 3.2.3.9000's own R code
// (tests/golden/pointer/mousetrap_golden.R): 54 KH2017 trials and 9 synthetic traces, every
// measure, the threshold variants and the time-normalised traces; a worked example by hand; and
// every rejection path.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "accuracy.hpp"
#include "feint/error.hpp"
#include "feint/metrics/pointer_measures.hpp"

namespace {

using namespace feint::metrics;

const std::string kDir = std::string(FEINT_SOURCE_DIR) + "/tests/golden/pointer/";

// Goldens: |got - want| <= 1e-9 max(1, |want|), i.e. 1e-9 absolute up to 1, relative above
// (AUC reaches 1e6 px^2, times 2e4 ms). Counts (flips, reversals, hovers) must be equal.
constexpr double kGolden = 1e-9;
// The worked example: exact values, so only rounding separates them.
constexpr double kExact = 1e-12;

struct Table {
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;
};

// A CSV without quoting; lines starting with '#' are the version stamp.
Table read_table(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot open " + path);
  Table t;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::vector<std::string> cells;
    std::stringstream ss(line);
    std::string cell;
    while (std::getline(ss, cell, ',')) cells.push_back(cell);
    if (t.header.empty()) {
      t.header = cells;
    } else {
      t.rows.push_back(cells);
    }
  }
  return t;
}

double number(const std::string& s) {
  return s == "NA" ? std::numeric_limits<double>::quiet_NaN() : std::stod(s);
}

std::size_t column(const Table& t, const std::string& name) {
  for (std::size_t j = 0; j < t.header.size(); ++j) {
    if (t.header[j] == name) return j;
  }
  throw std::runtime_error("no column " + name);
}

// mt_id -> samples, from the extract and the synthetic traces.
std::map<std::string, std::vector<PointerSample>> read_traces() {
  std::map<std::string, std::vector<PointerSample>> traces;
  for (const char* file : {"kh2017_extract.csv", "synthetic_traces.csv"}) {
    const Table t = read_table(kDir + file);
    const std::size_t id = column(t, "mt_id"), ct = column(t, "t"), cx = column(t, "x"),
                      cy = column(t, "y");
    for (const auto& r : t.rows)
      traces[r[id]].push_back({number(r[ct]), number(r[cx]), number(r[cy])});
  }
  return traces;
}

// The KH2017 pipeline: remap so that the trace ends up-left, start at (0, 0).
std::vector<PointerSample> preprocess(const std::vector<PointerSample>& raw) {
  return align_start(remap_symmetric(raw));
}

void expect_golden(double got, double want, const std::string& what) {
  feint::test::record("mousetrap mt_measures (KH2017 + synthetic)", got, want, what);
  EXPECT_LE(std::fabs(got - want), kGolden * std::max(1.0, std::fabs(want)))
      << what << ": got " << got << ", mousetrap " << want;
}

// Golden cells left NA on purpose (mousetrap_golden.R: the deviation measures of two degenerate
// normalised traces, which only rounding decides); counted so that no other NA slips through.
int g_na_cells = 0;

// Compares every column of `m` whose golden name (prefix + name + suffix) is in the table; returns
// the golden columns it compared. Counts are compared exactly.
std::set<std::string> compare(const Table& t, const std::vector<std::string>& row,
                              const PointerMeasures& m, const std::string& prefix,
                              const std::string& suffix, const std::set<std::string>& only = {}) {
  static const std::set<std::string> counts = {"xpos_flips", "ypos_flips", "xpos_reversals",
                                               "ypos_reversals", "hovers"};
  std::set<std::string> done;
  for (const auto& [name, value] : mousetrap_columns(m)) {
    const std::string n(name);
    if (!only.empty() && !only.count(n)) continue;
    const std::string golden = prefix + n + suffix;
    std::size_t j = t.header.size();
    for (std::size_t k = 0; k < t.header.size(); ++k) {
      if (t.header[k] == golden) j = k;
    }
    if (j == t.header.size()) continue;
    const std::string what = row[0] + " " + golden;
    done.insert(golden);
    if (row[j] == "NA") {
      ++g_na_cells;
      continue;
    }
    if (counts.count(n)) {
      EXPECT_EQ(value, number(row[j])) << what;
    } else {
      expect_golden(value, number(row[j]), what);
    }
  }
  return done;
}

TEST(PointerMeasuresGolden, EveryTrialEveryMeasureAgreesWithMousetrap) {
  const auto traces = read_traces();
  const Table t = read_table(kDir + "kh2017_measures.csv");
  ASSERT_EQ(t.rows.size(), 63u);  // 54 KH2017 trials + 9 synthetic traces
  std::set<std::string> expected(t.header.begin() + 3, t.header.end());
  std::size_t kh_trials = 0;
  for (const auto& row : t.rows) {
    ASSERT_TRUE(traces.count(row[0])) << row[0];
    kh_trials += row[1] != "synthetic" ? 1 : 0;
    const std::vector<PointerSample> p = preprocess(traces.at(row[0]));
    std::set<std::string> done = compare(t, row, pointer_measures(p), "", "");
    auto add = [&](const std::set<std::string>& s) { done.insert(s.begin(), s.end()); };
    PointerMeasureSettings flip;
    flip.flip_threshold = 20;
    add(compare(t, row, pointer_measures(p, flip), "", "_flip20", {"xpos_flips", "ypos_flips"}));
    PointerMeasureSettings init;
    init.initiation_threshold = 10;
    add(compare(t, row, pointer_measures(p, init), "", "_init10", {"initiation_time"}));
    PointerMeasureSettings hover;
    hover.hover_threshold = 100;
    add(compare(t, row, pointer_measures(p, hover), "", "_hover100", {"hover_time", "hovers"}));
    hover.hover_incl_initial = false;
    add(compare(t, row, pointer_measures(p, hover), "", "_hover100_noinitial",
                {"hover_time", "hovers"}));
    add(compare(t, row, pointer_measures(time_normalize(p)), "tn_", ""));
    EXPECT_EQ(done, expected) << row[0] << ": a golden column was not compared";
  }
  EXPECT_EQ(kh_trials, 54u);
  EXPECT_EQ(g_na_cells, 14);  // 7 deviation measures of tn two_samples and tn vertical_tie
}

TEST(PointerMeasuresGolden, TimeNormalisationAgreesWithMousetrap) {
  const auto traces = read_traces();
  const Table t = read_table(kDir + "kh2017_time_normalized.csv");
  ASSERT_EQ(t.rows.size(), 19u * 101u);  // 10 KH2017 trials + 9 synthetic, 101 steps each
  std::map<std::string, std::vector<PointerSample>> normalised;
  auto check = [](double got, const std::string& cell, const std::string& what) {
    const double want = number(cell);
    feint::test::record("mousetrap mt_time_normalize", got, want, what);
    EXPECT_LE(std::fabs(got - want), kGolden * std::max(1.0, std::fabs(want))) << what;
  };
  for (const auto& row : t.rows) {
    auto it = normalised.find(row[0]);
    if (it == normalised.end()) {
      it = normalised.emplace(row[0], time_normalize(preprocess(traces.at(row[0])))).first;
    }
    ASSERT_EQ(it->second.size(), 101u);
    const PointerSample& s = it->second.at(std::stoul(row[1]) - 1);
    const std::string what = row[0] + " step " + row[1];
    check(s.t, row[2], what + " t");
    check(s.x, row[3], what + " x");
    check(s.y, row[4], what + " y");
  }
  EXPECT_EQ(normalised.size(), 19u);
}

// The worked example of docs/pointer-measures.md, already remapped and aligned (it starts at
// (0, 0) and ends up-left at (-4, 4)): direct path y = -x, deviation (x + y)/sqrt(2).
const std::vector<PointerSample> kExample = {{0, 0, 0},  {10, 0, 0},  {30, 2, 2},
                                             {45, 1, 1}, {55, -1, 3}, {60, -4, 4}};

TEST(PointerMeasuresWorkedExample, ByHand) {
  const double r2 = std::sqrt(2.0), r10 = std::sqrt(10.0);
  PointerMeasureSettings s;
  s.hover_threshold = 5;
  const PointerMeasures m = pointer_measures(kExample, s);
  EXPECT_EQ(m.xpos_max, 2);
  EXPECT_EQ(m.xpos_min, -4);
  EXPECT_EQ(m.ypos_max, 4);
  EXPECT_EQ(m.ypos_min, 0);
  EXPECT_NEAR(m.mad, 2 * r2, kExact);  // (2 + 2)/sqrt(2) at (2, 2)
  EXPECT_EQ(m.mad_time, 30);
  EXPECT_NEAR(m.md_above, 2 * r2, kExact);
  EXPECT_EQ(m.md_above_time, 30);
  EXPECT_EQ(m.md_below, 0);  // never below the path; the first 0 is the start
  EXPECT_EQ(m.md_below_time, 0);
  EXPECT_NEAR(m.ad, 2 * r2 / 3, kExact);  // (0 + 0 + 2 sqrt2 + sqrt2 + sqrt2 + 0) / 6
  EXPECT_NEAR(m.auc, 6, kExact);          // shoelace: (0 + 0 + 0 + 4 + 8 + 0) / 2
  EXPECT_EQ(m.xpos_flips, 1);             // x steps 0, +2, -1, -2, -3: runs +2 | -6
  EXPECT_EQ(m.ypos_flips, 2);             // y steps 0, +2, -1, +2, +1: runs +2 | -1 | +3
  EXPECT_EQ(m.xpos_reversals, 1);         // x != 0: 2, 1, -1, -4
  EXPECT_EQ(m.ypos_reversals, 0);
  EXPECT_EQ(m.rt, 60);
  EXPECT_EQ(m.initiation_time, 10);  // the sample before the first one away from the start
  EXPECT_EQ(m.idle_time, 10);        // one still segment, 0 -> 10
  EXPECT_EQ(*m.hover_time, 10);      // that segment, 10 > 5
  EXPECT_EQ(*m.hovers, 1);
  EXPECT_NEAR(m.total_dist, 5 * r2 + r10, kExact);  // 0 + 2 sqrt2 + sqrt2 + 2 sqrt2 + sqrt10
  EXPECT_NEAR(m.vel_max, r10 / 5, kExact);          // last segment, sqrt10 / 5 ms
  EXPECT_EQ(m.vel_max_time, 55);                    // that segment's start
  EXPECT_EQ(m.vel_min, 0);
  EXPECT_EQ(m.vel_min_time, 0);
  EXPECT_NEAR(m.acc_max, (r10 - r2) / 50, kExact);  // (sqrt10/5 - sqrt2/5) / 10, at t = 55
  EXPECT_EQ(m.acc_max_time, 55);
  EXPECT_NEAR(m.acc_min, -r2 / 600, kExact);  // (sqrt2/15 - sqrt2/10) / 20, at t = 30
  EXPECT_EQ(m.acc_min_time, 30);
}

TEST(PointerMeasuresWorkedExample, ThresholdsByHand) {
  PointerMeasureSettings s;
  s.flip_threshold = 1.5;      // the y run -1 drops out; +2 and +3 are one direction
  s.initiation_threshold = 3;  // distances 0, 0, sqrt8, sqrt2, sqrt10: beyond 3 first at t = 55,
                               // so the sample before it, t = 45
  s.hover_threshold = 10;      // the 10 ms still segment is not longer than 10
  PointerMeasures m = pointer_measures(kExample, s);
  EXPECT_EQ(m.xpos_flips, 1);
  EXPECT_EQ(m.ypos_flips, 0);
  EXPECT_EQ(m.initiation_time, 45);
  EXPECT_EQ(*m.hover_time, 0);
  EXPECT_EQ(*m.hovers, 0);
  s = {};
  s.hover_threshold = 5;
  s.hover_incl_initial = false;  // the initial 10 ms (initiation_time 10 > 5) is taken off
  m = pointer_measures(kExample, s);
  EXPECT_EQ(*m.hover_time, 0);
  EXPECT_EQ(*m.hovers, 0);
}

TEST(PointerMeasuresWorkedExample, RemapAlignAndTimeNormalise) {
  // Ends at (30, -20): mirrored in x (ends right) and in y (ends down), then moved to (0, 0).
  const std::vector<PointerSample> raw = {{0, 10, 5}, {10, 20, -5}, {30, 30, -20}};
  const auto p = align_start(remap_symmetric(raw));
  ASSERT_EQ(p.size(), 3u);
  EXPECT_EQ(p[1].x, -10);
  EXPECT_EQ(p[1].y, 10);
  EXPECT_EQ(p[2].x, -20);
  EXPECT_EQ(p[2].y, 25);
  const auto kept = remap_symmetric(raw, RemapX::right, RemapY::down);  // already right and down
  EXPECT_EQ(kept[2].x, 30);
  EXPECT_EQ(kept[2].y, -20);
  // 4 steps: t = 0, 10, 20, 30; x halfway between -10 (t 10) and -20 (t 30) at t = 20.
  const auto tn = time_normalize(p, 4);
  ASSERT_EQ(tn.size(), 4u);
  EXPECT_EQ(tn[2].t, 20);
  EXPECT_NEAR(tn[2].x, -15, kExact);
  EXPECT_NEAR(tn[2].y, 17.5, kExact);
  EXPECT_EQ(tn[3].x, -20);
}

TEST(PointerMeasuresWorkedExample, DeviationSignsFollowMousetrap) {
  // Ends down-left of its start (direct path y = x, downwards): (1, -2) projects to (-1/2, -1/2),
  // lies below it (y -2 < -1/2), so -3/sqrt2; the path ends below its start, so every sign is
  // flipped: +3/sqrt2. The shoelace area is -6 (clockwise), flipped for a down-left end: +6.
  const std::vector<PointerSample> down = {{0, 0, 0}, {10, 1, -2}, {20, -4, -4}};
  const PointerDeviations d = pointer_deviations(down);
  EXPECT_NEAR(d.x_ideal[1], -0.5, kExact);
  EXPECT_NEAR(d.y_ideal[1], -0.5, kExact);
  EXPECT_NEAR(d.dev_ideal[1], 3 / std::sqrt(2.0), kExact);
  const PointerMeasures m = pointer_measures(down);
  EXPECT_NEAR(m.mad, 3 / std::sqrt(2.0), kExact);
  EXPECT_NEAR(m.auc, 6, kExact);
}

TEST(PointerMeasuresRejects, BadTraces) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  const std::vector<std::vector<PointerSample>> bad = {
      {},
      {{0, 0, 0}},
      {{0, 0, 0}, {10, 1, 1}, {10, 2, 2}},  // t repeats
      {{0, 0, 0}, {10, 1, 1}, {5, 2, 2}},   // t goes back
      {{0, 0, 0}, {10, nan, 1}},
      {{0, 0, 0}, {10, 1, inf}},
      {{0, 0, 0}, {inf, 1, 1}},
  };
  for (const auto& b : bad) {
    EXPECT_THROW(pointer_measures(b), feint::InvalidData) << b.size();
    EXPECT_THROW(remap_symmetric(b), feint::InvalidData) << b.size();
    EXPECT_THROW(align_start(b), feint::InvalidData) << b.size();
    EXPECT_THROW(time_normalize(b), feint::InvalidData) << b.size();
    EXPECT_THROW(pointer_deviations(b), feint::InvalidData) << b.size();
    EXPECT_THROW(pointer_derivatives(b), feint::InvalidData) << b.size();
  }
  try {
    pointer_measures(bad[2]);
    FAIL();
  } catch (const feint::InvalidData& e) {
    EXPECT_NE(std::string(e.what()).find("sample 3 of 3: t = 10 does not come after t = 10"),
              std::string::npos)
        << e.what();
  }
  try {
    pointer_measures(bad[1]);
    FAIL();
  } catch (const feint::InvalidData& e) {
    EXPECT_NE(std::string(e.what()).find("at least 2"), std::string::npos) << e.what();
  }
  // A negative first timestamp: mousetrap's mt_measures stops on it; the other steps take it.
  const std::vector<PointerSample> early = {{-5, 0, 0}, {10, 1, 1}};
  EXPECT_THROW(pointer_measures(early), feint::InvalidData);
  EXPECT_NO_THROW(time_normalize(early));
}

TEST(PointerMeasuresRejects, BadSettings) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  PointerMeasureSettings s;
  s.flip_threshold = -1;
  EXPECT_THROW(pointer_measures(kExample, s), feint::UsageError);
  s = {};
  s.hover_threshold = nan;
  EXPECT_THROW(pointer_measures(kExample, s), feint::UsageError);
  s = {};
  s.hover_threshold = -10;
  EXPECT_THROW(pointer_measures(kExample, s), feint::UsageError);
  s = {};
  s.initiation_threshold = -0.5;
  EXPECT_THROW(pointer_measures(kExample, s), feint::UsageError);
  EXPECT_THROW(time_normalize(kExample, 1), feint::UsageError);
  EXPECT_THROW(align_start(kExample, nan, 0), feint::UsageError);
}

}  // namespace
