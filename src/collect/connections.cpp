// The connection loop of `feint collect` (feint/collect/server.hpp): Boost.Beast sessions (modelled
// on Beast's http_server_async example), the Host check, the client's address, the connection cap
// (at the cap, the connection quiet longest is closed to let a new one in) and the back-off when
// descriptors run out. The requests themselves are answered in server.cpp.
#include <fmt/format.h>
#include <malloc.h>
#include <sys/resource.h>

#include <algorithm>
#include <atomic>
#include <boost/asio/executor_work_guard.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/signal_set.hpp>
#include <boost/asio/steady_timer.hpp>
#include <boost/asio/strand.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <functional>
#include <limits>
#include <list>
#include <memory>
#include <mutex>
#include <optional>
#include <random>
#include <thread>
#include <vector>

#include "feint/collect/server.hpp"
#include "feint/error.hpp"
#include "feint/io/number.hpp"

namespace feint::collect {

namespace beast = boost::beast;
namespace http = beast::http;
namespace net = boost::asio;
using tcp = net::ip::tcp;

// ---- the connection loop --------------------------------------------------------------------

namespace {

std::int64_t steady_ns() noexcept {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(
             std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

/// A connection that has received a byte of its request within this time is still sending (an
/// upload in progress) and is never closed to make room; nor is one accepted, or answered, within
/// it (a browser sends its request at once on a new or kept-alive connection).
constexpr std::int64_t kQuietBeforeClosable = 1'000'000'000;  // ns

/// What the acceptor's thread reads of a connection, to choose the one to close at the cap. Only
/// the connection's own thread writes it.
struct Activity {
  enum Phase : int {
    waiting,    // for the first byte of a request
    receiving,  // a request: some bytes in, not all
    busy,       // the request is being handled or answered, or the connection is closing
  };
  std::atomic<std::int64_t> quiet_since{steady_ns()};  // its last byte in, answer out, or accept
  std::atomic<int> phase{waiting};
  std::atomic<bool> served{false};  // it has had a whole request answered

  void heard() noexcept {
    quiet_since.store(steady_ns(), std::memory_order_relaxed);
    if (phase.load(std::memory_order_relaxed) == waiting)
      phase.store(receiving, std::memory_order_relaxed);
  }
  bool closable(std::int64_t now) const noexcept {
    return phase.load(std::memory_order_relaxed) != busy &&
           now - quiet_since.load(std::memory_order_relaxed) >= kQuietBeforeClosable;
  }
};

/// Beast's rate-policy hook, used only to see every read from the socket (however little it
/// brings, e.g. a header trickled byte by byte): no limit is applied.
class ArrivalPolicy {
 public:
  explicit ArrivalPolicy(Activity* a) noexcept : activity_(a) {}

 private:
  friend class beast::rate_policy_access;
  static constexpr std::size_t kAll = std::numeric_limits<std::size_t>::max();
  std::size_t available_read_bytes() const noexcept { return kAll; }
  std::size_t available_write_bytes() const noexcept { return kAll; }
  void transfer_read_bytes(std::size_t n) const noexcept {
    if (n > 0) activity_->heard();
  }
  void transfer_write_bytes(std::size_t) const noexcept {}
  void on_timer() const noexcept {}
  Activity* activity_;
};

using Stream = beast::basic_stream<tcp, net::any_io_executor, ArrivalPolicy>;

class Session;

/// What the sessions share with the server: options, the study, the state, the connections.
struct Shared {
  Study& study;
  ServerOptions opt;
  ServerState state;
  std::atomic<std::size_t> connections{0};
  std::atomic<std::size_t> pending{0};  // requests handed to the handler and not yet answered
  std::size_t max_connections = 0;
  std::vector<std::string> allowed_hosts;  // empty: no Host check
  std::mutex sessions_mu;                  // guards `sessions`
  std::list<Session*> sessions;            // every open connection (its entry is erased first)
  Shared(Study& s, ServerOptions o)
      : study(s), opt(std::move(o)), state(opt.rejections_per_minute) {}
  std::shared_ptr<Session> quiet_longest();
};

class Session : public std::enable_shared_from_this<Session> {
 public:
  Session(tcp::socket&& socket, Shared& shared)
      : stream_(ArrivalPolicy(&activity_), std::move(socket)), sh_(shared) {
    beast::error_code ec;
    const auto ep = stream_.socket().remote_endpoint(ec);
    peer_ = ec ? std::string() : ep.address().to_string();
    std::lock_guard lock(sh_.sessions_mu);
    entry_ = sh_.sessions.insert(sh_.sessions.end(), this);
  }
  ~Session() {
    {
      std::lock_guard lock(sh_.sessions_mu);
      sh_.sessions.erase(entry_);
    }
    release_slot();
  }

  void run() {
    net::dispatch(stream_.get_executor(),
                  beast::bind_front_handler(&Session::read, shared_from_this()));
  }

  const Activity& activity() const noexcept { return activity_; }

  /// Closes the connection to make room for a new one, if it may still be closed: checked again
  /// on its own thread, where no byte can arrive meanwhile. Then `then()`, on that thread.
  void make_room(std::function<void()> then) {
    net::dispatch(stream_.get_executor(), [self = shared_from_this(), then = std::move(then)] {
      if (self->activity_.closable(steady_ns())) {
        self->activity_.phase.store(Activity::busy, std::memory_order_relaxed);
        self->closed_to_make_room_ = true;
        self->stream_.close();  // the read waiting on it ends with operation_aborted
        self->release_slot();   // its descriptor is free now
      }
      then();
    });
  }

 private:
  void release_slot() {
    if (counted_) --sh_.connections;
    counted_ = false;
  }

  void read() {
    // Bytes already buffered (a pipelined request) are a request under way.
    activity_.phase.store(buffer_.size() > 0 ? Activity::receiving : Activity::waiting,
                          std::memory_order_relaxed);
    parser_.emplace();
    parser_->body_limit(sh_.opt.body_limit);
    parser_->header_limit(16 * 1024);
    // The first request has the full timeout; a kept-alive connection waiting for its next one
    // is closed after the (shorter) idle timeout, so idle connections do not hold descriptors.
    stream_.expires_after(first_ ? sh_.opt.timeout : std::min(sh_.opt.timeout, sh_.opt.idle_timeout));
    first_ = false;
    http::async_read(stream_, buffer_, *parser_,
                     beast::bind_front_handler(&Session::on_read, shared_from_this()));
  }

  void on_read(beast::error_code ec, std::size_t) {
    activity_.phase.store(Activity::busy, std::memory_order_relaxed);
    // A request read just before the connection was closed to make room is not handled: nobody
    // can be told its answer (a browser sends it again on a new connection).
    if (closed_to_make_room_) return;
    if (ec == http::error::end_of_stream || ec == beast::error::timeout ||
        ec == net::error::operation_aborted) {
      return close();
    }
    if (ec) {
      Response r;
      if (ec == http::error::body_limit || ec == http::error::header_limit) {
        r = {413, "application/json",
             fmt::format("{{\"error\":\"too_large\",\"message\":\"request larger than {} bytes\"}}",
                         sh_.opt.body_limit)};
        // Answered once the refusal is in the events log (without waiting on this thread).
        ++sh_.pending;
        return sh_.state.record_rejection(
            sh_.study, peer_, "", fmt::format("413 too_large: {}", ec.message()),
            [self = shared_from_this(), r = std::move(r)]() mutable {
              self->answer(std::move(r), false, 11, false);
            });
      }
      r = {400, "application/json",
           "{\"error\":\"malformed\",\"message\":\"not an HTTP request\"}"};
      return send(r, false, 11);
    }
    auto req = parser_->release();
    const std::string client =
        client_address(peer_, std::string(req["X-Forwarded-For"]), sh_.opt.trusted_proxies);
    const std::string host(req[http::field::host]);
    if (!sh_.allowed_hosts.empty() && !host_allowed(sh_.allowed_hosts, host)) {
      // DNS rebinding: a page of another site whose name now points here. Refused before
      // anything is read or written for it.
      Response r{
          421, "application/json",
          fmt::format("{{\"error\":\"bad_host\",\"message\":{}}}",
                      io::json_quote(fmt::format(
                          "this server does not answer to the host name '{}' (a protection "
                          "against DNS rebinding); open it as http://127.0.0.1:PORT/, or start "
                          "feint collect with --allowed-host NAME for your proxy's name",
                          host.substr(0, 200))))};
      ++sh_.pending;
      return sh_.state.record_rejection(
          sh_.study, client, "",
          fmt::format("{} {} 421 bad_host: Host '{}'", std::string(req.method_string()),
                      std::string(req.target().substr(0, req.target().find('?'))), host),
          [self = shared_from_this(), r = std::move(r), version = req.version()]() mutable {
            self->answer(std::move(r), false, version, false);
          });
    }
    // The handler does not block: a save is answered from the group committer's thread once its
    // group is synced, and this thread goes on serving other connections meanwhile.
    ++sh_.pending;
    handle_request(sh_.study, sh_.opt.admin_token, std::string(req.method_string()),
                   std::string(req.target()), std::move(req.body()), RequestInfo{client, &sh_.state},
                   [self = shared_from_this(), keep_alive = req.keep_alive(),
                    version = req.version(), head = req.method() == http::verb::head](Response r) {
                     self->answer(std::move(r), keep_alive, version, head);
                   });
  }

  /// The answer of a request handed to the handler: written on this connection's strand.
  void answer(Response r, bool keep_alive, unsigned version, bool head) {
    net::dispatch(stream_.get_executor(),
                  [self = shared_from_this(), r = std::move(r), keep_alive, version, head] {
                    self->send(r, keep_alive, version, head);
                  });
    --sh_.pending;  // after the dispatch: the server's io_context outlives every answer
  }

  void send(const Response& r, bool keep_alive, unsigned version, bool head = false) {
    auto res = std::make_shared<http::response<http::string_body>>(
        static_cast<http::status>(r.status), version);
    res->set(http::field::server, "feint-collect");
    res->set(http::field::content_type, r.content_type);
    res->set(http::field::cache_control, "no-store");
    res->set("X-Content-Type-Options", "nosniff");
    res->set("Content-Security-Policy",
             "default-src 'self'; img-src 'self' data:; style-src 'self'; script-src 'self'; "
             "frame-ancestors 'none'");
    if (r.status == 503) res->set(http::field::retry_after, "2");
    res->keep_alive(keep_alive);
    if (!head) res->body() = r.body;
    res->prepare_payload();
    if (head) res->body().clear();
    stream_.expires_after(sh_.opt.timeout);
    http::async_write(
        stream_, *res,
        [self = shared_from_this(), res, keep_alive](beast::error_code ec, std::size_t) {
          if (ec || !keep_alive) return self->close();
          // Quiet from now: the wait for the next request starts at the answer.
          self->activity_.quiet_since.store(steady_ns(), std::memory_order_relaxed);
          self->activity_.served.store(true, std::memory_order_relaxed);
          self->read();
        });
  }

  void close() {
    beast::error_code ec;
    stream_.socket().shutdown(tcp::socket::shutdown_send, ec);
  }

  Activity activity_;  // before stream_, whose policy points to it
  Stream stream_;
  beast::flat_buffer buffer_;
  std::optional<http::request_parser<http::string_body>> parser_;
  Shared& sh_;
  std::string peer_;
  std::list<Session*>::iterator entry_;
  bool first_ = true;
  bool counted_ = true;  // still counted in sh_.connections
  bool closed_to_make_room_ = false;
};

/// The connection to close for a new one. Of the connections neither busy nor sending (a byte of a
/// request within kQuietBeforeClosable), one that has never had a request answered goes before one
/// that has (a browser sends its request as soon as it connects: a connection that sent nothing, or
/// half a header, and fell silent is not a browser at work; a browser's kept-alive connection costs
/// it a reconnection), and among them the one quiet longest. When that one has been quiet for less
/// than kQuietBeforeClosable (just accepted, or just answered) nothing is closed yet: the caller
/// looks again shortly, rather than close a kept-alive connection for a newer silent one. Null
/// when nothing may be closed now.
std::shared_ptr<Session> Shared::quiet_longest() {
  const std::int64_t now = steady_ns();
  std::lock_guard lock(sessions_mu);
  Session* best = nullptr;
  bool best_served = true;
  std::int64_t best_since = 0;
  for (Session* s : sessions) {
    const Activity& a = s->activity();
    const int phase = a.phase.load(std::memory_order_relaxed);
    const std::int64_t since = a.quiet_since.load(std::memory_order_relaxed);
    if (phase == Activity::busy || (phase == Activity::receiving && !a.closable(now))) continue;
    const bool served = a.served.load(std::memory_order_relaxed);
    if (!best || (!served && best_served) || (served == best_served && since < best_since)) {
      best = s;
      best_served = served;
      best_since = since;
    }
  }
  if (!best || !best->activity().closable(now)) return nullptr;
  // Null also when it is being destroyed (its entry is erased first, under the lock).
  return best->weak_from_this().lock();
}

bool is_loopback(const net::ip::address& a) {
  return a.is_loopback() || (a.is_v4() && (a.to_v4().to_uint() >> 24) == 127);
}

}  // namespace

struct Server::Impl {
  Shared sh;
  // One io_context per connection thread, each run by its thread alone: a connection's reads,
  // handlers and writes stay on one thread, with no hand-offs between threads through a shared
  // scheduler (each one a futex wake: on a VM, an interrupt). iocs[0] also holds the acceptor.
  std::vector<std::unique_ptr<net::io_context>> iocs;
  std::vector<net::executor_work_guard<net::io_context::executor_type>> guards;
  std::size_t next = 0;  // the io_context of the next connection (round robin)
  tcp::acceptor acceptor;
  net::steady_timer backoff;
  // The conditions are logged once per episode: an episode ends when connections are accepted
  // normally again (below 90 % of the cap) a minute or more after it was logged, so that draining
  // a queue of waiting connections around the cap does not log it again.
  bool warned_cap = false;
  bool warned_fds = false;
  std::chrono::steady_clock::time_point noted_cap{}, noted_fds{};
  std::chrono::milliseconds delay{10};
  ~Impl() {
    // Answers still to come (saves waiting for their sync) post to iocs: wait for them first.
    while (sh.pending.load() > 0) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  Impl(Study& s, ServerOptions o)
      : sh(s, std::move(o)),
        iocs(make_iocs(std::max(1u, sh.opt.threads))),
        acceptor(*iocs[0]),
        backoff(*iocs[0]) {
    for (auto& c : iocs) guards.push_back(net::make_work_guard(*c));
  }

  static std::vector<std::unique_ptr<net::io_context>> make_iocs(unsigned n) {
    std::vector<std::unique_ptr<net::io_context>> v;
    for (unsigned i = 0; i < n; ++i) v.push_back(std::make_unique<net::io_context>(1));
    return v;
  }

  void stop_all() {
    for (auto& c : iocs) c->stop();
  }

  void note(bool& warned, std::chrono::steady_clock::time_point& when, const std::string& event,
            const std::string& text) {
    if (warned) return;
    warned = true;
    when = std::chrono::steady_clock::now();
    std::fprintf(stderr, "feint collect: %s\n", text.c_str());
    try {
      sh.study.record_event("", event, text);
    } catch (const std::exception&) {
    }
  }

  void wait_then_accept() {
    backoff.expires_after(delay);
    backoff.async_wait([this](beast::error_code ec) {
      if (!ec && acceptor.is_open()) accept();
    });
  }

  void accept() {
    // Over the cap by the connection just accepted: make room before accepting more.
    if (sh.connections.load() > sh.max_connections) return make_room();
    net::io_context& home = *iocs[next++ % iocs.size()];
    acceptor.async_accept(home, [this](beast::error_code ec, tcp::socket socket) {
      if (!ec) return accepted(std::move(socket));
      if (!acceptor.is_open() || ec == net::error::operation_aborted) return;
      if (ec == net::error::no_descriptors || ec.value() == ENFILE || ec == net::error::no_memory ||
          ec == net::error::no_buffer_space) {
        // Out of descriptors (files beyond the reserve, or the whole system): free one by closing
        // the connection quiet longest, if one may be closed, and back off instead of retrying at
        // once (which would spin on the same error): 10 ms doubling to 1 s.
        note(warned_fds, noted_fds, "descriptors_exhausted",
             fmt::format("cannot accept a connection: {}; closing the connection quiet longest "
                         "(if one may be closed) and retrying with back-off",
                         ec.message()));
        if (auto victim = sh.quiet_longest()) victim->make_room([] {});
        delay = std::min(std::chrono::milliseconds(1000), delay * 2);
      }
      wait_then_accept();
    });
  }

  void accepted(tcp::socket socket) {
    ++sh.connections;
    std::make_shared<Session>(std::move(socket), sh)->run();
    const auto now = std::chrono::steady_clock::now();
    if (sh.connections.load() < sh.max_connections * 9 / 10 &&
        now - noted_cap >= std::chrono::minutes(1))
      warned_cap = false;
    if (now - noted_fds >= std::chrono::minutes(1)) warned_fds = false;
    delay = std::chrono::milliseconds(10);
    if (acceptor.is_open()) accept();
  }

  /// At the cap a new connection is accepted (one descriptor over the cap, within the reserve) and
  /// the connection quiet longest is closed for it; accepting goes on once it is closed. When none
  /// may be closed (all busy or sending), new connections wait in the listen queue (no descriptor
  /// is spent on them) and this is tried again in 50 ms.
  void make_room() {
    note(warned_cap, noted_cap, "connections_capped",
         fmt::format("{} simultaneous connections (the cap): a new connection closes the one "
                     "quiet longest (never one being answered or sending a request)",
                     sh.max_connections));
    auto victim = sh.quiet_longest();
    if (!victim) {
      delay = std::chrono::milliseconds(50);
      return wait_then_accept();
    }
    victim->make_room([this] {
      net::post(*iocs[0], [this] {
        if (acceptor.is_open()) accept();
      });
    });
  }
};

Server::Server(Study& study, ServerOptions options)
    : impl_(std::make_unique<Impl>(study, std::move(options))) {
  auto& o = impl_->sh.opt;
  if (o.admin_token.empty()) {
    std::random_device rd;  // the kernel's generator (getrandom / /dev/urandom): 4 x 32 bits
    o.admin_token = fmt::format("{:08x}{:08x}{:08x}{:08x}", rd(), rd(), rd(), rd());
  }
  beast::error_code ec;
  const auto address = net::ip::make_address(o.host, ec);
  if (ec) throw UsageError(fmt::format("--host '{}': not an IP address", o.host));
  for (const auto& p : o.trusted_proxies) {
    net::ip::make_address(p, ec);
    if (ec) throw UsageError(fmt::format("--trusted-proxy '{}': not an IP address", p));
  }
  const tcp::endpoint ep(address, o.port);
  auto& a = impl_->acceptor;
  a.open(ep.protocol(), ec);
  if (!ec) a.set_option(net::socket_base::reuse_address(true), ec);
  if (!ec) a.bind(ep, ec);
  if (!ec) a.listen(net::socket_base::max_listen_connections, ec);
  if (ec) throw IoError(fmt::format("cannot listen on {}:{}: {}", o.host, o.port, ec.message()));
  auto& sh = impl_->sh;
  {
    rlimit rl{};
    const std::size_t reserve = reserved_descriptors(o.threads);
    const std::size_t limit =
        ::getrlimit(RLIMIT_NOFILE, &rl) == 0 && rl.rlim_cur != RLIM_INFINITY
            ? static_cast<std::size_t>(rl.rlim_cur)
            : std::size_t{1} << 20;
    // A larger --max-connections than the descriptors allow is lowered: connections beyond it
    // would take the descriptors the study's files need, and accept would fail with EMFILE.
    const std::size_t room = limit > reserve + 8 ? limit - reserve : 8;
    sh.max_connections = o.max_connections == 0 ? room : std::min(o.max_connections, room);
  }
  if (is_loopback(address) || !o.allowed_hosts.empty()) {
    sh.allowed_hosts = o.allowed_hosts;
    if (is_loopback(address)) {
      const std::string port = std::to_string(port_of());
      for (const char* h : {"localhost", "127.0.0.1", "[::1]"}) {
        sh.allowed_hosts.emplace_back(h);  // the Host header without a port
        sh.allowed_hosts.push_back(std::string(h) + ":" + port);
      }
    }
  }
  // A file-size limit (ulimit -f) makes a write fail with EFBIG instead of killing the server.
  std::signal(SIGXFSZ, SIG_IGN);
  // Every round allocates and frees some 50 kB (its body, samples and rows) on the connection
  // threads' malloc arenas; glibc would give the freed top of an arena back to the kernel each
  // time (madvise) and fault it in again at the next round: a sixth of the server's CPU time in
  // collect_load. The process keeps what it used instead (bounded by its peak).
  mallopt(M_TRIM_THRESHOLD, 256 << 20);
  mallopt(M_TOP_PAD, 16 << 20);
  mallopt(M_MMAP_THRESHOLD, 4 << 20);
}

Server::~Server() = default;

unsigned short Server::port_of() const noexcept { return impl_->acceptor.local_endpoint().port(); }
unsigned short Server::port() const noexcept { return port_of(); }
const std::string& Server::admin_token() const noexcept { return impl_->sh.opt.admin_token; }
std::size_t Server::max_connections() const noexcept { return impl_->sh.max_connections; }
ServerState& Server::state() noexcept { return impl_->sh.state; }

void Server::run() {
  impl_->accept();
  std::optional<net::signal_set> signals;
  if (impl_->sh.opt.stop_on_signals) {
    signals.emplace(*impl_->iocs[0], SIGINT, SIGTERM);
    signals->async_wait([this](beast::error_code, int) { impl_->stop_all(); });
  }
  std::vector<std::thread> pool;
  for (std::size_t i = 1; i < impl_->iocs.size(); ++i)
    pool.emplace_back([this, i] { impl_->iocs[i]->run(); });
  impl_->iocs[0]->run();
  for (auto& t : pool) t.join();
}

void Server::stop() { impl_->stop_all(); }

}  // namespace feint::collect
