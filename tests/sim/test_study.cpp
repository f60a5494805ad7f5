// The simulated observer and study: the behaviour selection.md requires, checked on the generated
// pad traces with a simple trapezoid error (trial_error), and the files write_study produces.
#include <gtest/gtest.h>

#include <zlib.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "feint/error.hpp"
#include "feint/io/csv.hpp"
#include "feint/io/number.hpp"
#include "feint/sim/options.hpp"
#include "feint/sim/study.hpp"

#include <unistd.h>

using namespace feint::sim;
using feint::Rng;

TEST(TrialError, TrapezoidOverTheTrimmedWindow) {
  // pad 0.5 -> 1 linearly over [0, 10], target 1: |T - pad| = 0.5 - t/20; window [0.5, 9.5]
  const std::vector<PadSample> pad = {{0, 0.5}, {10, 1.0}};
  EXPECT_NEAR(trial_error(pad, 1.0), 0.25, 1e-12);
  EXPECT_NEAR(trial_error(pad, 0.0), 0.75, 1e-12);
  EXPECT_NEAR(trial_error(pad, 1.0, 0.0), 0.25, 1e-12);
  EXPECT_TRUE(std::isnan(trial_error({{0, 0.5}}, 1.0)));
}

TEST(Observer, FamiliarityGrowsWithExposureAndFadesWithTime) {
  Observer o;
  EXPECT_EQ(o.familiarity(Strategy::switching, Variant::main), 0.0);
  double last = 0;
  for (int i = 0; i < 5; ++i) {
    o.remember(Strategy::switching, Variant::main);
    const double f = o.familiarity(Strategy::switching, Variant::main);
    EXPECT_GT(f, last);
    last = f;
  }
  EXPECT_EQ(o.familiarity(Strategy::switching, Variant::v2), 0.0);
  for (int i = 0; i < 10; ++i) o.remember(Strategy::optimal, Variant::main);
  EXPECT_LT(o.familiarity(Strategy::switching, Variant::main), last);  // not seen recently
}

TEST(Observer, PadStaysInRangeAndNeverOutrunsItsSpeed) {
  Observer o;
  Geometry g;
  Rng rng(5);
  for (auto s : {Strategy::exaggerating, Strategy::switching, Strategy::ambiguous, Strategy::optimal}) {
    const auto path = trajectory(s, Variant::main, Target::right, g);
    const auto pad = o.watch(path, s, Variant::main, Target::right, g, rng);
    ASSERT_EQ(pad.size(), path.size());
    EXPECT_EQ(pad.front().pad, 0.5);
    for (std::size_t i = 1; i < pad.size(); ++i) {
      EXPECT_GE(pad[i].pad, 0.0);
      EXPECT_LE(pad[i].pad, 1.0);
      EXPECT_LE(std::abs(pad[i].pad - pad[i - 1].pad) / (pad[i].t - pad[i - 1].t),
                o.params().pad_speed * (1 + 1e-9));
    }
  }
}

namespace {
/// Mean trial error by condition and iteration, and by strategy at first / later exposure.
struct StudyStats {
  std::map<int, std::vector<double>> by_iteration[2];  // condition -> iteration -> errors
  std::map<Strategy, std::vector<double>> first, repeated;
};

StudyStats run_study(int participants, std::uint64_t seed, const ObserverParams& observer) {
  StudySettings s;
  s.participants = participants;
  s.seed = seed;
  s.observer = observer;
  StudyStats st;
  for (int i = 0; i < 2 * participants; ++i) {
    const auto p = simulate_participant(s, i);
    std::map<std::pair<Strategy, Variant>, int> seen;
    for (const auto& tr : p.trials) {
      EXPECT_GE(tr.error, 0.0);
      EXPECT_LE(tr.error, 1.0);
      st.by_iteration[i / participants][tr.iteration].push_back(tr.error);
      int& n = seen[{tr.strategy, tr.variant}];
      if (n == 0) st.first[tr.strategy].push_back(tr.error);
      if (n >= 3) st.repeated[tr.strategy].push_back(tr.error);
      ++n;
    }
  }
  return st;
}

double mean(const std::vector<double>& v) {
  double s = 0;
  for (double x : v) s += x;
  return s / static_cast<double>(v.size());
}

/// Least-squares slope of the mean error on the iteration number.
double slope(const std::map<int, std::vector<double>>& by_it) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0, n = 0;
  for (const auto& [it, errs] : by_it) {
    const double y = mean(errs);
    sx += it; sy += y; sxx += it * it; sxy += it * y; n += 1;
  }
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}
}  // namespace

