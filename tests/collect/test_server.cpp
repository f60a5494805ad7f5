// feint collect over HTTP: routes, rejections (all recorded), limits, and the real binary killed
// and restarted mid-study, then `feint analyze` and `feint score` on the result.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <boost/asio/connect.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <chrono>
#include <csignal>
#include <thread>

#include "collect_helpers.hpp"
#include "http_helpers.hpp"
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

int count(const std::string& text, const std::string& what) {
  int n = 0;
  for (auto p = text.find(what); p != std::string::npos; p = text.find(what, p + 1)) ++n;
  return n;
}

TEST(CollectHttp, ServesOnlyTheEmbeddedPagesAndNeedsTheAdminToken) {
  const auto dir = fresh_dir("routes");
  Study study(dir, fast_settings());
  auto get = [&](const std::string& t) { return handle_request(study, "tok", "GET", t, ""); };
  const auto page = get("/");
  EXPECT_EQ(page.status, 200);
  EXPECT_NE(page.body.find("<canvas id=\"field\""), std::string::npos);
  EXPECT_EQ(get("/game.js").content_type, "text/javascript; charset=utf-8");
  EXPECT_NE(get("/game.js").body.find("performance.now()"), std::string::npos);
  EXPECT_EQ(get("/game.css").status, 200);
  for (const char* t :
       {"/../../etc/passwd", "/etc/passwd", "/admin.html", "/logs/P1.csv", "/%2e%2e/x"}) {
    EXPECT_EQ(get(t).status, 404) << t;
  }
  EXPECT_EQ(get("/admin").status, 403);
  EXPECT_EQ(get("/admin?token=wrong").status, 403);
  study.join("P7");
  const auto admin = get("/admin?token=tok");
  EXPECT_EQ(admin.status, 200);
  EXPECT_NE(admin.body.find("<td>P7</td>"), std::string::npos);
  EXPECT_NE(get("/api/admin?token=tok").body.find("\"participant\":\"P7\""), std::string::npos);
  EXPECT_EQ(handle_request(study, "tok", "DELETE", "/", "").status, 405);
  EXPECT_EQ(get("/api/join").status, 405);
}

TEST(CollectHttp, MalformedRequestsGetClearErrorsAndAreRecorded) {
  const auto dir = fresh_dir("malformed");
  Study study(dir, fast_settings());
  auto post = [&](const std::string& t, const std::string& b = "") {
    return handle_request(study, "tok", "POST", t, b);
  };
  EXPECT_EQ(post("/api/join?participant=../etc").status, 400);
  EXPECT_EQ(post("/api/join?participant=%zz").status, 400);
  const auto j = post("/api/join?PROLIFIC_PID=5f1b2c3d");
  EXPECT_EQ(j.status, 200);
  EXPECT_NE(j.body.find("\"participant\":\"5f1b2c3d\""), std::string::npos);
  EXPECT_EQ(post("/api/round/submit?participant=5f1b2c3d&kind=main").status, 400);
  EXPECT_EQ(post("/api/round/submit?participant=5f1b2c3d&kind=x&iteration=1").status, 400);
  const auto bad = post("/api/round/submit?participant=5f1b2c3d&kind=practice&iteration=1",
                        "0,0.5\nnot,numbers\n");
  EXPECT_EQ(bad.status, 400);
  EXPECT_NE(bad.body.find("\"error\":\"malformed\""), std::string::npos);
  EXPECT_EQ(post("/api/round/start?participant=ghost").status, 404);
  EXPECT_EQ(post("/api/questionnaire?participant=5f1b2c3d", "trust=3").status, 409);
  const std::string events = slurp(dir / "collect" / "events.csv");
  EXPECT_EQ(count(events, ",rejected,"), 7) << events;  // one per refused request above
  EXPECT_FALSE(fs::exists(dir / "practice" / "5f1b2c3d.csv"));
}

TEST(CollectHttp, OversizedAndGarbageRequestsAreRefusedOnTheWire) {
  const auto dir = fresh_dir("wire");
  Study study(dir, fast_settings());
  ServerOptions o;
  o.port = 0;
  o.admin_token = "tok";
  o.body_limit = 4096;
  o.threads = 2;
  Server server(study, o);
  std::thread t([&] { server.run(); });
  const auto port = server.port();
  EXPECT_EQ(request(port, http::verb::get, "/").status, 200);
  EXPECT_EQ(request(port, http::verb::post, "/api/join?participant=W1").status, 200);
  EXPECT_EQ(
      request(port, http::verb::post, "/api/round/submit?participant=W1&kind=practice&iteration=1",
              std::string(10000, '1'))
          .status,
      413);
  {
    net::io_context ioc;
    tcp::socket sock(ioc);
    sock.connect(tcp::endpoint(net::ip::make_address("127.0.0.1"), port));
    net::write(sock, net::buffer(std::string("THIS IS NOT HTTP\r\n\r\n")));
    beast::flat_buffer buf;
    http::response<http::string_body> res;
    http::read(sock, buf, res);
    EXPECT_EQ(res.result_int(), 400u);
  }
  server.stop();
  t.join();
  EXPECT_NE(slurp(dir / "collect" / "events.csv").find("413 too_large"), std::string::npos);
  EXPECT_FALSE(fs::exists(dir / "practice" / "W1.csv"));
}

