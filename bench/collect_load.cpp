// collect_load - simulated participants submitting rounds to `feint collect` (loopback only).
//
// Starts the collect server in-process on 127.0.0.1 (ephemeral port) over a fresh study folder
// (--dir; put it on the disk the study would use, not on tmpfs, to measure durable saves).
//
// Saturated (default): every participant on its own kept-alive connection: join, and for every
// round (2 practice + 20 analysed, the paper's geometry and robot speed) ask for the round and
// submit a 60 Hz pad trace of its length, as fast as the server answers.
//
// At a study's pace (--pace): every participant asks for a round, waits as long as the robot
// drives (the round's duration, as a person watching it would) plus a second, submits the round,
// and so on, for --seconds seconds; the participants join spread over the first 7 s. Each request
// is made on a new connection that the server closes after its answer (as a reverse proxy without
// upstream keep-alive does).
//
// The clients are asynchronous (Boost.Beast), all on --client-threads threads (default 1), so
// that the load generator takes as little as possible of the CPU it shares with the server. The
// trace of a round is made once per round length and reused (it is the same bytes each time).
//
// Reports rounds/s, the time from sending a round (connection already open) to its
// acknowledgement, which comes only after the rows are written and synced: the time to a durable
// save (median, 99th percentile, max; with --pace also for the saves sent in the first 7 s, while
// participants still join, and by 5 s window); the syncs and the appends they covered (group commit); the
// CPU time of the server and of the clients (per round); and the process's peak resident memory.
//
// The study folder is removed at the end, unless --keep. (Keep it when measuring again soon after:
// ext4 without a journal, as on the development machine, does not reuse the inodes of files
// deleted in the last minutes, and creating the next run's thousands of logs then spends most of
// its time skipping them.)
//
//   collect_load [participants=50] [--threads N=4] [--client-threads C=1] [--pace] [--seconds S=30]
//                [--dir D=/tmp/feint-collect-load] [--keep]
#include <sys/resource.h>

#include <algorithm>
#include <atomic>
#include <boost/asio/connect.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/steady_timer.hpp>
#include <boost/asio/strand.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <map>
#include <memory>
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

double field(const std::string& json, const std::string& name) {
  const auto p = json.find("\"" + name + "\":");
  return std::stod(json.substr(p + name.size() + 3));
}

/// The body of a round: a 60 Hz trace of its duration, the pad moving right.
std::string trace(double dur, long& samples) {
  std::string body;
  samples = 0;
  for (int k = 0;; ++k) {
    const double t = k / 60.0;
    if (t >= dur) break;
    body += feint::io::format_double(t) + "," +
            feint::io::format_double(std::min(1.0, 0.5 + 0.8 * t)) + "\n";
    ++samples;
  }
  ++samples;
  return body + feint::io::format_double(dur) + "," +
         feint::io::format_double(std::min(1.0, 0.5 + 0.8 * dur)) + "\n";
}

double cpu_seconds(int who) {
  rusage ru{};
  getrusage(who, &ru);
  return static_cast<double>(ru.ru_utime.tv_sec + ru.ru_stime.tv_sec) +
         static_cast<double>(ru.ru_utime.tv_usec + ru.ru_stime.tv_usec) / 1e6;
}

struct Bench {
  net::io_context ioc;
  tcp::endpoint server;
  bool pace = false;
  Clock::time_point end;  // --pace: no new round after this
  std::mutex mu;
  std::vector<double> latencies;
  std::vector<double> joining;  // --pace: the saves sent while participants still join (first 7 s)
  std::vector<std::vector<double>> windows;  // --pace: the saves by the 5 s window they were sent in
  Clock::time_point t0;
  std::map<double, std::pair<std::string, long>> bodies;  // round length -> trace, samples
  long samples = 0;
  std::atomic<int> failures{0};

  const std::pair<std::string, long>& body(double duration) {
    std::lock_guard lock(mu);
    auto it = bodies.find(duration);
    if (it == bodies.end()) {
      long n = 0;
      std::string b = trace(duration, n);
      it = bodies.emplace(duration, std::make_pair(std::move(b), n)).first;
    }
    return it->second;
  }
  void fail(const std::string& what) {
    if (failures++ < 5) std::fprintf(stderr, "client: %s\n", what.c_str());
  }
};

/// One participant: join -> (start, [wait the round], submit)* as an asynchronous state machine.
class Participant : public std::enable_shared_from_this<Participant> {
 public:
  Participant(Bench& b, int who)
      : b_(b),
        id_("L" + std::to_string(who)),
        strand_(net::make_strand(b.ioc)),
        sock_(strand_),
        timer_(strand_) {}

  /// --pace: the time is up; a participant watching a round leaves without submitting it.
  void finish() {
    net::post(strand_, [self = shared_from_this()] { self->timer_.cancel(); });
  }

