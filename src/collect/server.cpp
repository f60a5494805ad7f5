// The HTTP server of `feint collect` (feint/collect/server.hpp): request handling and the
// Boost.Beast connection loop (modelled on Beast's http_server_async example).
#include "feint/collect/server.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/signal_set.hpp>
#include <boost/asio/strand.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <csignal>
#include <map>
#include <optional>
#include <random>
#include <thread>
#include <vector>

#include "assets.hpp"
#include "durable.hpp"
#include "feint/error.hpp"
#include "feint/io/html_escape.hpp"
#include "feint/io/number.hpp"

namespace feint::collect {

namespace beast = boost::beast;
namespace http = beast::http;
namespace net = boost::asio;
using tcp = net::ip::tcp;

namespace {

std::string_view asset(std::string_view name) {
  for (std::size_t i = 0; i < detail::kAssetCount; ++i) {
    if (detail::kAssets[i].name == name) return detail::kAssets[i].data;
  }
  return {};
}

int hex(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

/// application/x-www-form-urlencoded decoding; nullopt on a bad escape.
std::optional<std::string> url_decode(std::string_view s) {
  std::string out;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (s[i] == '+') {
      out += ' ';
    } else if (s[i] == '%') {
      if (i + 2 >= s.size()) return std::nullopt;
      const int a = hex(s[i + 1]), b = hex(s[i + 2]);
      if (a < 0 || b < 0) return std::nullopt;
      out += static_cast<char>(a * 16 + b);
      i += 2;
    } else {
      out += s[i];
    }
  }
  return out;
}

std::map<std::string, std::string> parse_form(std::string_view q) {
  std::map<std::string, std::string> out;
  while (!q.empty()) {
    const auto amp = q.find('&');
    const std::string_view pair = q.substr(0, amp);
    q = amp == std::string_view::npos ? std::string_view() : q.substr(amp + 1);
    if (pair.empty()) continue;
    const auto eq = pair.find('=');
    const auto k = url_decode(pair.substr(0, eq));
    const auto v =
        url_decode(eq == std::string_view::npos ? std::string_view() : pair.substr(eq + 1));
    if (!k || !v) throw Rejection(400, "malformed", "a query or form field is not URL-encoded");
    if (out.count(*k)) throw Rejection(400, "malformed", fmt::format("field '{}' given twice", *k));
    out[*k] = *v;
  }
  return out;
}

std::string json_array(const std::vector<double>& v) {
  std::string s = "[";
  for (std::size_t i = 0; i < v.size(); ++i) {
    if (i) s += ',';
    s += io::json_number(v[i]);
  }
  return s + "]";
}

std::string_view stage_name(Stage s) {
  switch (s) {
    case Stage::consent:
      return "consent";
    case Stage::rounds:
      return "rounds";
    case Stage::questionnaire:
      return "questionnaire";
    case Stage::done:
      return "done";
  }
  return "rounds";
}

std::string status_json(const Study& study, const ParticipantStatus& st) {
  const Settings& s = study.settings();
  std::string items = "[";
  for (std::size_t i = 0; i < s.items.size(); ++i) {
    if (i) items += ',';
    items += fmt::format("{{\"name\":{},\"question\":{}}}", io::json_quote(s.items[i]),
                         io::json_quote(s.item_questions[i]));
  }
  items += "]";
  const std::string yes_no = s.yes_no_item.empty() ? "null"
                                                   : fmt::format("{{\"name\":{},\"question\":{}}}",
                                                                 io::json_quote(s.yes_no_item),
                                                                 io::json_quote(s.yes_no_question));
  return fmt::format(
      "{{\"participant\":{},\"stage\":\"{}\",\"practice\":{},\"iterations\":{},\"practice_saved\":{"
      "},"
      "\"rounds_saved\":{},\"pad_speed\":{},\"target_distance\":{},\"target_height\":{},"
      "\"consent\":{},\"completion_url\":{},\"items\":{},\"yes_no\":{}}}",
      io::json_quote(st.id), stage_name(study.stage(st)), s.practice, s.iterations,
      st.practice_saved, st.rounds_saved, io::json_number(s.pad_speed),
      io::json_number(s.geometry.target_distance), io::json_number(s.geometry.target_height),
      io::json_quote(s.consent), io::json_quote(s.completion_url), items, yes_no);
}

using io::html_escape;

std::string age(std::int64_t last_seen) {
  if (last_seen == 0) return "before restart";
  const auto d = detail::unix_now() - last_seen;
  if (d < 60) return fmt::format("{} s ago", d);
  if (d < 3600) return fmt::format("{} min ago", d / 60);
  return fmt::format("{} h ago", d / 3600);
}

Response admin_page(const Study& study, const std::string& token) {
  const auto all = study.overview();
  const Settings& s = study.settings();
  std::map<std::string, int> per_condition;
  int complete = 0;
  for (const auto& p : all) {
    ++per_condition[p.condition];
    if (p.questionnaire_done) ++complete;
  }
  std::string rows;
  for (const auto& p : all) {
    const char* state = p.questionnaire_done
                            ? "done"
                            : (p.rounds_saved == s.iterations ? "questionnaire" : "playing");
    rows += fmt::format(
        "<tr class=\"{}\"><td>{}</td><td>{}</td><td class=\"n\">{} / {}</td><td class=\"n\">{} / "
        "{}</td>"
        "<td>{}</td><td class=\"n\">{}</td><td>{}</td></tr>\n",
        state, html_escape(p.id), html_escape(p.condition), p.practice_saved, s.practice,
        p.rounds_saved, s.iterations, p.questionnaire_done ? "yes" : "no", p.interruptions,
        age(p.last_seen_unix));
  }
  std::string conds;
  for (const auto& c : s.conditions) {
    const int n = per_condition[c.name];
    conds += fmt::format("<li><b>{}</b>: {} participant{}</li>", html_escape(c.name), n,
                         n == 1 ? "" : "s");
  }
  std::string page(asset("admin.html"));
  auto put = [&](std::string_view key, const std::string& value) {
    const auto pos = page.find(key);
    if (pos != std::string::npos) page.replace(pos, key.size(), value);
  };
  put("{{study}}", html_escape(study.dir().filename().string()));
  put("{{participants}}", std::to_string(all.size()));
  put("{{complete}}", std::to_string(complete));
  put("{{conditions}}", conds);
  put("{{rows}}", rows.empty() ? "<tr><td colspan=\"7\">nobody has joined yet</td></tr>" : rows);
  put("{{token}}", html_escape(token));
  put("{{time}}", detail::utc_now());
  return {200, "text/html; charset=utf-8", page};
}

Response admin_json(const Study& study) {
  std::string body = "{\"participants\":[";
  bool first = true;
  for (const auto& p : study.overview()) {
    if (!first) body += ',';
    first = false;
    body += fmt::format(
        "{{\"participant\":{},\"condition\":{},\"practice_saved\":{},\"rounds_saved\":{},"
        "\"questionnaire_done\":{},\"interruptions\":{},\"last_seen_unix\":{}}}",
        io::json_quote(p.id), io::json_quote(p.condition), p.practice_saved, p.rounds_saved,
        p.questionnaire_done ? "true" : "false", p.interruptions, p.last_seen_unix);
  }
  return {200, "application/json", body + "]}"};
}

std::vector<PadSample> parse_trace(std::string_view body) {
  std::vector<PadSample> out;
  std::size_t line = 0;
  while (!body.empty()) {
    ++line;
    const auto nl = body.find('\n');
    std::string_view l = body.substr(0, nl);
    body = nl == std::string_view::npos ? std::string_view() : body.substr(nl + 1);
    if (!l.empty() && l.back() == '\r') l.remove_suffix(1);
    if (l.empty()) continue;
    const auto comma = l.find(',');
    const auto t =
        comma == std::string_view::npos ? std::nullopt : io::parse_double(l.substr(0, comma));
    const auto pad =
        comma == std::string_view::npos ? std::nullopt : io::parse_double(l.substr(comma + 1));
    if (!t || !pad) {
      throw Rejection(400, "malformed", fmt::format("trace line {}: expected 't,pad'", line));
    }
    out.push_back({*t, *pad});
  }
  return out;
}

bool constant_time_equal(const std::string& a, const std::string& b) {
  if (a.size() != b.size()) return false;
  unsigned char d = 0;
  for (std::size_t i = 0; i < a.size(); ++i) d |= static_cast<unsigned char>(a[i] ^ b[i]);
  return d == 0;
}

}  // namespace

Response handle_request(Study& study, const std::string& admin_token, const std::string& method,
                        const std::string& target, const std::string& body) {
  const auto q = target.find('?');
  const std::string path = target.substr(0, q);
  std::string participant;
  try {
    const auto query = parse_form(q == std::string::npos ? std::string_view()
                                                         : std::string_view(target).substr(q + 1));
    auto arg = [&](const char* name) {
      auto it = query.find(name);
      return it == query.end() ? std::string() : it->second;
    };
    participant = arg("participant");
    if (method == "GET" || method == "HEAD") {
      if (path == "/" || path == "/index.html")
        return {200, "text/html; charset=utf-8", std::string(asset("game.html"))};
      if (path == "/game.js")
        return {200, "text/javascript; charset=utf-8", std::string(asset("game.js"))};
      if (path == "/game.css")
        return {200, "text/css; charset=utf-8", std::string(asset("game.css"))};
      if (path == "/favicon.ico") return {204, "image/x-icon", ""};  // browsers ask for it
      if (path == "/admin" || path == "/api/admin") {
        if (!constant_time_equal(arg("token"), admin_token)) {
          throw Rejection(403, "forbidden", "the admin page needs the token printed at start-up");
        }
        return path == "/admin" ? admin_page(study, admin_token) : admin_json(study);
      }
      if (path.rfind("/api/", 0) == 0) throw Rejection(405, "method", "use POST for " + path);
      throw Rejection(404, "not_found", "no such page");
    }
    if (method != "POST") throw Rejection(405, "method", "only GET and POST are served");
    if (path == "/api/join") {
      if (participant.empty()) participant = arg("PROLIFIC_PID");
      const auto st = study.join(participant);
      participant = st.id;
      return {200, "application/json", status_json(study, st)};
    }
    if (path == "/api/round/start") {
      const Round r = study.start_round(participant);
      std::vector<double> t, x, y;
      for (const auto& p : r.path) {
        t.push_back(p.t);
        x.push_back(p.x);
        y.push_back(p.y);
      }
      const int total =
          r.kind == RoundKind::practice ? study.settings().practice : study.settings().iterations;
      return {200, "application/json",
              fmt::format("{{\"kind\":\"{}\",\"iteration\":{},\"of\":{},\"duration\":{},\"t\":{},"
                          "\"x\":{},\"y\":{}}}",
                          to_string(r.kind), r.iteration, total, io::json_number(r.duration()),
                          json_array(t), json_array(x), json_array(y))};
    }
    if (path == "/api/round/submit") {
      const std::string kind = arg("kind");
      if (kind != "practice" && kind != "main")
        throw Rejection(400, "malformed", "kind must be practice or main");
      const auto it = io::parse_integer(arg("iteration"));
      if (!it || *it < 1 || *it > 100000)
        throw Rejection(400, "malformed", "iteration must be a whole number >= 1");
      const auto samples = parse_trace(body);
      const auto st = study.submit_round(participant,
                                         kind == "practice" ? RoundKind::practice : RoundKind::main,
                                         static_cast<int>(*it), samples);
      return {200, "application/json", status_json(study, st)};
    }
    if (path == "/api/questionnaire") {
      const auto st = study.submit_questionnaire(participant, parse_form(body));
      return {200, "application/json", status_json(study, st)};
    }
    throw Rejection(404, "not_found", "no such page");
  } catch (const Rejection& r) {
    try {
      const std::string who = valid_participant_id(participant) ? participant : "";
      if (r.status() != 404 || path.rfind("/api/", 0) == 0) {
        study.record_event(
            who, "rejected",
            fmt::format("{} {} {} {}: {}", method, path, r.status(), r.code(), r.what()));
      }
    } catch (const std::exception&) {
      // The events log could not be written: the client still gets its answer.
    }
    return {r.status(), "application/json",
            fmt::format("{{\"error\":{},\"message\":{}}}", io::json_quote(r.code()),
                        io::json_quote(r.what()))};
  } catch (const std::exception& e) {
    // A file could not be written (disk full...): the round is NOT saved, the page retries.
    try {
      study.record_event(valid_participant_id(participant) ? participant : "", "server_error",
                         e.what());
    } catch (const std::exception&) {
    }
    return {503, "application/json",
            fmt::format("{{\"error\":\"server_error\",\"message\":{}}}", io::json_quote(e.what()))};
  }
}

// ---- the connection loop --------------------------------------------------------------------

namespace {

class Session : public std::enable_shared_from_this<Session> {
 public:
  Session(tcp::socket&& socket, Study& study, const ServerOptions& opt)
      : stream_(std::move(socket)), study_(study), opt_(opt) {}

