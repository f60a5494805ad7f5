// collect_load - simulated participants submitting rounds to `feint collect` (loopback only).
//
// Starts the collect server in-process on 127.0.0.1 (ephemeral port) over a fresh study folder.
//
// Saturated (default): one client thread per participant, on a kept-alive connection: join, and
// for every round (2 practice + 20 analysed, the paper's geometry and robot speed) ask for the
// round and submit a 60 Hz pad trace of its length, as fast as the server answers.
//
// At a study's pace (--pace): every participant asks for a round, waits as long as the robot
// drives (the round's duration, as a person watching it would) plus a second, submits the round,
// and so on, for --seconds seconds; the participants start spread over the first pace interval.
// A pool of client threads serves all participants, each request on a fresh connection (as a
// reverse proxy without upstream keep-alive does).
//
// Reports rounds/s, the time from sending a round to its acknowledgement (which comes only after
// the rows are written and synced: the time to a durable save; median, 99th percentile, max), the
// syncs and the appends they covered (group commit), and the process's peak resident memory.
//
//   collect_load [participants=50] [--threads N=16] [--pace] [--seconds S=30] [--dir D]
#include <sys/resource.h>

#include <algorithm>
#include <atomic>
#include <boost/asio/ip/tcp.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <mutex>
#include <queue>
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

/// The body of a round: a 60 Hz trace of its duration, the pad moving right.
std::string trace(double dur, long& samples) {
  std::string body;
  for (int k = 0;; ++k) {
    const double t = k / 60.0;
    if (t >= dur) break;
    body += feint::io::format_double(t) + "," +
            feint::io::format_double(std::min(1.0, 0.5 + 0.8 * t)) + "\n";
    ++samples;
  }
  return body + feint::io::format_double(dur) + "," +
         feint::io::format_double(std::min(1.0, 0.5 + 0.8 * dur)) + "\n";
}

std::string submit_target(const std::string& id, const std::string& round) {
  const bool practice = round.find("\"kind\":\"practice\"") != std::string::npos;
  return "/api/round/submit?participant=" + id + "&kind=" + (practice ? "practice" : "main") +
         "&iteration=" + std::to_string(static_cast<int>(field(round, "iteration")));
}

double ms_since(Clock::time_point t) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t).count();
}

}  // namespace

