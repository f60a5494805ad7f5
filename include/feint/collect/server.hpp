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
// STUDY/collect/events.csv.
#pragma once

#include <chrono>
#include <cstddef>
#include <functional>
#include <memory>
#include <string>

#include "feint/collect/study.hpp"

namespace feint::collect {

struct ServerOptions {
  std::string host = "127.0.0.1";
  unsigned short port = 8080;  // 0: an ephemeral port (see Server::port())
  std::string admin_token;     // empty: a random one
  unsigned threads = 4;
  std::size_t body_limit = 2 * 1024 * 1024;  // bytes per request body
  std::chrono::seconds timeout{30};          // to read one request
  bool stop_on_signals = false;              // SIGINT/SIGTERM make run() return
};

/// A response before it is put on the wire (also what the in-process tests look at).
struct Response {
  int status = 200;
  std::string content_type = "application/json";
  std::string body;
};

/// Answers one request. `target` is the request target (path and query). Never throws.
Response handle_request(Study& study, const std::string& admin_token, const std::string& method,
                        const std::string& target, const std::string& body);

class Server {
 public:
  /// Binds and listens (throws IoError when it cannot). Does not serve until run().
  Server(Study& study, ServerOptions options);
  ~Server();
  unsigned short port() const noexcept;
  const std::string& admin_token() const noexcept;
  /// Serves on `threads` threads until stop().
  void run();
  /// Thread-safe; makes run() return.
  void stop();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace feint::collect
