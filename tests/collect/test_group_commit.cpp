// Group commit: concurrent saves share syncs, and every acknowledged round is on disk, even when
// the server is killed (SIGKILL) in the middle of a stream of concurrent saves.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <boost/asio/ip/tcp.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <chrono>
#include <csignal>
#include <map>
#include <mutex>
#include <string>
#include <thread>

#include "collect_helpers.hpp"
#include "feint/collect/server.hpp"
#include "feint/io/number.hpp"

namespace feint::collect {
namespace {

namespace fs = std::filesystem;
namespace beast = boost::beast;
namespace http = beast::http;
namespace net = boost::asio;
using tcp = net::ip::tcp;
using namespace testing;

std::pair<int, std::string> post(tcp::socket& sock, beast::flat_buffer& buf,
                                 const std::string& target, const std::string& body) {
  http::request<http::string_body> req(http::verb::post, target, 11);
  req.set(http::field::host, "127.0.0.1");
  req.keep_alive(true);
  req.body() = body;
  req.prepare_payload();
  http::write(sock, req);
  http::response<http::string_body> res;
  http::read(sock, buf, res);
  return {static_cast<int>(res.result_int()), res.body()};
}

double field(const std::string& json, const std::string& name) {
  const auto p = json.find("\"" + name + "\":");
  return std::stod(json.substr(p + name.size() + 3));
}

// The durability bound after a SIGKILL, for one participant: every acknowledged round is on disk,
// and at most one round more (the one submit in flight at the kill: a client sends the next round
// only after the previous one is acknowledged). Counts are rounds saved/acknowledged of each kind,
// which equal the last iteration number, as iterations are saved in order from 1. Returns what is
// wrong, or "" when the bound holds.
std::string durability_violation(int practice_saved, int main_saved, int practice_acked, int main_acked) {
  if (practice_saved < practice_acked || main_saved < main_acked)
    return "an acknowledged round is missing from disk";
  const int unacknowledged = (practice_saved - practice_acked) + (main_saved - main_acked);
  if (unacknowledged > 1)
    return std::to_string(unacknowledged) + " rounds on disk were never acknowledged; at most 1 was in flight";
  return "";
}

// The bound itself: it holds for 0 or 1 unacknowledged round of either kind and fails for 2, as
// 2 main rounds with the practice counts equal, or 1 practice and 1 main round. (The previous
// check, practice * 100 + main <= acked_practice * 100 + acked_main + 100, let up to 100
// unacknowledged main rounds through.)
TEST(CollectGroupCommit, TheDurabilityBoundAllowsExactlyTheOneRoundInFlight) {
  EXPECT_EQ(durability_violation(2, 7, 2, 7), "");
  EXPECT_EQ(durability_violation(2, 8, 2, 7), "");  // the main round in flight was saved
  EXPECT_EQ(durability_violation(2, 1, 2, 0), "");  // the first main round was in flight
  EXPECT_EQ(durability_violation(2, 0, 1, 0), "");  // the last practice round was in flight
  EXPECT_NE(durability_violation(2, 9, 2, 7), "");  // 2 unacknowledged main rounds
  EXPECT_NE(durability_violation(2, 20, 2, 0), "");
  EXPECT_NE(durability_violation(2, 1, 1, 0), "");  // 1 practice + 1 main unacknowledged
  EXPECT_NE(durability_violation(2, 6, 2, 7), "");  // an acknowledged round lost
  EXPECT_NE(durability_violation(1, 7, 2, 7), "");
}

TEST(CollectGroupCommit, ConcurrentSavesShareSyncsAndAreAllDurable) {
  const auto dir = fresh_dir("group");
  Study study(dir, fast_settings());
  ServerOptions o;
  o.port = 0;
  o.threads = 16;
  Server server(study, o);
  std::thread t([&] { server.run(); });
  std::vector<std::thread> clients;
  for (int i = 0; i < 16; ++i) {
    clients.emplace_back([&, i] {
      net::io_context ioc;
      tcp::socket sock(ioc);
      sock.connect(tcp::endpoint(net::ip::make_address("127.0.0.1"), server.port()));
      beast::flat_buffer buf;
      const std::string id = "G" + std::to_string(i);
      post(sock, buf, "/api/join?participant=" + id, "");
      for (;;) {
        const auto [st, round] = post(sock, buf, "/api/round/start?participant=" + id, "");
        if (st != 200) break;
        Round r;
        r.path = {{0, 0, 0}, {field(round, "duration"), 0, 0}};
        std::string body;
        for (const auto& x : valid_trace(r, 0.8))
          body += io::format_double(x.t) + "," + io::format_double(x.pad) + "\n";
        const bool practice = round.find("\"kind\":\"practice\"") != std::string::npos;
        const auto s = post(sock, buf,
                            "/api/round/submit?participant=" + id +
                                "&kind=" + (practice ? "practice" : "main") + "&iteration=" +
                                std::to_string(static_cast<int>(field(round, "iteration"))),
                            body);
        ASSERT_EQ(s.first, 200) << s.second;
      }
    });
  }
  for (auto& c : clients) c.join();
  server.stop();
  t.join();
  const auto cs = study.commit_stats();
  // 16 participants x (join: 2 appends, 8 x (shown + round + saved)) = 16 x 26 appends; with 16
  // at once, a sync covers more than one append on average.
  EXPECT_GE(cs.appends, 16u * 26u);
  EXPECT_LT(cs.syncs, cs.appends);
  for (int i = 0; i < 16; ++i) EXPECT_EQ(study.status("G" + std::to_string(i))->rounds_saved, 6);
}

TEST(CollectGroupCommit, EveryAcknowledgedRoundSurvivesSigkillDuringConcurrentSaves) {
  const auto dir = fresh_dir("groupkill");
  const fs::path out = dir.parent_path() / (dir.filename().string() + ".stdout");
  auto launch = [&](pid_t& pid) {
    pid = ::fork();
    if (pid == 0) {
      const int fd = ::open(out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
      ::dup2(fd, 1);
      ::execl(FEINT_EXE, FEINT_EXE, "collect", dir.c_str(), "--port", "0", "--robot-speed", "8",
              "--iterations", "20", static_cast<char*>(nullptr));
      ::_exit(127);
    }
    unsigned short port = 0;
    for (int i = 0; i < 200 && port == 0; ++i) {
      std::this_thread::sleep_for(std::chrono::milliseconds(25));
      for (const auto& l : lines(slurp(out)))
        if (l.rfind("port: ", 0) == 0) port = static_cast<unsigned short>(std::stoi(l.substr(6)));
    }
    return port;
  };
  pid_t pid = -1;
  const unsigned short port = launch(pid);
  ASSERT_NE(port, 0);
  std::mutex mu;
  std::map<std::string, std::pair<int, int>> acked;  // participant -> (practice, main) acknowledged
  std::atomic<bool> killed{false};
  std::vector<std::thread> clients;
  for (int i = 0; i < 24; ++i) {
    clients.emplace_back([&, i] {
      const std::string id = "K" + std::to_string(i);
      try {
        net::io_context ioc;
        tcp::socket sock(ioc);
        sock.connect(tcp::endpoint(net::ip::make_address("127.0.0.1"), port));
        beast::flat_buffer buf;
        post(sock, buf, "/api/join?participant=" + id, "");
        while (!killed) {
          const auto [st, round] = post(sock, buf, "/api/round/start?participant=" + id, "");
          if (st != 200) break;
          Round r;
          r.path = {{0, 0, 0}, {field(round, "duration"), 0, 0}};
          std::string body;
          for (const auto& x : valid_trace(r, 0.8))
            body += io::format_double(x.t) + "," + io::format_double(x.pad) + "\n";
          const bool practice = round.find("\"kind\":\"practice\"") != std::string::npos;
          const int it = static_cast<int>(field(round, "iteration"));
          const auto s = post(sock, buf,
                              "/api/round/submit?participant=" + id +
                                  "&kind=" + (practice ? "practice" : "main") +
                                  "&iteration=" + std::to_string(it),
                              body);
          if (s.first != 200) break;
          std::lock_guard lock(mu);
          (practice ? acked[id].first : acked[id].second) = it;
        }
      } catch (const std::exception&) {
        // the server was killed under this client's feet
      }
    });
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(700));
  ::kill(pid, SIGKILL);
  killed = true;
  int status = 0;
  ::waitpid(pid, &status, 0);
  for (auto& c : clients) c.join();
  int total = 0;
  Settings s = fast_settings();
  s.iterations = 20;
  Study after(dir, s);  // the rebuild after the crash, from the files alone
  for (int i = 0; i < 24; ++i) {
    const std::string id = "K" + std::to_string(i);
    const auto f = acked.find(id);
    const std::pair<int, int> a = f == acked.end() ? std::make_pair(0, 0) : f->second;
    const auto st = after.status(id);
    if (f != acked.end()) {
      ASSERT_TRUE(st) << id;
    }
    if (!st) continue;  // its join was never made durable: nothing of it was acknowledged
    // Every acknowledged round is on disk, and at most the one round in flight at the kill is on
    // disk without its acknowledgement.
    EXPECT_EQ(durability_violation(st->practice_saved, st->rounds_saved, a.first, a.second), "")
        << id << ": on disk " << st->practice_saved << " practice + " << st->rounds_saved
        << " main rounds, acknowledged " << a.first << " + " << a.second;
    total += a.first + a.second;
  }
  EXPECT_GT(total, 24) << "too few rounds were acknowledged before the kill to test anything";
}

}  // namespace
}  // namespace feint::collect