TEST(SimulatedStudy, HeuristicFirstExposuresDeceiveAndRepetitionTeaches) {
  const StudyStats st = run_study(60, 11, ObserverParams{});
  for (auto s : {Strategy::exaggerating, Strategy::switching, Strategy::ambiguous}) {
    EXPECT_GT(mean(st.first.at(s)), 0.5) << to_string(s);                          // high error
    EXPECT_LT(mean(st.repeated.at(s)), mean(st.first.at(s)) - 0.08) << to_string(s);  // learnt
  }
  EXPECT_LT(mean(st.first.at(Strategy::optimal)), 0.3);  // the honest path is read correctly
}

TEST(SimulatedStudy, HeuristicErrorFallsMoreUnderRandomThanUnderAdaptive) {
  const StudyStats st = run_study(120, 3, ObserverParams{});
  const double adaptive = slope(st.by_iteration[0]);
  const double random = slope(st.by_iteration[1]);
  EXPECT_LT(random, -0.0005);           // random: the error falls over the 20 iterations
  EXPECT_LT(random, adaptive - 0.0005);  // ... clearly more than under adaptive
  // iteration 1 is a first exposure under both algorithms: similar error
  EXPECT_NEAR(mean(st.by_iteration[0].at(1)), mean(st.by_iteration[1].at(1)), 0.06);
}

TEST(SimulatedStudy, SameSeedSameParticipant) {
  StudySettings s;
  s.participants = 2;
  const auto a = simulate_participant(s, 3);
  const auto b = simulate_participant(s, 3);
  EXPECT_EQ(a.id, "P04");
  EXPECT_EQ(a.condition, Algorithm::random);
  ASSERT_EQ(a.trials.size(), b.trials.size());
  for (std::size_t i = 0; i < a.trials.size(); ++i) EXPECT_EQ(a.trials[i].error, b.trials[i].error);
  s.seed = 2;
  EXPECT_NE(simulate_participant(s, 3).mean_error, a.mean_error);
}

