// The server never waits for a disk: with a slow sync (a test hook pauses before every group's
// fdatasync), page GETs and requests that write nothing are answered while saves wait; saves that
// arrive together share one sync, whatever the number of server threads; one participant's
// requests still run one after another; new participants are numbered in order of arrival.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <future>
#include <thread>

#include "collect_helpers.hpp"
#include "http_helpers.hpp"
#include "feint/collect/server.hpp"
#include "feint/io/csv.hpp"
#include "feint/io/number.hpp"

namespace feint::collect {
namespace {

namespace fs = std::filesystem;
namespace http = boost::beast::http;
using namespace testing;
using namespace std::chrono_literals;

struct Serving {
  Study study;
  Server server;
  std::thread thread;
  Serving(const fs::path& dir, unsigned threads) : study(dir, fast_settings()), server(study, opts(threads)) {
    thread = std::thread([this] { server.run(); });
  }
  ~Serving() {
    server.stop();
    thread.join();
  }
  static ServerOptions opts(unsigned threads) {
    ServerOptions o;
    o.port = 0;
    o.admin_token = "tok";
    o.threads = threads;
    return o;
  }
  unsigned short port() const { return server.port(); }
};

TEST(CollectAsync, ASlowSyncBlocksNeitherPagesNorOtherParticipants) {
  const auto dir = fresh_dir("slowsync");
  Serving s(dir, 2);
  for (int i = 0; i < 6; ++i) s.study.join("S" + std::to_string(i));
  s.study.join("Other");
  std::vector<std::string> bodies;
  for (int i = 0; i < 6; ++i)
    bodies.push_back(trace_body(valid_trace(s.study.start_round("S" + std::to_string(i)), 0.8)));
  // From now on every sync takes 1.5 s. Six saves at once: three times the two server threads.
  s.study.set_sync_delay(1500ms);
  std::vector<std::future<HttpReply>> saves;
  for (int i = 0; i < 6; ++i)
    saves.push_back(std::async(std::launch::async, [&, i] {
      return request(s.port(), http::verb::post,
                     "/api/round/submit?participant=S" + std::to_string(i) +
                         "&kind=practice&iteration=1",
                     bodies[static_cast<std::size_t>(i)]);
    }));
  std::this_thread::sleep_for(200ms);  // the saves are in, waiting for their sync
  // The page, the admin page and another participant's round (which writes nothing that it must
  // wait for) are answered while the saves still wait.
  EXPECT_EQ(request(s.port(), http::verb::get, "/").status, 200);
  EXPECT_EQ(request(s.port(), http::verb::get, "/game.js").status, 200);
  EXPECT_EQ(request(s.port(), http::verb::get, "/api/admin?token=tok").status, 200);
  const auto other = request(s.port(), http::verb::post, "/api/round/start?participant=Other");
  EXPECT_EQ(other.status, 200) << other.body;
  int waiting = 0;
  for (auto& f : saves)
    if (f.wait_for(0ms) != std::future_status::ready) ++waiting;
  EXPECT_EQ(waiting, 6) << "a save was answered before its sync";
  for (auto& f : saves) {
    const auto r = f.get();
    EXPECT_EQ(r.status, 200) << r.body;
  }
  s.study.set_sync_delay(0ms);
  for (int i = 0; i < 6; ++i) EXPECT_EQ(s.study.status("S" + std::to_string(i))->practice_saved, 1);
}

TEST(CollectAsync, SavesArrivingTogetherShareOneSyncWhateverTheThreadCount) {
  const auto dir = fresh_dir("onesync");
  Serving s(dir, 1);
  constexpr int kN = 40;
  std::vector<std::string> bodies;
  for (int i = 0; i < kN; ++i) {
    s.study.join("T" + std::to_string(i));
    bodies.push_back(trace_body(valid_trace(s.study.start_round("T" + std::to_string(i)), 0.8)));
  }
  s.study.record_event("", "test", "synced after the round_shown lines before it");
  s.study.set_sync_delay(300ms);
  const auto before = s.study.commit_stats();
  std::vector<std::future<int>> saves;
  for (int i = 0; i < kN; ++i)
    saves.push_back(std::async(std::launch::async, [&, i] {
      return request(s.port(), http::verb::post,
                     "/api/round/submit?participant=T" + std::to_string(i) +
                         "&kind=practice&iteration=1",
                     bodies[static_cast<std::size_t>(i)])
          .status;
    }));
  for (auto& f : saves) EXPECT_EQ(f.get(), 200);
  const auto after = s.study.commit_stats();
  // 40 rounds (each its rows and its `saved` line) on one server thread: the first group may hold
  // the first arrivals only, the rest arrive during its 300 ms sync and share the next one. A
  // server whose threads wait for the sync would need a sync per round here.
  EXPECT_EQ(after.appends - before.appends, 2u * kN);
  EXPECT_LE(after.syncs - before.syncs, 4u);
  for (int i = 0; i < kN; ++i) EXPECT_EQ(s.study.status("T" + std::to_string(i))->practice_saved, 1);
}

TEST(CollectAsync, OneParticipantsRequestsRunOneAfterAnother) {
  const auto dir = fresh_dir("serial");
  Study study(dir, fast_settings());
  study.join("D1");
  const Round r = study.start_round("D1");
  const auto trace = valid_trace(r, 0.8);
  study.set_sync_delay(200ms);
  // A double click: the same round twice, and a round start, before the first save is synced.
  std::promise<int> first, second;
  std::promise<int> next_round;
  auto code = [](std::exception_ptr e) {
    if (!e) return 200;
    try {
      std::rethrow_exception(e);
    } catch (const Rejection& x) {
      return x.status();
    } catch (...) {
      return 503;
    }
  };
  study.submit_round("D1", r.kind, r.iteration, trace,
                     [&](std::exception_ptr e, ParticipantStatus) { first.set_value(code(e)); });
  study.submit_round("D1", r.kind, r.iteration, trace,
                     [&](std::exception_ptr e, ParticipantStatus) { second.set_value(code(e)); });
  study.start_round("D1", [&](std::exception_ptr e, Round n) {
    next_round.set_value(e ? -1 : n.iteration);
  });
  EXPECT_EQ(first.get_future().get(), 200);
  EXPECT_EQ(second.get_future().get(), 409);  // duplicate: it waited for the first save
  EXPECT_EQ(next_round.get_future().get(), 2);  // the round after the saved one
  study.set_sync_delay(0ms);
  const auto log = lines(slurp(dir / "practice" / "D1.csv"));
  EXPECT_EQ(log.size(), 1 + trace.size());  // the header and the round once
}

TEST(CollectAsync, ParticipantsJoiningTogetherAreNumberedInOrderInOneBatch) {
  const auto dir = fresh_dir("joins");
  Study study(dir, fast_settings());
  study.set_sync_delay(200ms);
  const auto before = study.commit_stats();
  constexpr int kN = 30;
  std::vector<std::promise<std::string>> done(kN);
  std::promise<std::string> dup;
  for (int i = 0; i < kN; ++i) {
    study.join("J" + std::to_string(i), [&, i](std::exception_ptr e, ParticipantStatus st) {
      done[static_cast<std::size_t>(i)].set_value(e ? "error" : st.id);
    });
    if (i == 10)  // a double click: answered with the same row
      study.join("J10", [&](std::exception_ptr e, ParticipantStatus st) {
        dup.set_value(e ? "error" : st.id);
      });
  }
  for (int i = 0; i < kN; ++i)
    EXPECT_EQ(done[static_cast<std::size_t>(i)].get_future().get(), "J" + std::to_string(i));
  EXPECT_EQ(dup.get_future().get(), "J10");
  // The first join is assigned alone (nothing was in flight); the 29 that came during its sync
  // share the next one.
  EXPECT_LE(study.commit_stats().syncs - before.syncs, 2u);
  study.set_sync_delay(0ms);
  const auto rows = lines(slurp(dir / "collect" / "assignment.csv"));
  ASSERT_EQ(rows.size(), 1u + kN);
  for (int i = 0; i < kN; ++i) {
    const auto f = io::split_csv_line(rows[static_cast<std::size_t>(i) + 1], ',');
    EXPECT_EQ(f[0], "J" + std::to_string(i));
    EXPECT_EQ(f[1], std::to_string(i));
  }
  Study again(dir, fast_settings());  // the rebuild accepts the numbering
  EXPECT_EQ(again.overview().size(), static_cast<std::size_t>(kN));
}

// With four connection threads, a run of connections (GETs, then a save) is answered, and stop()
// from another thread ends run() (every thread returns).
TEST(CollectAsync, FourConnectionThreadsServeAndStopEndsThemAll) {
  const auto dir = fresh_dir("iocs");
  Study study(dir, fast_settings());
  Server server(study, Serving::opts(4));
  std::thread thread([&] { server.run(); });
  study.join("T");
  const std::string body = trace_body(valid_trace(study.start_round("T"), 0.8));
  // Twelve connections, one after another.
  for (int i = 0; i < 11; ++i) {
    const auto r = request(server.port(), http::verb::get, i % 2 ? "/game.js" : "/");
    EXPECT_EQ(r.status, 200) << "request " << i << ": " << r.body;
  }
  const auto saved = request(server.port(), http::verb::post,
                             "/api/round/submit?participant=T&kind=practice&iteration=1", body);
  EXPECT_EQ(saved.status, 200) << saved.body;
  EXPECT_NE(saved.body.find("\"practice_saved\":1"), std::string::npos) << saved.body;
  auto stopped = std::async(std::launch::async, [&] {
    server.stop();
    thread.join();
  });
  EXPECT_EQ(stopped.wait_for(10s), std::future_status::ready) << "run() did not return after stop()";
}

}  // namespace
}  // namespace feint::collect