// ---- the real binary ----

struct Running {
  pid_t pid = -1;
  unsigned short port = 0;
};

Running launch(const fs::path& dir) {
  const fs::path out = dir.parent_path() / (dir.filename().string() + ".stdout");
  fs::remove(out);
  Running r;
  r.pid = ::fork();
  if (r.pid == 0) {
    const int fd = ::open(out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    ::dup2(fd, 1);
    ::execl(FEINT_EXE, FEINT_EXE, "collect", dir.c_str(), "--port", "0", "--admin-token", "tok",
            static_cast<char*>(nullptr));
    ::_exit(127);
  }
  for (int i = 0; i < 200 && r.port == 0; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(25));
    for (const auto& l : lines(slurp(out))) {
      if (l.rfind("port: ", 0) == 0) r.port = static_cast<unsigned short>(std::stoi(l.substr(6)));
    }
  }
  return r;
}

void stop(Running& r, int sig) {
  ::kill(r.pid, sig);
  int status = 0;
  ::waitpid(r.pid, &status, 0);
}

TEST(CollectBinary, KilledMidStudyAndRestartedThenFeintAnalyzeReadsTheFolder) {
  const auto dir = fresh_dir("binary");
  {
    std::ofstream(dir / "feint.toml") << "[collect]\niterations = 4\nrobot-speed = 8\n"
                                         "[analyze]\ncompare = \"adaptive,random\"\n";
  }
  Settings s = fast_settings();
  s.iterations = 4;
  Running srv = launch(dir);
  ASSERT_NE(srv.port, 0) << slurp(dir.parent_path() / (dir.filename().string() + ".stdout"));
  const std::vector<std::string> people{"B1", "B2", "B3", "B4"};
  auto play = [&](const std::string& id, int rounds) {
    for (int i = 0; i < rounds; ++i) {
      const auto start = request(srv.port, http::verb::post, "/api/round/start?participant=" + id);
      ASSERT_EQ(start.status, 200) << start.body;
      const bool practice = start.body.find("\"kind\":\"practice\"") != std::string::npos;
      const int it = std::stoi(start.body.substr(start.body.find("\"iteration\":") + 12));
      const double dur = *io::parse_double(
          start.body.substr(start.body.find("\"duration\":") + 11,
                            start.body.find(',', start.body.find("\"duration\":")) -
                                start.body.find("\"duration\":") - 11));
      Round r;
      r.path = {{0, 0, 0}, {dur, 0, 0}};
      const auto sub = request(srv.port, http::verb::post,
                               "/api/round/submit?participant=" + id +
                                   "&kind=" + (practice ? "practice" : "main") +
                                   "&iteration=" + std::to_string(it),
                               trace_body(valid_trace(r, 0.8, it % 2)));
      ASSERT_EQ(sub.status, 200) << sub.body;
    }
  };
  for (const auto& id : people)
    ASSERT_EQ(request(srv.port, http::verb::post, "/api/join?participant=" + id).status, 200);
  for (const auto& id : people) play(id, 3);  // 2 practice + 1 analysed each
  stop(srv, SIGKILL);                         // no chance to clean up
  srv = launch(dir);
  ASSERT_NE(srv.port, 0);
  const auto admin = request(srv.port, http::verb::get, "/api/admin?token=tok").body;
  EXPECT_EQ(count(admin, "\"rounds_saved\":1"), 4) << admin;
  for (const auto& id : people) {
    play(id, 3);
    EXPECT_EQ(request(srv.port, http::verb::post, "/api/round/start?participant=" + id).status,
              409);
    const int q = request(srv.port, http::verb::post, "/api/questionnaire?participant=" + id,
                          "entertainment=6&deception=5&intelligence=7&trust=2&intentional=yes")
                      .status;
    EXPECT_EQ(q, 200);
  }
  stop(srv, SIGTERM);
  // feint analyze reads the folder as it is; practice rounds are not in it.
  const fs::path out = dir.parent_path() / (dir.filename().string() + "-out");
  const std::string cmd = std::string(FEINT_EXE) + " analyze " + dir.string() + " -o " +
                          out.string() + " > " + out.string() + ".log 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << slurp(out.string() + ".log");
  const auto scores = lines(slurp(out / "scores.csv"));
  ASSERT_EQ(scores.size(), 1u + 4 * 4);
  const auto header = io::split_csv_line(scores[0]);
  const auto col = std::find(header.begin(), header.end(), "overspeed_segments") - header.begin();
  for (std::size_t i = 1; i < scores.size(); ++i)
    EXPECT_EQ(io::split_csv_line(scores[i])[col], "0");
  EXPECT_TRUE(fs::exists(out / "likert_summary.csv"));
}

}  // namespace
}  // namespace feint::collect
