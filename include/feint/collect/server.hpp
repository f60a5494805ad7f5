// feint/collect/server.hpp - the HTTP server of `feint collect` (Boost.Beast over Boost.Asio).
//
// Routes (docs/collect.md, "HTTP interface"):
//   GET  /                       the game page (embedded; no other file is ever served)
//   GET  /admin?token=T          the admin page;  GET /api/admin?token=T  the same as JSON
//   POST /api/join?participant=ID | PROLIFIC_PID=ID | (none: generated)
//   POST /api/round/start?participant=ID
//   POST /api/round/submit?participant=ID&kind=practice|main&iteration=N   body: "t,pad" lines
//   POST /api/questionnaire?participant=ID                                  body: item=value&...
// Errors are JSON {"error": code, "message": text} with a 4xx status, and are recorded in
// STUDY/collect/events.csv (rate-limited per client); a write that fails (disk full) gives 503
// "could not save, please wait" and the page retries.
#pragma once

#include <chrono>
#include <cstddef>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "feint/collect/study.hpp"

namespace feint::collect {

struct ServerOptions {
  std::string host = "127.0.0.1";
  unsigned short port = 8080;  // 0: an ephemeral port (see Server::port())
  std::string admin_token;     // empty: a random one
  /// Threads running the connections. None of them waits for a disk (a save is answered when
  /// its group is synced, from the committer's thread), so about one per core is enough.
  unsigned threads = 4;
  std::size_t body_limit = 2 * 1024 * 1024;  // bytes per request body
  std::chrono::seconds timeout{30};          // to read one request
  std::chrono::seconds idle_timeout{10};     // a kept-alive connection waiting for its next request
  /// Simultaneous connections; 0 (or more than fits): the descriptor limit (RLIMIT_NOFILE) less a
  /// reserve for the files the server writes (reserved_descriptors()). At the cap, a new
  /// connection is accepted and the connection quiet longest is closed for it (never one whose
  /// request is being handled or answered, nor one that received a byte, was answered or was
  /// accepted within the last second); when none may be closed, new connections wait in the
  /// listen queue.
  std::size_t max_connections = 0;
  /// Accepted `Host` headers (DNS-rebinding defence): NAME or NAME:PORT, case-insensitive. When
  /// bound to a loopback address, localhost, 127.0.0.1 and [::1] (without a port or with the
  /// server's) are always accepted and any other host gets 421; on another address the check is
  /// made only when this list is not empty.
  std::vector<std::string> allowed_hosts;
  /// Peers (IP addresses, e.g. the reverse proxy's 127.0.0.1) whose X-Forwarded-For is believed:
  /// the client's address is then the rightmost X-Forwarded-For entry that is not itself trusted.
  std::vector<std::string> trusted_proxies;
  int rejections_per_minute = 20;  // `rejected` lines per client and minute in the events log
  bool stop_on_signals = false;    // SIGINT/SIGTERM make run() return
};

/// Descriptors kept free of connections for the files the server writes (logs, events, folders).
std::size_t reserved_descriptors(unsigned threads) noexcept;

/// A response before it is put on the wire (also what the in-process tests look at).
struct Response {
  int status = 200;
  std::string content_type = "application/json";
  std::string body;
};

/// What the server remembers between requests: how many rejections each client had this minute
/// (the events log gets at most `per_minute` `rejected` lines per client and minute, then one
/// `rate_limited` line, and the count of the ones not written when the client is next refused
/// after the minute), and the last failed write (the admin page's red banner). Thread-safe.
class ServerState {
 public:
  explicit ServerState(int rejections_per_minute = 20);
  ~ServerState();
  /// Records a rejection of `client` in the events log, rate-limited. Never throws.
  /// With `then`, it does not wait: `then` is called once the lines are synced (or at once when
  /// none is written).
  void record_rejection(Study& study, const std::string& client, const std::string& participant,
                        const std::string& detail, std::function<void()> then = {});
  void write_failed(const std::string& what);
  void write_succeeded();
  struct WriteFailure {
    std::string what;
    std::string since_utc;
    long attempts = 0;
  };
  /// The write failure not yet followed by a successful save, if any.
  std::optional<WriteFailure> write_failure() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Who sent a request (after X-Forwarded-For from a trusted proxy) and the server's memory.
struct RequestInfo {
  std::string client;             // an IP address, or "" (in-process callers)
  ServerState* state = nullptr;   // null: rejections are logged without a rate limit
};

using Reply = std::function<void(Response)>;

/// Answers one request: `reply` is called once, when the answer is known (for a save: once it is
/// synced), on the calling thread or on the group committer's completion thread; nothing waits
/// for a disk meanwhile. `target` is the request target (path and query). Never throws.
void handle_request(Study& study, const std::string& admin_token, const std::string& method,
                    const std::string& target, std::string body, const RequestInfo& info,
                    Reply reply);

/// The same, waiting for the answer (tests, in-process callers).
Response handle_request(Study& study, const std::string& admin_token, const std::string& method,
                        const std::string& target, const std::string& body,
                        const RequestInfo& info = {});

/// Whether a Host header value is among `allowed` (NAME matches NAME and NAME:any port).
bool host_allowed(const std::vector<std::string>& allowed, std::string_view host);

/// The client's address: `peer`, or, when `peer` is a trusted proxy, the rightmost entry of
/// `forwarded_for` (X-Forwarded-For) that is not itself a trusted proxy.
std::string client_address(const std::string& peer, std::string_view forwarded_for,
                           const std::vector<std::string>& trusted_proxies);

class Server {
 public:
  /// Binds and listens (throws IoError when it cannot). Does not serve until run().
  /// It also sets two process-wide things a long-running server needs, which a program embedding
  /// it should know about: SIGXFSZ is ignored (a file-size limit makes a write fail with EFBIG
  /// instead of killing the process), and glibc's malloc keeps freed memory up to 256 MB instead of
  /// returning it to the kernel after every round (mallopt M_TRIM_THRESHOLD, M_TOP_PAD,
  /// M_MMAP_THRESHOLD; docs/collect.md).
  Server(Study& study, ServerOptions options);
  ~Server();
  unsigned short port() const noexcept;
  const std::string& admin_token() const noexcept;
  /// The connection cap in force (ServerOptions::max_connections or the one derived from it).
  std::size_t max_connections() const noexcept;
  ServerState& state() noexcept;
  /// Serves on `threads` threads until stop().
  void run();
  /// Thread-safe; makes run() return.
  void stop();

 private:
  unsigned short port_of() const noexcept;
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace feint::collect