TEST(WriteStudy, WritesGzippedLogsAndAQuestionnaire) {
  const auto dir = std::filesystem::temp_directory_path() / ("feint-sim-study-" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  StudySettings s;
  s.participants = 2;
  s.iterations = 3;
  const auto people = write_study(s, dir.string());
  ASSERT_EQ(people.size(), 4u);
  for (const auto& p : people) {
    const auto file = dir / "logs" / (p.id + ".csv.gz");
    ASSERT_TRUE(std::filesystem::exists(file)) << file;
    feint::io::CsvReader r(file.string());
    EXPECT_TRUE(r.compressed());
    EXPECT_EQ(r.header(), (std::vector<std::string>{"participant", "condition", "iteration", "strategy",
                                                    "variant", "target", "t", "pad", "pad_speed",
                                                    "robot_x", "robot_y"}));
    int rows = 0;
    double last_t = -1;
    std::string last_it;
    while (r.next()) {
      ++rows;
      EXPECT_EQ(r.field(0), p.id);
      EXPECT_EQ(r.field(1), to_string(p.condition));
      const double t = *feint::io::parse_double(r.field(6));
      if (std::string(r.field(2)) == last_it) {
        EXPECT_GT(t, last_t);
      }
      last_it = std::string(r.field(2));
      last_t = t;
      const double pad = *feint::io::parse_double(r.field(7));
      EXPECT_GE(pad, 0.0);
      EXPECT_LE(pad, 1.0);
    }
    EXPECT_GT(rows, 3 * 50);
  }
  feint::io::CsvReader q((dir / "questionnaire.csv").string());
  EXPECT_EQ(q.header(), (std::vector<std::string>{"participant", "condition", "entertainment", "deception",
                                                  "intelligence", "trust"}));
  int n = 0;
  while (q.next()) {
    ++n;
    for (std::size_t i = 2; i < 6; ++i) {
      const auto v = feint::io::parse_integer(q.field(i));
      ASSERT_TRUE(v.has_value());
      EXPECT_GE(*v, 1);
      EXPECT_LE(*v, 7);
    }
  }
  EXPECT_EQ(n, 4);
  // The yes/no question, as `feint collect` writes it: one row per participant, in order.
  feint::io::CsvReader yn((dir / "questionnaire_yesno.csv").string());
  EXPECT_EQ(yn.header(), (std::vector<std::string>{"participant", "condition", "intentional"}));
  for (const auto& p : people) {
    ASSERT_TRUE(yn.next());
    EXPECT_EQ(yn.field(0), p.id);
    EXPECT_EQ(yn.field(1), to_string(p.condition));
    EXPECT_EQ(yn.field(2), p.intentional ? "yes" : "no");
  }
  EXPECT_FALSE(yn.next());
  std::filesystem::remove_all(dir);
}

TEST(SimulatedStudy, IntentionalFollowsTheDeceptionRatingAsDocumented) {
  // P(yes | deception rating d) = 1 / (1 + exp(-(d - 4.5))): over 400 participants the yes count
  // equals the sum of those probabilities within 4 standard deviations of the binomial sum.
  StudySettings s;
  s.participants = 200;
  s.iterations = 2;
  double expected = 0, variance = 0;
  int yes = 0;
  for (int i = 0; i < 2 * s.participants; ++i) {
    const auto p = simulate_participant(s, i);
    const double q = 1 / (1 + std::exp(-(p.likert[1] - 4.5)));
    expected += q;
    variance += q * (1 - q);
    yes += p.intentional ? 1 : 0;
  }
  EXPECT_NEAR(yes, expected, 4 * std::sqrt(variance));
  EXPECT_GT(variance, 20.0);  // the ratings vary, so the check has power
}

// The goal-inference participant (the default of feint simulate study; docs/paper-scale.md) meets
// selection.md's three requirements too. Its pads stay nearer the middle (beta 0.3 /m: a cautious
// observer), so the margins are smaller than the heuristic's; the figures in the comments were
// measured with these seeds.
TEST(SimulatedStudy, GoalInferenceFirstExposuresDeceiveAndRepetitionTeaches) {
  const StudyStats st = run_study(60, 11, goal_inference_observer());
  // measured: first 0.564 / 0.558 / 0.546, repeated (4th exposure on) 0.267 / 0.284 / 0.317
  for (auto s : {Strategy::exaggerating, Strategy::switching, Strategy::ambiguous}) {
    EXPECT_GT(mean(st.first.at(s)), 0.53) << to_string(s);                           // deceived
    EXPECT_LT(mean(st.repeated.at(s)), mean(st.first.at(s)) - 0.15) << to_string(s);  // learnt
  }
  EXPECT_LT(mean(st.first.at(Strategy::optimal)), 0.46);  // measured 0.436: read toward the truth
}

TEST(SimulatedStudy, GoalInferenceErrorFallsMoreUnderRandomThanUnderAdaptive) {
  const StudyStats st = run_study(120, 3, goal_inference_observer());
  // measured: slopes -0.00151 (adaptive) and -0.00324 (random) per iteration
  const double adaptive = slope(st.by_iteration[0]);
  const double random = slope(st.by_iteration[1]);
  EXPECT_LT(random, -0.002);
  EXPECT_LT(random, adaptive - 0.001);
  EXPECT_NEAR(mean(st.by_iteration[0].at(1)), mean(st.by_iteration[1].at(1)), 0.06);
}

// Three or more conditions (docs/simulation.md "Conditions"): participant i belongs to condition
// i / N between participants; within participants every participant sees every condition once,
// in an order rotated by participant, so each condition is seen in each position equally often.
TEST(SimulatedStudy, ThreeConditionsBetweenAssignEachBlockOfParticipantsToOneCondition) {
  StudySettings s;
  s.participants = 3;
  s.iterations = 4;
  s.conditions = {Algorithm::adaptive, Algorithm::random, Algorithm::fixed_block};
  std::vector<std::string> ids;
  for (int i = 0; i < 9; ++i) {
    const ParticipantRecord p = simulate_participant(s, i);
    EXPECT_EQ(p.condition, s.conditions[static_cast<std::size_t>(i / 3)]) << i;
    EXPECT_EQ(p.trials.size(), 4u);
    ids.push_back(p.id);
  }
  EXPECT_EQ(ids.front(), "P01");
  EXPECT_EQ(ids.back(), "P09");
  EXPECT_THROW(simulate_participant(s, 9), feint::UsageError);
  // The first two conditions' participants are those of a two-condition study with the same seed.
  StudySettings two = s;
  two.conditions = {Algorithm::adaptive, Algorithm::random};
  for (int i = 0; i < 6; ++i) EXPECT_EQ(simulate_participant(two, i).mean_error, simulate_participant(s, i).mean_error);
}

TEST(SimulatedStudy, ThreeConditionsWithinRotateTheOrderByParticipant) {
  StudySettings s;
  s.within = true;
  s.participants = 6;
  s.iterations = 3;
  s.conditions = {Algorithm::adaptive, Algorithm::random, Algorithm::fixed_balanced};
  std::map<std::pair<Algorithm, int>, int> position_count;  // (condition, block) -> participants
  for (int i = 0; i < 6; ++i) {
    const auto blocks = simulate_participant_within(s, i);
    ASSERT_EQ(blocks.size(), 3u);
    for (std::size_t b = 0; b < 3; ++b) {
      EXPECT_EQ(blocks[b].condition, s.conditions[(b + static_cast<std::size_t>(i)) % 3]) << i << " " << b;
      EXPECT_EQ(blocks[b].trials.front().block, static_cast<int>(b) + 1);
      ++position_count[{blocks[b].condition, static_cast<int>(b) + 1}];
    }
  }
  for (const auto& [key, n] : position_count) EXPECT_EQ(n, 2);  // 6 people: each position twice
  EXPECT_EQ(position_count.size(), 9u);
  // Two conditions: adaptive first for P01, P03, ..., random first for P02, P04, ...
  s.conditions = {Algorithm::adaptive, Algorithm::random};
  EXPECT_EQ(simulate_participant_within(s, 0).front().condition, Algorithm::adaptive);
  EXPECT_EQ(simulate_participant_within(s, 1).front().condition, Algorithm::random);
}

TEST(SimulatedStudy, ConditionsMustBeTwoOrMoreAndDistinct) {
  StudySettings s;
  s.conditions = {Algorithm::adaptive};
  try {
    simulate_participant(s, 0);
    FAIL() << "one condition accepted";
  } catch (const feint::UsageError& e) {
    EXPECT_NE(std::string(e.what()).find("1 condition(s) given; a study compares two or more"), std::string::npos)
        << e.what();
  }
  s.conditions = {Algorithm::random, Algorithm::adaptive, Algorithm::random};
  try {
    simulate_participant_within(s, 0);
    FAIL() << "a repeated condition accepted";
  } catch (const feint::UsageError& e) {
    EXPECT_NE(std::string(e.what()).find("'random' is named twice"), std::string::npos) << e.what();
  }
}

TEST(SimulatedStudy, ThreeConditionTomlNamesNoPairAndTwoConditionTomlComparesThem) {
  StudySettings s;
  const std::string two = study_toml(s, "test");
  EXPECT_NE(two.find("compare = \"adaptive,random\"\n"), std::string::npos) << two;
  s.conditions = {Algorithm::adaptive, Algorithm::random, Algorithm::fixed_block};
  const std::string three = study_toml(s, "test");
  EXPECT_EQ(three.find("compare ="), std::string::npos) << three;
  EXPECT_NE(three.find("# The study compares its 3 conditions (adaptive, random, fixed-block)"), std::string::npos)
      << three;
  EXPECT_NE(three.find("design = \"between\""), std::string::npos);
}

TEST(SimulatedStudy, NamedConditionsRunOneAlgorithmUnderSeveralNames) {
  StudyOptions o;
  o.conditions = "a=random, b=random ,c=random";
  const StudySettings s = study_settings(o);
  ASSERT_EQ(s.conditions.size(), 3u);
  EXPECT_EQ(s.condition_names, (std::vector<std::string>{"a", "b", "c"}));
  ASSERT_EQ(s.participants, 20);
  const ParticipantRecord p = simulate_participant(s, 45);  // the third block of 20
  EXPECT_EQ(p.condition, Algorithm::random);
  EXPECT_EQ(p.condition_name, "c");
  EXPECT_NE(study_toml(s, "t").find("# The study compares its 3 conditions (a, b, c)"), std::string::npos);
  o.conditions = "a=random,random";  // unnamed ones keep the algorithm's name
  EXPECT_EQ(study_settings(o).condition_names, (std::vector<std::string>{"a", "random"}));
  o.conditions = "x=random,x=adaptive";
  EXPECT_THROW(study_settings(o), feint::UsageError);
  o.conditions = "a b=random,adaptive";
  EXPECT_THROW(study_settings(o), feint::UsageError);
  o.conditions = "adaptive,coin";
  try {
    study_settings(o);
    FAIL() << "an unknown algorithm accepted";
  } catch (const feint::UsageError& e) {
    EXPECT_NE(std::string(e.what()).find("--conditions 'adaptive,coin': unknown selection algorithm 'coin'"),
              std::string::npos)
        << e.what();
  }
}