  void begin(Clock::time_point at) {
    timer_.expires_at(at);
    timer_.async_wait([self = shared_from_this()](beast::error_code) {
      if (self->b_.pace && Clock::now() >= self->b_.end) return;
      self->request("/api/join?participant=" + self->id_, "", &Participant::on_join);
    });
  }

 private:
  using Next = void (Participant::*)(int, const std::string&);

  /// POSTs on the open connection (saturated) or on a new one (--pace), then calls `next`.
  void request(std::string target, std::string body, Next next) {
    req_ = http::request<http::string_body>(http::verb::post, std::move(target), 11);
    req_.set(http::field::host, "127.0.0.1");
    req_.keep_alive(!b_.pace);
    req_.body() = std::move(body);
    req_.prepare_payload();
    next_ = next;
    if (sock_.is_open()) return send();
    sock_.async_connect(b_.server, [self = shared_from_this()](beast::error_code ec) {
      if (ec) return self->b_.fail("connect: " + ec.message());
      self->send();
    });
  }
  void send() {
    sent_ = Clock::now();
    http::async_write(sock_, req_, [self = shared_from_this()](beast::error_code ec, std::size_t) {
      if (ec) return self->b_.fail("write: " + ec.message());
      self->res_ = {};
      http::async_read(self->sock_, self->buf_, self->res_,
                       [self](beast::error_code ec2, std::size_t) {
                         if (ec2) return self->b_.fail("read: " + ec2.message());
                         if (self->b_.pace) {  // the server closes it (Connection: close)
                           beast::error_code ignored;
                           self->sock_.close(ignored);
                           self->buf_.clear();
                         }
                         (self.get()->*self->next_)(static_cast<int>(self->res_.result_int()),
                                                    self->res_.body());
                       });
    });
  }

  void on_join(int status, const std::string& body) {
    if (status != 200) return b_.fail("join: " + body);
    start();
  }
  void start() {
    if (b_.pace && Clock::now() >= b_.end) return;
    request("/api/round/start?participant=" + id_, "", &Participant::on_start);
  }
  void on_start(int status, const std::string& round) {
    if (status != 200) return;  // 409: every round saved
    const double dur = field(round, "duration");
    const bool practice = round.find("\"kind\":\"practice\"") != std::string::npos;
    target_ = "/api/round/submit?participant=" + id_ + "&kind=" + (practice ? "practice" : "main") +
              "&iteration=" + std::to_string(static_cast<int>(field(round, "iteration")));
    const auto& [body, n] = b_.body(dur);
    body_ = &body;
    round_samples_ = n;
    if (!b_.pace) return submit();
    if (Clock::now() >= b_.end) return;  // the time is up: this round is not played
    // As a person does: watch the robot drive, then a second more.
    timer_.expires_after(std::chrono::duration_cast<Clock::duration>(
        std::chrono::duration<double>(dur + 1.0)));
    timer_.async_wait([self = shared_from_this()](beast::error_code) { self->submit(); });
  }
  void submit() {
    if (b_.pace && Clock::now() >= b_.end) return;
    request(target_, *body_, &Participant::on_submit);
  }
  void on_submit(int status, const std::string& body) {
    const double ms = std::chrono::duration<double, std::milli>(Clock::now() - sent_).count();
    // (In --pace mode sent_ is taken once connected: the connection is not part of the save.)
    if (status != 200) return b_.fail("submit: " + body);
    {
      std::lock_guard lock(b_.mu);
      b_.latencies.push_back(ms);
      if (b_.pace && sent_ - b_.t0 < std::chrono::seconds(7)) b_.joining.push_back(ms);
      if (b_.pace) {
        const auto w = static_cast<std::size_t>(std::chrono::duration<double>(sent_ - b_.t0).count() / 5);
        if (b_.windows.size() <= w) b_.windows.resize(w + 1);
        b_.windows[w].push_back(ms);
      }
      b_.samples += round_samples_;
    }
    start();
  }

  Bench& b_;
  std::string id_;
  net::strand<net::io_context::executor_type> strand_;  // this participant's handlers, in turn
  tcp::socket sock_;
  net::steady_timer timer_;
  beast::flat_buffer buf_;
  http::request<http::string_body> req_;
  http::response<http::string_body> res_;
  Next next_ = nullptr;
  Clock::time_point sent_;
  std::string target_;
  const std::string* body_ = nullptr;
  long round_samples_ = 0;
};

}  // namespace