int main(int argc, char** argv) {
  int people = 50;
  unsigned threads = 16;
  bool pace = false;
  double seconds = 30;
  std::filesystem::path dir = "/tmp/feint-collect-load";
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--threads" && i + 1 < argc) {
      threads = static_cast<unsigned>(std::atoi(argv[++i]));
    } else if (a == "--pace") {
      pace = true;
    } else if (a == "--seconds" && i + 1 < argc) {
      seconds = std::atof(argv[++i]);
    } else if (a == "--dir" && i + 1 < argc) {
      dir = argv[++i];
    } else {
      people = std::atoi(argv[i]);
    }
  }
  // One descriptor per connection on each side, all in this process.
  rlimit rl{};
  if (::getrlimit(RLIMIT_NOFILE, &rl) == 0) {
    rl.rlim_cur = rl.rlim_max;
    ::setrlimit(RLIMIT_NOFILE, &rl);
  }
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  feint::collect::Study study(dir, {});
  feint::collect::ServerOptions o;
  o.port = 0;
  o.threads = threads;
  feint::collect::Server server(study, o);
  std::thread srv([&] { server.run(); });
  const auto port = server.port();

  std::mutex mu;
  std::vector<double> latencies;
  std::atomic<long> samples{0};
  std::atomic<int> failures{0};
  const auto t0 = Clock::now();
  std::vector<std::thread> clients;
  if (!pace) {
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
        long n = 0;
        for (;;) {
          const auto [st, round] = c.post("/api/round/start" + q, "");
          if (st != 200) break;  // 409: every round saved
          const std::string body = trace(field(round, "duration"), n);
          const auto s0 = Clock::now();
          const auto r = c.post(submit_target(id, round), body);
          mine.push_back(ms_since(s0));
          if (r.first != 200) {
            ++failures;
            break;
          }
        }
        samples += n;
        std::lock_guard lock(mu);
        latencies.insert(latencies.end(), mine.begin(), mine.end());
      });
    }
  } else {
    // Every participant is a small state machine: join -> (start, wait the round, submit)*.
    struct Job {
      Clock::time_point due;
      int who;
      int step;  // 0 join, 1 start, 2 submit
      std::string target, body;
      bool operator>(const Job& o) const { return due > o.due; }
    };
    std::priority_queue<Job, std::vector<Job>, std::greater<>> jobs;
    const auto spread = std::chrono::duration<double>(7.0);
    for (int i = 0; i < people; ++i)
      jobs.push({t0 + std::chrono::duration_cast<Clock::duration>(spread * i / people), i, 0, "", ""});
    const auto end = t0 + std::chrono::duration_cast<Clock::duration>(
                              std::chrono::duration<double>(seconds));
    std::condition_variable cv;
    const unsigned workers = std::min(256, std::max(8, people / 20));
    for (unsigned w = 0; w < workers; ++w) {
      clients.emplace_back([&] {
        std::vector<double> mine;
        long n = 0;
        for (;;) {
          Job j;
          {
            std::unique_lock lock(mu);
            for (;;) {
              if (jobs.empty() || Clock::now() >= end) goto done;
              if (jobs.top().due <= Clock::now()) break;
              cv.wait_until(lock, jobs.top().due);
            }
            j = jobs.top();
            jobs.pop();
          }
          const std::string id = "L" + std::to_string(j.who);
          try {
            Client c(port);
            if (j.step == 0) {
              if (c.post("/api/join?participant=" + id, "").first != 200) ++failures;
              j.step = 1;
            } else if (j.step == 1) {
              const auto [st, round] = c.post("/api/round/start?participant=" + id, "");
              if (st != 200) continue;  // every round saved: this participant is done
              const double dur = field(round, "duration");
              j.target = submit_target(id, round);
              j.body = trace(dur, n);
              j.step = 2;
              j.due = Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                         std::chrono::duration<double>(dur + 1.0));
              std::lock_guard lock(mu);
              jobs.push(std::move(j));
              cv.notify_one();
              continue;
            } else {
              const auto s0 = Clock::now();
              const auto r = c.post(j.target, j.body);
              mine.push_back(ms_since(s0));
              if (r.first != 200) ++failures;
              j.step = 1;
            }
          } catch (const std::exception& e) {
            ++failures;
            std::fprintf(stderr, "client: %s\n", e.what());
          }
          j.due = Clock::now();
          std::lock_guard lock(mu);
          jobs.push(std::move(j));
          cv.notify_one();
        }
      done:
        samples += n;
        std::lock_guard lock(mu);
        latencies.insert(latencies.end(), mine.begin(), mine.end());
        cv.notify_all();
      });
    }
    for (auto& t : clients) t.join();  // before jobs and cv go out of scope
  }
  for (auto& t : clients)
    if (t.joinable()) t.join();
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
  const auto cs = study.commit_stats();
  std::printf("%s: participants %d, server threads %u, rounds saved %zu (%ld samples), failures %d, "
              "%.2f s\n",
              pace ? "at a study's pace" : "saturated", people, threads, latencies.size(),
              samples.load(), failures.load(), secs);
  std::printf("rounds/s %.0f\n", static_cast<double>(latencies.size()) / secs);
  std::printf("time to durable save: median %.2f ms, p99 %.2f ms, max %.2f ms\n", q(0.5), q(0.99),
              latencies.empty() ? 0.0 : latencies.back());
  std::printf("syncs %llu for %llu appends (%.1f appends per sync)\n",
              static_cast<unsigned long long>(cs.syncs),
              static_cast<unsigned long long>(cs.appends),
              cs.syncs ? static_cast<double>(cs.appends) / static_cast<double>(cs.syncs) : 0.0);
  std::printf("peak memory (server + clients, one process): %.1f MB\n", ru.ru_maxrss / 1024.0);
  std::filesystem::remove_all(dir);
  return failures.load() == 0 ? 0 : 1;
}
