// feint collect after a crash: every file it appends to, in every state a crash can leave it in
// (empty, header only, cut in the header, cut mid-line, ending with a complete append), is
// recognised and repaired on restart; nothing is lost (the original goes whole to
// collect/damaged/), the study carries on, restarts again, and `feint analyze` reads the folder.
#include <gtest/gtest.h>

#include <cstdlib>
#include <map>

#include "collect_helpers.hpp"
#include "feint/collect/study.hpp"
#include "feint/error.hpp"

namespace feint::collect {
namespace {

namespace fs = std::filesystem;
using namespace testing;

const std::vector<std::string> kFiles{"logs/P1.csv",       "practice/P1.csv",
                                      "questionnaire.csv", "questionnaire_yesno.csv",
                                      "collect/assignment.csv", "collect/events.csv"};

void answer(Study& s, const std::string& id) {
  s.submit_questionnaire(id, {{"entertainment", "5"},
                              {"deception", "4"},
                              {"intelligence", "6"},
                              {"trust", "3"},
                              {"intentional", "yes"}});
}

/// Plays every participant to the end (rounds, questionnaire), then a new one all the way.
void finish_everyone(Study& s, const std::string& newcomer) {
  for (const auto& p : s.overview()) {
    while (s.stage(*s.status(p.id)) == Stage::rounds) {
      const Round r = s.start_round(p.id);
      s.submit_round(p.id, r.kind, r.iteration, valid_trace(r, 0.8, r.iteration % 2));
    }
    if (!s.status(p.id)->questionnaire_done) answer(s, p.id);
  }
  s.join(newcomer);
  play_all(s, newcomer);
  answer(s, newcomer);
}

void copy_tree(const fs::path& from, const fs::path& to) {
  fs::remove_all(to);
  fs::create_directories(to);
  fs::copy(from, to, fs::copy_options::recursive);
}

/// The study's history, one snapshot of the folder after each step: P1 joins, plays every round,
/// answers; P2 joins and plays 3 rounds.
std::vector<fs::path> history(const fs::path& root) {
  const fs::path live = root / "live";
  fs::create_directories(live);
  std::vector<fs::path> snaps;
  auto snap = [&] {
    snaps.push_back(root / ("step" + std::to_string(snaps.size())));
    copy_tree(live, snaps.back());
  };
  Study s(live, fast_settings());
  snap();  // nothing yet
  s.join("P1");
  snap();
  for (int i = 0; i < 8; ++i) {
    const Round r = s.start_round("P1");
    s.submit_round("P1", r.kind, r.iteration, valid_trace(r, 0.8, r.iteration % 2));
    snap();
  }
  answer(s, "P1");
  snap();
  s.join("P2");
  snap();
  for (int i = 0; i < 3; ++i) {
    const Round r = s.start_round("P2");
    s.submit_round("P2", r.kind, r.iteration, valid_trace(r, 0.8));
    snap();
  }
  return snaps;
}

struct Case {
  std::string file, state;
  std::size_t step;     // the folder as after this step...
  std::string content;  // ...but with the file in this state
  std::string acked;    // what was acknowledged of the file before the crash
};

std::vector<Case> crash_cases(const std::vector<fs::path>& snaps) {
  std::vector<Case> out;
  for (const auto& f : kFiles) {
    // The step of the file's first append, and of its last.
    std::size_t first = 0, last = 0;
    for (std::size_t i = 1; i < snaps.size(); ++i) {
      const std::string before = slurp(snaps[i - 1] / f), after = slurp(snaps[i] / f);
      if (before == after) continue;
      if (first == 0) first = i;
      last = i;
    }
    const std::string one = slurp(snaps[first] / f);
    const std::string header = one.substr(0, one.find('\n') + 1);
    out.push_back({f, "empty", first, "", ""});
    out.push_back({f, "header only", first, header, ""});
    out.push_back({f, "cut in the header", first, header.substr(0, header.size() / 2), ""});
    const std::string before = slurp(snaps[last - 1] / f), after = slurp(snaps[last] / f);
    std::size_t cut = before.size() + (after.size() - before.size()) / 2;
    while (after[cut - 1] == '\n') ++cut;  // really mid-line
    out.push_back({f, "cut mid-line", last, after.substr(0, cut), before});
    out.push_back({f, "a complete append", last, after, after});
  }
  return out;
}

int run_analyze(const fs::path& dir) {
  const fs::path out = dir.parent_path() / (dir.filename().string() + "-out");
  const std::string cmd = std::string(FEINT_EXE) + " analyze " + dir.string() + " -o " +
                          out.string() + " > " + out.string() + ".log 2>&1";
  return std::system(cmd.c_str());
}

TEST(CollectCrashStates, EveryAppendedFileInEveryStateIsRepairedAndNothingIsLost) {
  const fs::path root = fresh_dir("states");
  const auto snaps = history(root);
  const auto cases = crash_cases(snaps);
  ASSERT_EQ(cases.size(), kFiles.size() * 5);
  int n = 0, analyzed = 0;
  for (const auto& c : cases) {
    SCOPED_TRACE(c.file + ", " + c.state);
    const fs::path dir = root / ("case" + std::to_string(n++));
    copy_tree(snaps[c.step], dir);
    { std::ofstream(dir / c.file, std::ios::binary | std::ios::trunc) << c.content; }
    std::map<std::string, std::string> headers;
    for (const auto& f : kFiles) {
      const std::string t = slurp(snaps.back() / f);
      headers[f] = t.substr(0, t.find('\n') + 1);
    }
    {
      std::unique_ptr<Study> s;
      ASSERT_NO_THROW(s = std::make_unique<Study>(dir, fast_settings()));
      // The acknowledged part is kept, byte for byte, at the start of the file.
      const std::string now = slurp(dir / c.file);
      EXPECT_EQ(now.substr(0, c.acked.size()), c.acked);
      if (c.state != "a complete append") {
        // Whatever changed went whole to collect/damaged/: the crash state is there as it was.
        if (now != c.content) {
          bool kept = false;
          for (const auto& e : fs::directory_iterator(dir / "collect" / "damaged"))
            kept = kept || slurp(e.path()) == c.content;
          EXPECT_TRUE(kept) << "the damaged original is not in collect/damaged/";
        }
      } else {
        EXPECT_EQ(now.substr(0, c.content.size()), c.content);
      }
      ASSERT_NO_THROW(finish_everyone(*s, "P9"));
    }
    // Every file: its header, then whole rows (at least one), and a second restart accepts it.
    for (const auto& f : kFiles) {
      if (!fs::exists(dir / f)) continue;
      const std::string t = slurp(dir / f);
      EXPECT_EQ(t.substr(0, headers[f].size()), headers[f]) << f;
      EXPECT_GT(lines(t).size(), 1u) << f;
      EXPECT_EQ(t.back(), '\n') << f;
    }
    ASSERT_NO_THROW(Study(dir, fast_settings()));
    EXPECT_EQ(lines(slurp(dir / "logs" / "P9.csv")).front() + "\n",
              headers["logs/P1.csv"]);
    // `feint analyze` reads the folder (for the states of the issue: empty and header only).
    if (c.state == "empty" || c.state == "header only") {
      EXPECT_EQ(run_analyze(dir), 0) << slurp(dir.string() + "-out.log");
      ++analyzed;
    }
  }
  EXPECT_EQ(analyzed, 12);
}

TEST(CollectCrashStates, ALogLeftWithoutAHeaderByAnEarlierVersionIsRepaired) {
  // The study: a crash left logs/P1.csv empty, the old server then appended rounds to it
  // without a header, and every restart refused the file. Now the header is put back.
  const fs::path dir = fresh_dir("headerless");
  {
    Study s(dir, fast_settings());
    s.join("P1");
    for (int i = 0; i < 5; ++i) {
      const Round r = s.start_round("P1");
      s.submit_round("P1", r.kind, r.iteration, valid_trace(r, 0.8, r.iteration % 2));
    }
  }
  const fs::path log = dir / "logs" / "P1.csv";
  const std::string good = slurp(log);
  const std::string header = good.substr(0, good.find('\n') + 1);
  const std::string broken = good.substr(header.size()) + "P1,adaptive,4,x";  // and a cut tail
  { std::ofstream(log, std::ios::binary | std::ios::trunc) << broken; }
  {
    Study s(dir, fast_settings());
    EXPECT_EQ(s.status("P1")->rounds_saved, 3);
    EXPECT_EQ(slurp(log), good);
    bool kept = false;
    for (const auto& e : fs::directory_iterator(dir / "collect" / "damaged"))
      kept = kept || slurp(e.path()) == broken;
    EXPECT_TRUE(kept);
    finish_everyone(s, "P2");
  }
  EXPECT_NO_THROW(Study(dir, fast_settings()));
  EXPECT_EQ(run_analyze(dir), 0) << slurp(dir.string() + "-out.log");
}

}  // namespace
}  // namespace feint::collect