  void run() {
    net::dispatch(stream_.get_executor(),
                  beast::bind_front_handler(&Session::read, shared_from_this()));
  }

 private:
  void read() {
    parser_.emplace();
    parser_->body_limit(opt_.body_limit);
    parser_->header_limit(16 * 1024);
    stream_.expires_after(opt_.timeout);
    http::async_read(stream_, buffer_, *parser_,
                     beast::bind_front_handler(&Session::on_read, shared_from_this()));
  }

  void on_read(beast::error_code ec, std::size_t) {
    if (ec == http::error::end_of_stream || ec == beast::error::timeout ||
        ec == net::error::operation_aborted) {
      return close();
    }
    if (ec) {
      Response r;
      if (ec == http::error::body_limit || ec == http::error::header_limit) {
        r = {413, "application/json",
             fmt::format("{{\"error\":\"too_large\",\"message\":\"request larger than {} bytes\"}}",
                         opt_.body_limit)};
        try {
          study_.record_event("", "rejected", fmt::format("413 too_large: {}", ec.message()));
        } catch (const std::exception&) {
        }
      } else {
        r = {400, "application/json",
             "{\"error\":\"malformed\",\"message\":\"not an HTTP request\"}"};
      }
      return send(r, false, 11);
    }
    auto req = parser_->release();
    const Response r = handle_request(study_, opt_.admin_token, std::string(req.method_string()),
                                      std::string(req.target()), req.body());
    send(r, req.keep_alive(), req.version(), req.method() == http::verb::head);
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
    res->keep_alive(keep_alive);
    if (!head) res->body() = r.body;
    res->prepare_payload();
    if (head) res->body().clear();
    stream_.expires_after(opt_.timeout);
    http::async_write(
        stream_, *res,
        [self = shared_from_this(), res, keep_alive](beast::error_code ec, std::size_t) {
          if (ec || !keep_alive) return self->close();
          self->read();
        });
  }

