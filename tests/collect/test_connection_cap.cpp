// feint collect at its connection cap (docs/collect.md, Security, "Connections and file
// descriptors"): the real binary with a descriptor limit of 1 024 and 1 000 connections that send
// nothing or half a header still serves a participant within 5 s and stays idle; an upload in
// progress is never the connection closed to make room; a --max-connections the descriptors cannot
// hold is lowered. Before, new people waited in the listen queue until the 30 s request timeout
// closed an idle connection.
//
// FEINT_COLLECT_EXE=PATH runs the tests against another feint binary (e.g. a build before this
// defence, to see them fail).
#include <fcntl.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/resource.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/write.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <memory>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "collect_helpers.hpp"
#include "http_helpers.hpp"

namespace feint::collect {
namespace {

namespace fs = std::filesystem;
namespace beast = boost::beast;
namespace http = beast::http;
namespace net = boost::asio;
using tcp = net::ip::tcp;
using Clock = std::chrono::steady_clock;
using namespace testing;

const char* exe() {
  const char* other = std::getenv("FEINT_COLLECT_EXE");
  return other && *other ? other : FEINT_EXE;
}

/// `feint collect DIR` in a child process with RLIMIT_NOFILE `nofile` (soft and hard); killed with
/// SIGTERM at the end of the test, however it ends.
struct Child {
  pid_t pid = -1;
  unsigned short port = 0;
  fs::path dir, out, err;
  Child(const fs::path& study, rlim_t nofile, std::vector<std::string> extra = {}) : dir(study) {
    out = dir.parent_path() / (dir.filename().string() + ".stdout");
    err = dir.parent_path() / (dir.filename().string() + ".stderr");
    std::vector<std::string> args{exe(), "collect",       dir.string(), "--port",
                                  "0",   "--admin-token", "tok",        "--robot-speed",
                                  "8",   "--iterations",  "6",          "--threads",
                                  "4"};
    args.insert(args.end(), extra.begin(), extra.end());
    // Made before fork(): the child only calls async-signal-safe functions.
    std::vector<char*> argv;
    for (auto& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    pid = ::fork();
    if (pid == 0) {
      const rlimit rl{nofile, nofile};
      ::setrlimit(RLIMIT_NOFILE, &rl);
      const int o = ::open(out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
      const int e = ::open(err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
      ::dup2(o, 1);
      ::dup2(e, 2);
      for (int fd = 3; fd < 4096; ++fd) ::close(fd);  // none of the test's sockets
      ::execv(argv[0], argv.data());
      ::_exit(127);
    }
    for (int i = 0; i < 400 && port == 0; ++i) {
      std::this_thread::sleep_for(std::chrono::milliseconds(25));
      for (const auto& l : lines(slurp(out)))
        if (l.rfind("port: ", 0) == 0) port = static_cast<unsigned short>(std::stoi(l.substr(6)));
    }
  }
  ~Child() { stop(); }
  void stop() {
    if (pid <= 0) return;
    ::kill(pid, SIGTERM);
    int status = 0;
    ::waitpid(pid, &status, 0);
    pid = -1;
  }
  double cpu_seconds() const {
    const std::string stat = slurp("/proc/" + std::to_string(pid) + "/stat");
    std::istringstream in(stat.substr(stat.rfind(')') + 2));
    std::string f;
    long utime = 0, stime = 0;
    for (int i = 3; i <= 15 && in >> f; ++i) {
      if (i == 14) utime = std::stol(f);
      if (i == 15) stime = std::stol(f);
    }
    return static_cast<double>(utime + stime) / static_cast<double>(::sysconf(_SC_CLK_TCK));
  }
};

/// A browser's kept-alive connection: everything it asks must be answered before `deadline`
/// (a request not answered by then gives status 0 and the error's text).
struct Browser {
  net::io_context ioc;
  beast::tcp_stream stream{ioc};
  beast::flat_buffer buf;
  Clock::time_point deadline;
  beast::error_code failed;
  Browser(unsigned short port, Clock::time_point until) : deadline(until) {
    stream.expires_at(deadline);
    stream.async_connect(tcp::endpoint(net::ip::make_address("127.0.0.1"), port),
                         [this](beast::error_code ec) { failed = ec; });
    ioc.run();
  }
  HttpReply ask(http::verb method, const std::string& target, const std::string& body = "") {
    if (failed) return {0, failed.message()};
    auto req = std::make_shared<http::request<http::string_body>>(method, target, 11);
    req->set(http::field::host, "127.0.0.1");
    req->keep_alive(true);
    req->body() = body;
    req->prepare_payload();
    return exchange([this, req](auto then) { http::async_write(stream, *req, then); });
  }
  /// Sends the bytes of a request by `write` (e.g. slowly, in pieces) and reads the answer.
  template <class Write>
  HttpReply exchange(Write write) {
    http::response<http::string_body> res;
    beast::error_code result;
    stream.expires_at(deadline);
    write([&](beast::error_code ec, std::size_t) {
      if (ec) {
        result = ec;
        return;
      }
      http::async_read(stream, buf, res, [&](beast::error_code e, std::size_t) { result = e; });
    });
    ioc.restart();
    ioc.run();
    if (result) return {0, result.message()};
    return {static_cast<int>(res.result_int()), res.body()};
  }
};

/// The round's duration, as the server wrote it in the answer of /api/round/start.
double duration_of(const std::string& round_json) {
  const auto at = round_json.find("\"duration\":");
  return at == std::string::npos ? 0.0 : std::stod(round_json.substr(at + 11));
}

/// The body of a round a person could have played (tests' valid_trace) for the round answered.
std::string round_body(const std::string& round_json) {
  Round r;
  r.path.push_back({});
  r.path.back().t = duration_of(round_json);
  return trace_body(valid_trace(r, 0.8));
}

/// `n` connections to 127.0.0.1:`port` that send nothing (even ones) or the first line of a
/// request and one header, never ending it (odd ones).
std::vector<int> idle_connections(unsigned short port, int n) {
  std::vector<int> fds;
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_port = htons(port);
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  static const char partial[] = "POST /api/join?participant=X HTTP/1.1\r\nHost: 127.0.0.1\r\n";
  for (int i = 0; i < n; ++i) {
    const int fd = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
    if (fd < 0) break;
    if (::connect(fd, reinterpret_cast<const sockaddr*>(&a), sizeof a) != 0) {
      ::close(fd);
      break;
    }
    if (i % 2 == 1 && ::write(fd, partial, sizeof partial - 1) < 0) {
      ::close(fd);
      break;
    }
    fds.push_back(fd);
  }
  return fds;
}

struct Closer {
  std::vector<int>& fds;
  ~Closer() {
    for (int fd : fds) ::close(fd);
  }
};

/// The test process needs more than 1 000 descriptors for its clients.
bool enough_descriptors(rlim_t want) {
  rlimit rl{};
  if (::getrlimit(RLIMIT_NOFILE, &rl) != 0) return false;
  if (rl.rlim_cur >= want) return true;
  if (rl.rlim_max != RLIM_INFINITY && rl.rlim_max < want) return false;
  rl.rlim_cur = want;
  return ::setrlimit(RLIMIT_NOFILE, &rl) == 0;
}

TEST(CollectConnectionCap, AParticipantIsServedWithinFiveSecondsPastAThousandIdleConnections) {
  if (!enough_descriptors(1200))
    GTEST_SKIP() << "the test needs RLIMIT_NOFILE >= 1200 (ulimit -Hn)";
  const auto dir = fresh_dir("cap");
  Child srv(dir, 1024);
  ASSERT_NE(srv.port, 0) << slurp(srv.err);
  // The cap: 1 024 descriptors less the reserve, 32 + 64 (a commit group's files) + 4 x 4 threads.
  ASSERT_NE(slurp(srv.out).find("connections: at most 912 at once"), std::string::npos)
      << slurp(srv.out);
  std::vector<int> idle = idle_connections(srv.port, 1000);
  Closer closer{idle};
  ASSERT_EQ(idle.size(), 1000u);

  // A participant arrives at once, as a browser does: the page, its script, join, the first round
  // and its save, on one kept-alive connection.
  const auto t0 = Clock::now();
  Browser p1(srv.port, t0 + std::chrono::seconds(5));
  const auto page = p1.ask(http::verb::get, "/");
  ASSERT_EQ(page.status, 200) << "the page was not served within 5 s: " << page.body;
  EXPECT_NE(page.body.find("game.js"), std::string::npos);
  EXPECT_EQ(p1.ask(http::verb::get, "/game.js").status, 200);
  const auto join = p1.ask(http::verb::post, "/api/join?participant=P1");
  ASSERT_EQ(join.status, 200) << join.body;
  const auto round = p1.ask(http::verb::post, "/api/round/start?participant=P1");
  ASSERT_EQ(round.status, 200) << round.body;
  const auto saved =
      p1.ask(http::verb::post, "/api/round/submit?participant=P1&kind=practice&iteration=1",
             round_body(round.body));
  ASSERT_EQ(saved.status, 200) << saved.body;
  EXPECT_NE(saved.body.find("\"practice_saved\":1"), std::string::npos) << saved.body;
  const double served_in = std::chrono::duration<double>(Clock::now() - t0).count();
  EXPECT_LT(served_in, 5.0);

  // Idle, with the server full of silent connections: under 30 % of a core.
  const double cpu0 = srv.cpu_seconds();
  std::this_thread::sleep_for(std::chrono::seconds(3));
  const double cpu = srv.cpu_seconds() - cpu0;
  EXPECT_LT(cpu, 0.9) << "the server used " << cpu << " s of CPU in 3 s while idle";

  // Another participant, each request on a new connection (as a proxy without keep-alive): each
  // takes the place of an idle connection.
  const auto t1 = Clock::now();
  for (const char* target : {"/api/join?participant=P2", "/api/round/start?participant=P2"}) {
    Browser b(srv.port, t1 + std::chrono::seconds(5));
    const auto r = b.ask(http::verb::post, target);
    EXPECT_EQ(r.status, 200) << target << ": " << r.body;
  }
  srv.stop();
  // The save is on disk, as acknowledged.
  EXPECT_EQ(lines(slurp(dir / "practice" / "P1.csv")).size(),
            1 + lines(round_body(round.body)).size());
  const std::string events = slurp(dir / "collect" / "events.csv");
  EXPECT_NE(events.find(",connections_capped,"), std::string::npos);
  std::printf("  participant served in %.2f s; server CPU %.2f s in 3 s idle\n", served_in, cpu);
}

TEST(CollectConnectionCap, AnUploadInProgressIsNeverTheConnectionClosedToMakeRoom) {
  const auto dir = fresh_dir("cap-upload");
  Child srv(dir, 1024, {"--max-connections", "2"});
  ASSERT_NE(srv.port, 0) << slurp(srv.err);
  ASSERT_NE(slurp(srv.out).find("connections: at most 2 at once"), std::string::npos);
  HttpReply round;
  {
    Browser b(srv.port, Clock::now() + std::chrono::seconds(5));
    ASSERT_EQ(b.ask(http::verb::post, "/api/join?participant=U1").status, 200);
    round = b.ask(http::verb::post, "/api/round/start?participant=U1");
    ASSERT_EQ(round.status, 200) << round.body;
  }
  // The round is uploaded slowly, in 8 pieces 300 ms apart, on a new connection: the oldest one
  // and, like the two silent connections that come right after its first piece, one that has had
  // no request answered. A fourth person comes at once, over the cap: the connection quiet longest
  // is then the upload's, which is sending, and must not be the one closed.
  Browser up(srv.port, Clock::now() + std::chrono::seconds(10));
  std::thread crowd;
  HttpReply late;
  double late_in = 0;
  std::vector<int> silent;
  Closer closer{silent};
  const std::string body = round_body(round.body);
  const std::string head =
      "POST /api/round/submit?participant=U1&kind=practice&iteration=1 "
      "HTTP/1.1\r\nHost: 127.0.0.1\r\nContent-Length: " +
      std::to_string(body.size()) + "\r\n\r\n";
  const auto saved = up.exchange([&](auto then) {
    beast::error_code ec;
    net::write(up.stream.socket(), net::buffer(head), ec);
    for (std::size_t i = 0, n = 8; i < n && !ec; ++i) {
      const std::size_t from = body.size() * i / n, to = body.size() * (i + 1) / n;
      net::write(up.stream.socket(), net::buffer(body.data() + from, to - from), ec);
      if (i == 0) {
        // Right after a piece: the upload's last byte is older than these connections.
        silent = idle_connections(srv.port, 2);  // one sends nothing, one half a header
        crowd = std::thread([&] {
          const auto t = Clock::now();
          Browser b(srv.port, t + std::chrono::seconds(5));
          late = b.ask(http::verb::get, "/");
          late_in = std::chrono::duration<double>(Clock::now() - t).count();
        });
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(300));
    }
    then(ec, 0);
  });
  if (crowd.joinable()) crowd.join();
  EXPECT_EQ(saved.status, 200) << "the slow upload: " << saved.body;
  EXPECT_EQ(late.status, 200) << "the person who came at the cap: " << late.body;
  EXPECT_LT(late_in, 5.0);
  srv.stop();
  EXPECT_EQ(lines(slurp(dir / "practice" / "U1.csv")).size(), 1 + lines(body).size());
}

TEST(CollectConnectionCap, AMaxConnectionsTheDescriptorsCannotHoldIsLowered) {
  const auto dir = fresh_dir("cap-clamp");
  Child srv(dir, 160, {"--max-connections", "100000"});
  ASSERT_NE(srv.port, 0) << slurp(srv.err);
  // 160 descriptors less the reserve of 112: 48 connections, not 100 000 (which would take the
  // descriptors of the study's files, then fail every accept with EMFILE).
  EXPECT_NE(slurp(srv.out).find("connections: at most 48 at once"), std::string::npos)
      << slurp(srv.out);
}

}  // namespace
}  // namespace feint::collect
