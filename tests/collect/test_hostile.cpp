// feint collect against hostile clients and a hostile machine: bounded, rate-limited events log;
// the Host check (DNS rebinding); X-Forwarded-For only from a trusted proxy; out of file
// descriptors (no spinning, participants still served); a full disk (503 "could not save", the
// admin page's red banner, nothing acknowledged that is not on disk, recovery once there is room).
#include <fcntl.h>
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <boost/asio/ip/tcp.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <chrono>
#include <csignal>
#include <memory>
#include <thread>

#include "collect_helpers.hpp"
#include "feint/collect/server.hpp"
#include "feint/io/csv.hpp"
#include "feint/io/number.hpp"

namespace feint::collect {
namespace {

namespace fs = std::filesystem;
namespace beast = boost::beast;
namespace http = beast::http;
namespace net = boost::asio;
using tcp = net::ip::tcp;
using namespace testing;

/// A keep-alive HTTP/1.1 client on 127.0.0.1.
struct Conn {
  net::io_context ioc;
  tcp::socket sock{ioc};
  beast::flat_buffer buf;
  explicit Conn(unsigned short port) {
    sock.connect(tcp::endpoint(net::ip::make_address("127.0.0.1"), port));
  }
  std::pair<int, std::string> send(http::verb method, const std::string& target,
                                   const std::string& body = "", const std::string& host = "127.0.0.1",
                                   const std::string& xff = "") {
    http::request<http::string_body> req(method, target, 11);
    if (host != "none") req.set(http::field::host, host);
    if (!xff.empty()) req.set("X-Forwarded-For", xff);
    req.keep_alive(true);
    req.body() = body;
    req.prepare_payload();
    http::write(sock, req);
    http::response<http::string_body> res;
    http::read(sock, buf, res);
    return {static_cast<int>(res.result_int()), res.body()};
  }
};

struct InProcess {
  Study study;
  Server server;
  std::thread thread;
  InProcess(const fs::path& dir, ServerOptions o)
      : study(dir, fast_settings()), server(study, std::move(o)) {
    thread = std::thread([this] { server.run(); });
  }
  ~InProcess() {
    server.stop();
    thread.join();
  }
  unsigned short port() const { return server.port(); }
};

ServerOptions options() {
  ServerOptions o;
  o.port = 0;
  o.admin_token = "tok";
  o.threads = 2;
  return o;
}

std::string trace_body(const std::vector<PadSample>& s) {
  std::string b;
  for (const auto& x : s) b += io::format_double(x.t) + "," + io::format_double(x.pad) + "\n";
  return b;
}

int count(const std::string& text, const std::string& what) {
  int n = 0;
  for (auto p = text.find(what); p != std::string::npos; p = text.find(what, p + 1)) ++n;
  return n;
}

// ---- 2. the events log: bounded lines, rate-limited rejections ----

TEST(CollectEventsLog, AHugeDetailBecomesOneBoundedLine) {
  const auto dir = fresh_dir("bounded");
  Study study(dir, fast_settings());
  study.record_event("", "test", "first line");
  std::string huge = "\"quoted\",\nnew line\r\x01";
  huge += std::string(1 << 20, 'A');
  const auto before = fs::file_size(dir / "collect" / "events.csv");
  study.record_event("P1", "rejected", huge);
  const auto text = slurp(dir / "collect" / "events.csv");
  const std::string line = text.substr(before);
  EXPECT_LE(line.size(), 512u);
  EXPECT_EQ(std::count(line.begin(), line.end(), '\n'), 1);
  EXPECT_NE(line.find("[1048596 bytes in all]"), std::string::npos) << line;
  EXPECT_NE(line.find("'quoted'"), std::string::npos) << line;
}

TEST(CollectEventsLog, ManyOversizedRequestsFromOneClientAddABoundedNumberOfBytes) {
  const auto dir = fresh_dir("ratelimit");
  ServerOptions o = options();
  o.rejections_per_minute = 10;
  InProcess srv(dir, o);
  Conn c(srv.port());
  ASSERT_EQ(c.send(http::verb::post, "/api/join?participant=R1").first, 200);
  const auto events = dir / "collect" / "events.csv";
  const auto before = fs::file_size(events);
  // A field given twice, 100 kB each: the refusal's message names the field (the 1 MB
  // lines). 60 requests, 12 MB sent over loopback.
  const std::string key(100 * 1024, 'k');
  for (int i = 0; i < 60; ++i) {
    const auto r = c.send(http::verb::post, "/api/questionnaire?participant=R1",
                          key + "=1&" + key + "=2");
    ASSERT_EQ(r.first, 400);
  }
  // And requests over the body limit, refused while being read.
  for (int i = 0; i < 3; ++i) {
    Conn big(srv.port());
    try {
      EXPECT_EQ(big.send(http::verb::post, "/api/round/submit?participant=R1&kind=main&iteration=1",
                         std::string(3 * 1024 * 1024, '1'))
                    .first,
                413);
    } catch (const std::exception&) {
      // The server answered 413 and closed while the body was still being sent (broken pipe).
    }
  }
  const auto text = slurp(events);
  const auto added = fs::file_size(events) - before;
  // At most 10 rejected lines per minute (the test may straddle a minute: twice that), plus the
  // rate_limited lines; each line under 512 bytes.
  EXPECT_LE(added, (2 * 10 + 4) * 512u) << added;
  for (const auto& l : lines(text)) EXPECT_LT(l.size(), 512u);
  EXPECT_GE(count(text, ",rate_limited,"), 1);
  EXPECT_LE(count(text, ",rejected,"), 20 + 3);
  EXPECT_NE(text.find("from 127.0.0.1: POST /api/questionnaire 400 malformed"), std::string::npos);
}

// ---- 5. Host header check; X-Forwarded-For from a trusted proxy only ----

TEST(CollectHost, HostNamesAndForwardedAddressesAreParsedStrictly) {
  const std::vector<std::string> allowed{"localhost", "study.example.org:443", "[::1]:8080"};
  EXPECT_TRUE(host_allowed(allowed, "localhost"));
  EXPECT_TRUE(host_allowed(allowed, "LOCALHOST:8080"));
  EXPECT_TRUE(host_allowed(allowed, "study.example.org:443"));
  EXPECT_TRUE(host_allowed(allowed, "study.example.org"));
  EXPECT_FALSE(host_allowed(allowed, "study.example.org:8443"));
  EXPECT_TRUE(host_allowed(allowed, "[::1]:8080"));
  EXPECT_FALSE(host_allowed(allowed, "[::1]:9090"));
  EXPECT_FALSE(host_allowed(allowed, "evil.example:8080"));
  EXPECT_FALSE(host_allowed(allowed, "localhost.evil.example"));
  EXPECT_FALSE(host_allowed(allowed, ""));
  const std::vector<std::string> proxies{"127.0.0.1", "10.0.0.2"};
  EXPECT_EQ(client_address("127.0.0.1", "203.0.113.9", proxies), "203.0.113.9");
  EXPECT_EQ(client_address("127.0.0.1", "1.1.1.1, 203.0.113.9", proxies), "203.0.113.9");
  EXPECT_EQ(client_address("127.0.0.1", "203.0.113.9, 10.0.0.2", proxies), "203.0.113.9");
  EXPECT_EQ(client_address("127.0.0.1", "not-an-address", proxies), "127.0.0.1");
  EXPECT_EQ(client_address("127.0.0.1", "", proxies), "127.0.0.1");
  EXPECT_EQ(client_address("192.0.2.1", "203.0.113.9", proxies), "192.0.2.1");  // not trusted
}

TEST(CollectHost, OnLoopbackOnlyTheLoopbackNamesAndTheAllowedHostsAreServed) {
  const auto dir = fresh_dir("host");
  ServerOptions o = options();
  o.allowed_hosts = {"study.example.org"};
  InProcess srv(dir, o);
  const std::string port = std::to_string(srv.port());
  for (const std::string& h : {"localhost:" + port, "127.0.0.1:" + port, "[::1]:" + port,
                              std::string("127.0.0.1"), std::string("Study.Example.org")}) {
    Conn c(srv.port());
    EXPECT_EQ(c.send(http::verb::get, "/", "", h).first, 200) << h;
  }
  for (const std::string& h : {"evil.example:" + port, "localhost.evil.example:" + port,
                              "127.0.0.1.nip.io:" + port}) {
    Conn c(srv.port());
    const auto r = c.send(http::verb::post, "/api/join?participant=H1", "", h);
    EXPECT_EQ(r.first, 421) << h;
    EXPECT_NE(r.second.find("DNS rebinding"), std::string::npos);
    EXPECT_NE(r.second.find("--allowed-host"), std::string::npos);
  }
  {
    Conn c(srv.port());
    EXPECT_EQ(c.send(http::verb::get, "/", "", "none").first, 421);  // no Host header at all
  }
  EXPECT_FALSE(srv.study.status("H1"));  // nothing was done for the refused requests
  EXPECT_NE(slurp(dir / "collect" / "events.csv").find("421 bad_host: Host 'evil.example:"),
            std::string::npos);
}

TEST(CollectHost, XForwardedForIsBelievedOnlyFromATrustedProxy) {
  const auto dir = fresh_dir("xff");
  {
    InProcess srv(dir, options());  // no trusted proxy
    Conn c(srv.port());
    EXPECT_EQ(c.send(http::verb::post, "/api/join?participant=X1", "", "127.0.0.1",
                     "203.0.113.9")
                  .first,
              200);
  }
  {
    ServerOptions o = options();
    o.trusted_proxies = {"127.0.0.1"};
    InProcess srv(dir, o);
    Conn c(srv.port());
    EXPECT_EQ(c.send(http::verb::post, "/api/join?participant=X2", "", "127.0.0.1",
                     "198.51.100.1, 203.0.113.7")
                  .first,
              200);
  }
  const auto text = slurp(dir / "collect" / "events.csv");
  EXPECT_NE(text.find(",X1,joined,from 127.0.0.1"), std::string::npos) << text;
  EXPECT_NE(text.find(",X2,joined,from 203.0.113.7"), std::string::npos) << text;
}

// ---- 3. out of file descriptors ----

struct Child {
  pid_t pid = -1;
  unsigned short port = 0;
  fs::path out, err;
};

Child launch_limited(const fs::path& dir, rlim_t nofile) {
  Child c;
  c.out = dir.parent_path() / (dir.filename().string() + ".stdout");
  c.err = dir.parent_path() / (dir.filename().string() + ".stderr");
  c.pid = ::fork();
  if (c.pid == 0) {
    const rlimit rl{nofile, nofile};
    ::setrlimit(RLIMIT_NOFILE, &rl);
    const int o = ::open(c.out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int e = ::open(c.err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    ::dup2(o, 1);
    ::dup2(e, 2);
    ::execl(FEINT_EXE, FEINT_EXE, "collect", dir.c_str(), "--port", "0", "--admin-token", "tok",
            "--robot-speed", "8", "--iterations", "6", "--threads", "4",
            static_cast<char*>(nullptr));
    ::_exit(127);
  }
  for (int i = 0; i < 200 && c.port == 0; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(25));
    for (const auto& l : lines(slurp(c.out)))
      if (l.rfind("port: ", 0) == 0) c.port = static_cast<unsigned short>(std::stoi(l.substr(6)));
  }
  return c;
}

double cpu_seconds(pid_t pid) {
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

TEST(CollectDescriptors, ManyIdleConnectionsNeitherSpinNorLockOutParticipants) {
  const auto dir = fresh_dir("fds");
  Child srv = launch_limited(dir, 160);
  ASSERT_NE(srv.port, 0) << slurp(srv.err);
  EXPECT_NE(slurp(srv.out).find("connections: at most 48 at once"), std::string::npos)
      << slurp(srv.out);
  // A participant in the study, on a kept-alive connection, as a browser has.
  auto participant = std::make_unique<Conn>(srv.port);
  ASSERT_EQ(participant->send(http::verb::post, "/api/join?participant=F1", "", "127.0.0.1").first,
            200);
  // 300 connections that send nothing: more than the 160 descriptors the server has.
  std::vector<std::unique_ptr<tcp::socket>> idle;
  net::io_context ioc;
  for (int i = 0; i < 300; ++i) {
    idle.push_back(std::make_unique<tcp::socket>(ioc));
    idle.back()->connect(tcp::endpoint(net::ip::make_address("127.0.0.1"), srv.port));
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  const double cpu0 = cpu_seconds(srv.pid);
  std::this_thread::sleep_for(std::chrono::seconds(3));
  const double cpu = cpu_seconds(srv.pid) - cpu0;
  EXPECT_LT(cpu, 0.3) << "the server used " << cpu << " s of CPU in 3 s while idle";
  // The participant is still served, and can save a round.
  const auto start = participant->send(http::verb::post, "/api/round/start?participant=F1", "",
                                       "127.0.0.1");
  ASSERT_EQ(start.first, 200) << start.second;
  // Once the idle connections go, a new participant gets in.
  idle.clear();
  Conn late(srv.port);
  EXPECT_EQ(late.send(http::verb::post, "/api/join?participant=F2", "", "127.0.0.1").first, 200);
  ::kill(srv.pid, SIGTERM);
  int status = 0;
  ::waitpid(srv.pid, &status, 0);
  // The condition is logged once (stderr and events log), not once per connection.
  EXPECT_EQ(count(slurp(srv.err), "connections (the cap)"), 1) << slurp(srv.err);
  EXPECT_EQ(count(slurp(dir / "collect" / "events.csv"), ",connections_capped,"), 1);
}

// ---- 6. a full disk ----

TEST(CollectFullDisk, NothingUnsavedIsAcknowledgedTheAdminSeesItAndItRecovers) {
  const auto dir = fresh_dir("fulldisk");
  Study study(dir, fast_settings());
  ServerState state;
  const RequestInfo info{"127.0.0.1", &state};
  auto post = [&](const std::string& t, const std::string& b = "") {
    return handle_request(study, "tok", "POST", t, b, info);
  };
  ASSERT_EQ(post("/api/join?participant=D1").status, 200);
  Round r;
  auto submit = [&] {
    return post(fmt::format("/api/round/submit?participant=D1&kind={}&iteration={}",
                            to_string(r.kind), r.iteration),
                trace_body(valid_trace(r, 0.8)));
  };
  r = study.start_round("D1");
  ASSERT_EQ(submit().status, 200);
  r = study.start_round("D1");
  const fs::path log = dir / "practice" / "D1.csv";
  const std::string saved = slurp(log);
  // The disk is "full": no file may grow past its size now (RLIMIT_FSIZE; SIGXFSZ ignored, so a
  // write fails with EFBIG, as ENOSPC on a full disk).
  rlimit old{};
  ASSERT_EQ(::getrlimit(RLIMIT_FSIZE, &old), 0);
  const auto prev = std::signal(SIGXFSZ, SIG_IGN);
  rlimit tight = old;
  tight.rlim_cur = saved.size() + 300;  // half a round fits: a partial write happens
  ASSERT_EQ(::setrlimit(RLIMIT_FSIZE, &tight), 0);
  const Response failed = submit();
  const Response again = submit();
  ASSERT_EQ(::setrlimit(RLIMIT_FSIZE, &old), 0);
  std::signal(SIGXFSZ, prev);
  EXPECT_EQ(failed.status, 503);
  EXPECT_EQ(again.status, 503);
  EXPECT_NE(failed.body.find("could not save, please wait"), std::string::npos) << failed.body;
  EXPECT_EQ(failed.body.find(dir.string()), std::string::npos);  // no server paths to participants
  EXPECT_EQ(slurp(log), saved);  // not a byte of the unacknowledged round is left
  EXPECT_EQ(study.status("D1")->practice_saved, 1);
  const auto admin = handle_request(study, "tok", "GET", "/admin?token=tok", "", info);
  EXPECT_NE(admin.body.find("id=\"write-failure\""), std::string::npos);
  EXPECT_NE(admin.body.find("(2 attempts)"), std::string::npos);
  EXPECT_NE(handle_request(study, "tok", "GET", "/api/admin?token=tok", "", info)
                .body.find("\"write_failure\":{\"since\""),
            std::string::npos);
  // Room again: the page's retry saves the round; the banner goes; nothing was lost or doubled.
  ASSERT_EQ(submit().status, 200);
  EXPECT_EQ(handle_request(study, "tok", "GET", "/admin?token=tok", "", info)
                .body.find("write-failure"),
            std::string::npos);
  const auto rows = lines(slurp(log));
  EXPECT_EQ(slurp(log).substr(0, saved.size()), saved);
  EXPECT_EQ(io::split_csv_line(rows.back())[2], "2");
  EXPECT_FALSE(fs::exists(dir / "collect" / "damaged"));
  Study reopened(dir, fast_settings());
  EXPECT_EQ(reopened.status("D1")->practice_saved, 2);
}

}  // namespace
}  // namespace feint::collect