int main(int argc, char** argv) {
  int people = 50;
  unsigned threads = 4, client_threads = 1;
  bool pace = false, keep = false;
  double seconds = 30;
  std::filesystem::path dir = "/tmp/feint-collect-load";
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--threads" && i + 1 < argc) {
      threads = static_cast<unsigned>(std::atoi(argv[++i]));
    } else if (a == "--client-threads" && i + 1 < argc) {
      client_threads = std::max(1u, static_cast<unsigned>(std::atoi(argv[++i])));
    } else if (a == "--pace") {
      pace = true;
    } else if (a == "--keep") {
      keep = true;
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

  Bench b;
  b.server = tcp::endpoint(net::ip::make_address("127.0.0.1"), server.port());
  b.pace = pace;
  const double cpu0 = cpu_seconds(RUSAGE_SELF);
  const auto t0 = Clock::now();
  b.t0 = t0;
  b.end = t0 + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(seconds));
  std::vector<std::shared_ptr<Participant>> all;
  for (int i = 0; i < people; ++i) {
    const auto at = pace ? t0 + std::chrono::duration_cast<Clock::duration>(
                                    std::chrono::duration<double>(7.0 * i / people))
                         : t0;
    all.push_back(std::make_shared<Participant>(b, i));
    all.back()->begin(at);
  }
  net::steady_timer stop(b.ioc);
  if (pace) {
    stop.expires_at(b.end);
    stop.async_wait([&](beast::error_code) {
      for (auto& p : all) p->finish();
    });
  }
  std::vector<std::thread> clients;
  std::atomic<double> client_cpu{0};
  for (unsigned c = 0; c < client_threads; ++c)
    clients.emplace_back([&] {
      b.ioc.run();  // returns when every participant is done
      double v = client_cpu.load();
      while (!client_cpu.compare_exchange_weak(v, v + cpu_seconds(RUSAGE_THREAD))) {
      }
    });
  for (auto& t : clients) t.join();
  const double secs = std::chrono::duration<double>(Clock::now() - t0).count();
  const double cpu = cpu_seconds(RUSAGE_SELF) - cpu0;
  server.stop();
  srv.join();
  auto& lat = b.latencies;
  std::sort(lat.begin(), lat.end());
  auto q = [&](double p) {
    return lat.empty() ? 0.0
                       : lat[std::min(lat.size() - 1, static_cast<std::size_t>(p * lat.size()))];
  };
  auto& jl = b.joining;
  std::sort(jl.begin(), jl.end());
  rusage ru{};
  getrusage(RUSAGE_SELF, &ru);
  const auto cs = study.commit_stats();
  const double rounds = static_cast<double>(lat.size());
  std::printf("%s: participants %d, server threads %u, client threads %u, rounds saved %zu (%ld "
              "samples), failures %d, %.2f s\n",
              pace ? "at a study's pace" : "saturated", people, threads, client_threads, lat.size(),
              b.samples, b.failures.load(), secs);
  std::printf("rounds/s %.0f\n", rounds / secs);
  std::printf("time to durable save: median %.2f ms, p99 %.2f ms, max %.2f ms\n", q(0.5), q(0.99),
              lat.empty() ? 0.0 : lat.back());
  if (pace && !jl.empty()) {
    auto jq = [&](double p) { return jl[std::min(jl.size() - 1, static_cast<std::size_t>(p * jl.size()))]; };
    std::printf("  of which sent in the first 7 s (joins going on): %zu, median %.2f ms, p99 %.2f "
                "ms, max %.2f ms\n",
                jl.size(), jq(0.5), jq(0.99), jl.back());
    for (std::size_t w = 0; w < b.windows.size(); ++w) {
      auto& v = b.windows[w];
      if (v.empty()) continue;
      std::sort(v.begin(), v.end());
      std::printf("  sent %zu-%zu s: %zu saves, median %.2f ms, p99 %.2f ms\n", 5 * w, 5 * w + 5,
                  v.size(), v[v.size() / 2], v[std::min(v.size() - 1, v.size() * 99 / 100)]);
    }
  }
  std::printf("syncs %llu for %llu appends (%.1f appends per sync), %.1f ms per group written and "
              "synced, writer busy %.0f%% of the time\n",
              static_cast<unsigned long long>(cs.syncs),
              static_cast<unsigned long long>(cs.appends),
              cs.syncs ? static_cast<double>(cs.appends) / static_cast<double>(cs.syncs) : 0.0,
              cs.syncs ? cs.busy_seconds * 1e3 / static_cast<double>(cs.syncs) : 0.0,
              100.0 * cs.busy_seconds / secs);
  std::printf("CPU: %.2f s in all, server %.2f s (%.0f us per round), clients %.2f s (%.0f us per "
              "round)\n",
              cpu, cpu - client_cpu.load(), rounds > 0 ? (cpu - client_cpu.load()) / rounds * 1e6 : 0.0,
              client_cpu.load(), rounds > 0 ? client_cpu.load() / rounds * 1e6 : 0.0);
  std::printf("peak memory (server + clients, one process): %.1f MB\n", ru.ru_maxrss / 1024.0);
  if (!keep) std::filesystem::remove_all(dir);
  return b.failures.load() == 0 ? 0 : 1;
}
