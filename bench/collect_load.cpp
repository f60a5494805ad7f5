// collect_load - 50 simulated participants submitting rounds to `feint collect` at once.
//
// Starts the collect server in-process on 127.0.0.1 (ephemeral port, 4 server threads) over a
// fresh study folder, then runs one client thread per participant: join, and for every round
// (2 practice + 20 analysed, the paper's geometry and robot speed) ask for the round and submit a
// 60 Hz pad trace of its length, as fast as the server answers (no waiting for the robot). Reports
// rounds/s, the time from sending a round to its acknowledgement (the acknowledgement comes only
// after the rows are written and fdatasync'ed: the time to a durable save), median and 99th
// percentile, and the process's peak resident memory (server and clients).
//
//   collect_load [participants=50] [folder=/tmp/feint-collect-load]
#include <sys/resource.h>

#include <algorithm>
#include <atomic>
#include <boost/asio/ip/tcp.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "feint/collect/server.hpp"
#include "feint/io/number.hpp"

namespace beast = boost::beast;
namespace http = beast::http;
namespace net = boost::asio;
using tcp = net::ip::tcp;
using Clock = std::chrono::steady_clock;

namespace {

struct Client {
  net::io_context ioc;
  tcp::socket sock{ioc};
  beast::flat_buffer buf;
  explicit Client(unsigned short port) {
    sock.connect(tcp::endpoint(net::ip::make_address("127.0.0.1"), port));
  }
  std::pair<int, std::string> post(const std::string& target, const std::string& body) {
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
};

double field(const std::string& json, const std::string& name) {
  const auto p = json.find("\"" + name + "\":");
  return std::stod(json.substr(p + name.size() + 3));
}

}  // namespace

int main(int argc, char** argv) {
  const int people = argc > 1 ? std::atoi(argv[1]) : 50;
  const std::filesystem::path dir = argc > 2 ? argv[2] : "/tmp/feint-collect-load";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  feint::collect::Study study(dir, {});
  feint::collect::ServerOptions o;
  o.port = 0;
  o.threads = 4;
  feint::collect::Server server(study, o);
  std::thread srv([&] { server.run(); });
  const auto port = server.port();

  std::mutex mu;
  std::vector<double> latencies;
  std::atomic<long> samples{0};
  std::atomic<int> failures{0};
  const auto t0 = Clock::now();
  std::vector<std::thread> clients;
  for (int i = 0; i < people; ++i) {
    clients.emplace_back([&, i] {
      Client c(port);
      const std::string id = "L" + std::to_string(i);
      const std::string q = "?participant=" + id;
      if (c.post("/api/join" + q, "").first != 200) {
        ++failures;
        return;
      }
      std::vector<double> mine;
      for (;;) {
        const auto [st, round] = c.post("/api/round/start" + q, "");
        if (st != 200) break;  // 409: every round saved
        const double dur = field(round, "duration");
        const int it = static_cast<int>(field(round, "iteration"));
        const bool practice = round.find("\"kind\":\"practice\"") != std::string::npos;
        std::string body;
        double pad = 0.5;
        for (int k = 0;; ++k) {
          const double t = k / 60.0;
          if (t >= dur) break;
          pad = std::min(1.0, 0.5 + 0.8 * t);
          body += feint::io::format_double(t) + "," + feint::io::format_double(pad) + "\n";
          ++samples;
        }
        body += feint::io::format_double(dur) + "," +
                feint::io::format_double(std::min(1.0, 0.5 + 0.8 * dur)) + "\n";
        const auto s0 = Clock::now();
        const auto r =
            c.post("/api/round/submit" + q + "&kind=" + (practice ? "practice" : "main") +
                       "&iteration=" + std::to_string(it),
                   body);
        mine.push_back(std::chrono::duration<double, std::milli>(Clock::now() - s0).count());
        if (r.first != 200) {
          ++failures;
          break;
        }
      }
      std::lock_guard lock(mu);
      latencies.insert(latencies.end(), mine.begin(), mine.end());
    });
  }
  for (auto& t : clients) t.join();
  const double secs = std::chrono::duration<double>(Clock::now() - t0).count();
  server.stop();
  srv.join();
  std::sort(latencies.begin(), latencies.end());
  auto q = [&](double p) {
    return latencies.empty() ? 0.0
                             : latencies[std::min(latencies.size() - 1,
                                                  static_cast<std::size_t>(p * latencies.size()))];
  };
  rusage ru{};
  getrusage(RUSAGE_SELF, &ru);
  std::printf("participants %d, rounds saved %zu (%ld samples), failures %d, %.2f s\n", people,
              latencies.size(), samples.load(), failures.load(), secs);
  std::printf("rounds/s %.0f\n", static_cast<double>(latencies.size()) / secs);
  std::printf("time to durable save: median %.2f ms, p99 %.2f ms, max %.2f ms\n", q(0.5), q(0.99),
              latencies.empty() ? 0.0 : latencies.back());
  std::printf("peak memory (server + %d clients, one process): %.1f MB\n", people,
              ru.ru_maxrss / 1024.0);
  std::filesystem::remove_all(dir);
  return failures.load() == 0 ? 0 : 1;
}