  void close() {
    beast::error_code ec;
    stream_.socket().shutdown(tcp::socket::shutdown_send, ec);
  }

  beast::tcp_stream stream_;
  beast::flat_buffer buffer_;
  std::optional<http::request_parser<http::string_body>> parser_;
  Study& study_;
  const ServerOptions& opt_;
};

}  // namespace

struct Server::Impl {
  Study& study;
  ServerOptions opt;
  net::io_context ioc;
  tcp::acceptor acceptor;
  Impl(Study& s, ServerOptions o)
      : study(s),
        opt(std::move(o)),
        ioc(static_cast<int>(std::max(1u, opt.threads))),
        acceptor(net::make_strand(ioc)) {}

  void accept() {
    acceptor.async_accept(net::make_strand(ioc), [this](beast::error_code ec, tcp::socket socket) {
      if (!ec) std::make_shared<Session>(std::move(socket), study, opt)->run();
      if (acceptor.is_open()) accept();
    });
  }
};

Server::Server(Study& study, ServerOptions options)
    : impl_(std::make_unique<Impl>(study, std::move(options))) {
  auto& o = impl_->opt;
  if (o.admin_token.empty()) {
    std::random_device rd;  // the kernel's generator (getrandom / /dev/urandom): 4 x 32 bits
    o.admin_token = fmt::format("{:08x}{:08x}{:08x}{:08x}", rd(), rd(), rd(), rd());
  }
  beast::error_code ec;
  const auto address = net::ip::make_address(o.host, ec);
  if (ec) throw UsageError(fmt::format("--host '{}': not an IP address", o.host));
  const tcp::endpoint ep(address, o.port);
  auto& a = impl_->acceptor;
  a.open(ep.protocol(), ec);
  if (!ec) a.set_option(net::socket_base::reuse_address(true), ec);
  if (!ec) a.bind(ep, ec);
  if (!ec) a.listen(net::socket_base::max_listen_connections, ec);
  if (ec) throw IoError(fmt::format("cannot listen on {}:{}: {}", o.host, o.port, ec.message()));
}

Server::~Server() = default;

unsigned short Server::port() const noexcept { return impl_->acceptor.local_endpoint().port(); }
const std::string& Server::admin_token() const noexcept { return impl_->opt.admin_token; }

void Server::run() {
  impl_->accept();
  std::optional<net::signal_set> signals;
  if (impl_->opt.stop_on_signals) {
    signals.emplace(impl_->ioc, SIGINT, SIGTERM);
    signals->async_wait([this](beast::error_code, int) { impl_->ioc.stop(); });
  }
  std::vector<std::thread> pool;
  for (unsigned i = 1; i < std::max(1u, impl_->opt.threads); ++i)
    pool.emplace_back([this] { impl_->ioc.run(); });
  impl_->ioc.run();
  for (auto& t : pool) t.join();
}

void Server::stop() { impl_->ioc.stop(); }

}  // namespace feint::collect
