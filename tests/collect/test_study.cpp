// feint collect: assignment, rounds, validation, durable logs and the rebuild after a restart.
#include <gtest/gtest.h>

#include <map>
#include <set>
#include <thread>

#include "collect_helpers.hpp"
#include "feint/collect/study.hpp"
#include "feint/error.hpp"
#include "feint/io/csv.hpp"
#include "feint/rng.hpp"

namespace feint::collect {
namespace {

namespace fs = std::filesystem;
using namespace testing;

int rejection_status(const std::function<void()>& f, std::string* code = nullptr) {
  try {
    f();
  } catch (const Rejection& r) {
    if (code) *code = r.code();
    return r.status();
  }
  return 0;
}

TEST(CollectAssignment, IsBalancedInEveryBlockOfConditions) {
  const auto dir = fresh_dir("balance");
  Settings s = fast_settings();
  s.conditions = {parse_condition("adaptive", 0.5), parse_condition("random", 0.5),
                  parse_condition("fixed-block", 0.5)};
  Study study(dir, s);
  std::vector<std::string> cond;
  for (int i = 0; i < 30; ++i) cond.push_back(study.join("P" + std::to_string(i)).condition);
  for (int b = 0; b < 10; ++b) {
    std::set<std::string> block(cond.begin() + 3 * b, cond.begin() + 3 * b + 3);
    EXPECT_EQ(block.size(), 3u) << "block " << b;
  }
  // Not always the same order (it is randomised per block).
  std::set<std::string> firsts;
  for (int b = 0; b < 10; ++b) firsts.insert(cond[3 * b]);
  EXPECT_GT(firsts.size(), 1u);
  // Written to a file in STUDY, one row per participant, in order.
  const auto rows = lines(slurp(dir / "collect" / "assignment.csv"));
  ASSERT_EQ(rows.size(), 31u);
  EXPECT_EQ(rows[0], "participant,index,condition,assigned_utc");
  EXPECT_EQ(rows[5].substr(0, rows[5].find(',', 3)), "P4,4");
  // The same seed gives the same assignment (a study can be re-created).
  const auto dir2 = fresh_dir("balance2");
  Study again(dir2, s);
  for (int i = 0; i < 30; ++i) EXPECT_EQ(again.join("Q" + std::to_string(i)).condition, cond[i]);
}

TEST(CollectRounds, AreTheSimulatorsRunsSeededPerParticipant) {
  const auto dir = fresh_dir("plan");
  Settings s = fast_settings();
  s.seed = 42;
  Study study(dir, s);
  study.join("A");
  const auto b = study.join("B");
  const std::size_t cond = b.condition == "adaptive" ? 0 : 1;
  sim::RunSettings rs;
  rs.algorithm = s.conditions[cond].algorithm;
  rs.iterations = s.iterations;
  Rng rng = Rng::stream(42, 1000003 + 1);
  const auto run = sim::generate_run(rs, rng);
  for (int i = 1; i <= s.iterations; ++i) {
    const Round r = study.plan_round(1, cond, RoundKind::main, i);
    EXPECT_EQ(r.strategy, run[i - 1].strategy);
    EXPECT_EQ(r.variant, run[i - 1].variant);
    EXPECT_EQ(r.target, run[i - 1].target);
    EXPECT_EQ(r.path.size(), sim::trajectory(r.strategy, r.variant, r.target, s.geometry).size());
  }
  for (int i = 1; i <= s.practice; ++i) {
    EXPECT_EQ(study.plan_round(1, cond, RoundKind::practice, i).strategy, sim::Strategy::optimal);
  }
}

TEST(CollectRounds, SavedRoundsAreAppendedInTheFormatsLayout) {
  const auto dir = fresh_dir("layout");
  Study study(dir, fast_settings());
  const auto st = study.join("P01");
  play_all(study, "P01");
  const auto status = *study.status("P01");
  EXPECT_EQ(status.practice_saved, 2);
  EXPECT_EQ(status.rounds_saved, 6);
  const auto log = lines(slurp(dir / "logs" / "P01.csv"));
  ASSERT_GT(log.size(), 6u);
  EXPECT_EQ(log[0],
            "participant,condition,iteration,strategy,variant,target,t,pad,pad_speed,robot_x,robot_y");
  std::set<std::string> iterations;
  for (std::size_t i = 1; i < log.size(); ++i) {
    const auto f = io::split_csv_line(log[i]);
    ASSERT_EQ(f.size(), 11u);
    EXPECT_EQ(f[0], "P01");
    EXPECT_EQ(f[1], st.condition);
    EXPECT_EQ(f[8], "0.8");
    iterations.insert(f[2]);
  }
  EXPECT_EQ(iterations.size(), 6u);
  // Practice rounds are apart, outside logs/, and always the optimal strategy.
  const auto practice = lines(slurp(dir / "practice" / "P01.csv"));
  for (std::size_t i = 1; i < practice.size(); ++i) {
    EXPECT_EQ(io::split_csv_line(practice[i])[3], "optimal");
  }
  EXPECT_EQ(study.stage(status), Stage::questionnaire);
}

TEST(CollectRounds, DuplicateAndOutOfOrderSubmissionsAreRefusedAndTheLogKept) {
  const auto dir = fresh_dir("order");
  Study study(dir, fast_settings());
  study.join("P1");
  const auto& s = study.settings();
  const Round p1 = study.start_round("P1");
  const auto trace = valid_trace(p1, s.pad_speed);
  std::string code;
  // Main rounds before the practice is done: out of order.
  EXPECT_EQ(rejection_status([&] { study.submit_round("P1", RoundKind::main, 1, trace); }, &code),
            409);
  EXPECT_EQ(code, "out_of_order");
  // Practice 2 before practice 1.
  EXPECT_EQ(
      rejection_status([&] { study.submit_round("P1", RoundKind::practice, 2, trace); }, &code),
      409);
  EXPECT_EQ(code, "out_of_order");
  study.submit_round("P1", RoundKind::practice, 1, trace);
  const std::string before = slurp(dir / "practice" / "P1.csv");
  // The same round again (a replay, or a retry whose answer was lost): duplicate.
  EXPECT_EQ(
      rejection_status([&] { study.submit_round("P1", RoundKind::practice, 1, trace); }, &code),
      409);
  EXPECT_EQ(code, "duplicate");
  EXPECT_EQ(rejection_status([&] { study.submit_round("P1", RoundKind::main, 99, trace); }, &code),
            409);
  EXPECT_EQ(slurp(dir / "practice" / "P1.csv"), before);
  EXPECT_EQ(rejection_status([&] { study.submit_round("nobody", RoundKind::practice, 1, trace); }),
            404);
}

TEST(CollectRounds, EveryInvalidTraceIsRefusedWithItsReason) {
  const auto dir = fresh_dir("invalid");
  Settings s = fast_settings();
  s.max_samples = 500;
  Study study(dir, s);
  study.join("P1");
  const Round r = study.start_round("P1");
  const auto good = valid_trace(r, s.pad_speed);
  auto submit = [&](std::vector<PadSample> t) {
    std::string code;
    const int status =
        rejection_status([&] { study.submit_round("P1", RoundKind::practice, 1, t); }, &code);
    return std::to_string(status) + " " + code;
  };
  auto bad = good;
  bad[3].pad = 1.2;  // outside [0, 1]
  EXPECT_EQ(submit(bad), "422 invalid_trace");
  bad = good;
  bad[4].t = bad[3].t;  // times not increasing
  EXPECT_EQ(submit(bad), "422 invalid_trace");
  bad = good;
  bad[5].pad = bad[4].pad + 0.5;  // a jump: faster than the pad speed
  EXPECT_EQ(submit(bad), "422 invalid_trace");
  bad = good;
  bad[2].pad = bad[1].pad + s.pad_speed * (bad[2].t - bad[1].t) * (1 + 1e-5);  // just too fast
  bad[3].pad = bad[2].pad;
  EXPECT_EQ(submit(bad), "422 invalid_trace");
  bad = good;
  bad.front().pad = 0.6;  // the pad starts in the middle
  EXPECT_EQ(submit(bad), "422 invalid_trace");
  bad = good;
  bad.pop_back();  // the round is not over
  EXPECT_EQ(submit(bad), "422 invalid_trace");
  bad = good;
  bad[2].t = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(submit(bad), "422 invalid_trace");
  EXPECT_EQ(submit({{0, 0.5}}), "422 invalid_trace");
  std::vector<PadSample> many(501, PadSample{0, 0.5});
  EXPECT_EQ(submit(many), "413 too_many_samples");
  EXPECT_FALSE(fs::exists(dir / "practice" / "P1.csv"));  // nothing was written
  EXPECT_EQ(submit(good), "0 ");                          // and the real one is accepted
}

TEST(CollectParticipants, UnsafeIdsNeverBecomeFileNames) {
  const auto dir = fresh_dir("ids");
  Study study(dir, fast_settings());
  for (const std::string& id : std::vector<std::string>{"../x", "a/b", "-rf", "a b", "a.csv",
                                                        std::string(65, 'a'), "P1\n"}) {
    EXPECT_EQ(rejection_status([&] { study.join(id); }), 400) << id;
  }
  EXPECT_TRUE(valid_participant_id("5f1b2c3d4e5f6a7b8c9d0e1f"));  // a Prolific ID
  const auto g = study.join("");
  EXPECT_TRUE(valid_participant_id(g.id));
  EXPECT_EQ(g.id.front(), 'G');
  EXPECT_NE(study.join("").id, g.id);
}

TEST(CollectQuestionnaire, IsWrittenInTheWideLikertLayoutOnceAfterTheRounds) {
  const auto dir = fresh_dir("quest");
  Study study(dir, fast_settings());
  const auto st = study.join("P1");
  std::map<std::string, std::string> a{{"entertainment", "6"},
                                       {"deception", "5"},
                                       {"intelligence", "7"},
                                       {"trust", "2"},
                                       {"intentional", "yes"}};
  EXPECT_EQ(rejection_status([&] { study.submit_questionnaire("P1", a); }), 409);  // rounds first
  play_all(study, "P1");
  auto bad = a;
  bad["trust"] = "8";
  EXPECT_EQ(rejection_status([&] { study.submit_questionnaire("P1", bad); }), 422);
  bad = a;
  bad["intentional"] = "maybe";
  EXPECT_EQ(rejection_status([&] { study.submit_questionnaire("P1", bad); }), 422);
  bad = a;
  bad["extra"] = "1";
  EXPECT_EQ(rejection_status([&] { study.submit_questionnaire("P1", bad); }), 422);
  study.submit_questionnaire("P1", a);
  EXPECT_EQ(rejection_status([&] { study.submit_questionnaire("P1", a); }), 409);
  EXPECT_EQ(slurp(dir / "questionnaire.csv"),
            "participant,condition,entertainment,deception,intelligence,trust\nP1," + st.condition +
                ",6,5,7,2\n");
  EXPECT_EQ(slurp(dir / "questionnaire_yesno.csv"),
            "participant,condition,intentional\nP1," + st.condition + ",yes\n");
  EXPECT_EQ(study.stage(*study.status("P1")), Stage::done);
}

TEST(CollectRestart, RebuildsTheStateFromTheFiles) {
  const auto dir = fresh_dir("restart");
  std::string cond;
  {
    Study study(dir, fast_settings());
    cond = study.join("P1").condition;
    study.join("P2");
    for (int i = 0; i < 4; ++i) {
      const Round r = study.start_round("P1");
      study.submit_round("P1", r.kind, r.iteration, valid_trace(r, 0.8));
    }
    study.start_round("P2");  // P2's first round is on screen when the server goes down
  }
  Study study(dir, fast_settings());
  study.start_round("P2");  // the page reloads after the restart: the same round again
  EXPECT_EQ(study.status("P2")->interruptions, 1);
  EXPECT_NE(slurp(dir / "collect" / "events.csv").find(",P2,interrupted,"), std::string::npos);
  const auto st = *study.status("P1");
  EXPECT_EQ(st.condition, cond);
  EXPECT_EQ(st.practice_saved, 2);
  EXPECT_EQ(st.rounds_saved, 2);
  EXPECT_EQ(study.status("P2")->rounds_saved, 0);
  // Resumes at the first round not saved; the next participant gets the next index.
  const Round r = study.start_round("P1");
  EXPECT_EQ(r.kind, RoundKind::main);
  EXPECT_EQ(r.iteration, 3);
  EXPECT_EQ(study.status("P1")->interruptions, 0);  // round 3 had not been shown before
  study.join("P3");
  EXPECT_EQ(lines(slurp(dir / "collect" / "assignment.csv")).back().substr(0, 5), "P3,2,");
}

TEST(CollectRestart, ARoundCutShortByACrashIsSetAsideNeverTruncated) {
  const auto dir = fresh_dir("crash");
  {
    Study study(dir, fast_settings());
    study.join("P1");
    for (int i = 0; i < 3; ++i) {
      const Round r = study.start_round("P1");
      study.submit_round("P1", r.kind, r.iteration, valid_trace(r, 0.8));
    }
  }
  const fs::path log = dir / "logs" / "P1.csv";
  const std::string good = slurp(log);
  // A crash in the middle of round 2: some complete rows, then half a line.
  const auto rows = lines(good);
  const std::string partial = std::string("P1,") + io::split_csv_line(rows[1])[1] +
                              ",2,optimal,main,left,0,0.5,0.8,0,0\nP1,x,2,optimal,main,left,0.01";
  {
    std::ofstream out(log, std::ios::app | std::ios::binary);
    out << partial;
  }
  Study study(dir, fast_settings());
  EXPECT_EQ(study.status("P1")->rounds_saved, 1);
  EXPECT_EQ(slurp(log), good);  // the complete rounds, byte for byte
  // The damaged original is kept whole.
  int damaged = 0;
  for (const auto& e : fs::directory_iterator(dir / "collect" / "damaged")) {
    ++damaged;
    EXPECT_EQ(slurp(e.path()), good + partial);
  }
  EXPECT_EQ(damaged, 1);
  EXPECT_NE(slurp(dir / "collect" / "events.csv").find(",P1,recovered,"), std::string::npos);
  const Round r = study.start_round("P1");
  EXPECT_EQ(r.iteration, 2);
  study.submit_round("P1", r.kind, r.iteration, valid_trace(r, 0.8));
  EXPECT_EQ(study.status("P1")->rounds_saved, 2);
}

TEST(CollectRestart, RefusesLogsItDidNotWriteAndChangedConditions) {
  const auto dir = fresh_dir("foreign");
  {
    Study study(dir, fast_settings());
    study.join("P1");
  }
  { std::ofstream(dir / "logs" / "X9.csv") << "participant,iteration,target,t,pad\n"; }
  EXPECT_THROW(Study(dir, fast_settings()), InvalidData);
  fs::remove(dir / "logs" / "X9.csv");
  Settings other = fast_settings();
  other.conditions = {parse_condition("fixed-block", 0.5)};
  EXPECT_THROW(Study(dir, other), InvalidData);
  Settings items = fast_settings();
  EXPECT_NO_THROW(Study(dir, items));
}

TEST(CollectConcurrency, ParticipantsPlayingAtOnceNeverMixRows) {
  const auto dir = fresh_dir("concurrent");
  Study study(dir, fast_settings());
  constexpr int kPeople = 12;
  std::vector<std::thread> threads;
  for (int i = 0; i < kPeople; ++i) {
    threads.emplace_back([&study, i] {
      const std::string id = "C" + std::to_string(i);
      study.join(id);
      play_all(study, id);
      study.submit_questionnaire(id, {{"entertainment", "5"},
                                      {"deception", "4"},
                                      {"intelligence", "6"},
                                      {"trust", "3"},
                                      {"intentional", "no"}});
    });
  }
  for (auto& t : threads) t.join();
  std::map<std::string, int> per_condition;
  for (int i = 0; i < kPeople; ++i) {
    const std::string id = "C" + std::to_string(i);
    const auto log = lines(slurp(dir / "logs" / (id + ".csv")));
    int last = 0;
    for (std::size_t r = 1; r < log.size(); ++r) {
      const auto f = io::split_csv_line(log[r]);
      ASSERT_EQ(f[0], id);
      const int it = std::stoi(f[2]);
      ASSERT_TRUE(it == last || it == last + 1) << id << " row " << r;
      last = it;
    }
    EXPECT_EQ(last, 6);
    ++per_condition[study.status(id)->condition];
  }
  EXPECT_EQ(per_condition["adaptive"], kPeople / 2);
  EXPECT_EQ(per_condition["random"], kPeople / 2);
  EXPECT_EQ(lines(slurp(dir / "questionnaire.csv")).size(), kPeople + 1u);
  EXPECT_EQ(lines(slurp(dir / "collect" / "assignment.csv")).size(), kPeople + 1u);
}

}  // namespace
}  // namespace feint::collect
