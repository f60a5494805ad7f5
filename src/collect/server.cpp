// The HTTP server of `feint collect` (feint/collect/server.hpp): request handling, the admin page,
// the rate limit of the events log, Host and X-Forwarded-For parsing. The connection loop is in
// connections.cpp.
#include "feint/collect/server.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <future>
#include <iterator>
#include <boost/asio/ip/tcp.hpp>
#include <boost/beast/core.hpp>
#include <map>
#include <mutex>
#include <optional>
#include <vector>

#include "assets.hpp"
#include "durable.hpp"
#include "feint/error.hpp"
#include "feint/io/html_escape.hpp"
#include "feint/io/number.hpp"

namespace feint::collect {

namespace beast = boost::beast;
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

/// `,"name":[v0,v1,...]` of one coordinate of a path, appended without temporaries.
void json_array(std::string& out, std::string_view name,
                const std::vector<sim::TrajectorySample>& path,
                double sim::TrajectorySample::*coordinate) {
  out += ",\"";
  out += name;
  out += "\":[";
  for (std::size_t i = 0; i < path.size(); ++i) {
    if (i) out += ',';
    const double v = path[i].*coordinate;
    if (std::isfinite(v)) {
      detail::append_double(out, v);  // io::json_number()
    } else {
      out += "null";
    }
  }
  out += ']';
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
  std::string out = fmt::format(
      "{{\"participant\":{},\"stage\":\"{}\",\"practice\":{},\"iterations\":{},\"practice_saved\":{"
      "},"
      "\"rounds_saved\":{},\"pad_speed\":{},\"target_distance\":{},\"target_height\":{},"
      "\"consent\":{},\"completion_url\":{},\"items\":{},\"yes_no\":{}}}",
      io::json_quote(st.id), stage_name(study.stage(st)), s.practice, s.iterations,
      st.practice_saved, st.rounds_saved, io::json_number(s.pad_speed),
      io::json_number(s.geometry.target_distance), io::json_number(s.geometry.target_height),
      io::json_quote(s.consent), io::json_quote(s.completion_url), items, yes_no);
  if (s.belief == BeliefInput::pointer) {  // the page draws the map in these bounds (metres)
    const MapBounds b = map_bounds(s);
    out.pop_back();
    out += fmt::format(
        ",\"belief\":\"pointer\",\"targets\":{},\"sample_rate\":{},"
        "\"map\":{{\"x_min\":{},\"x_max\":{},\"y_min\":{},\"y_max\":{}}}}}",
        s.targets, io::json_number(s.geometry.sample_rate), io::json_number(b.x_min),
        io::json_number(b.x_max), io::json_number(b.y_min), io::json_number(b.y_max));
  }
  return out;
}

using io::html_escape;

std::string age(std::int64_t last_seen) {
  if (last_seen == 0) return "before restart";
  const auto d = detail::unix_now() - last_seen;
  if (d < 60) return fmt::format("{} s ago", d);
  if (d < 3600) return fmt::format("{} min ago", d / 60);
  return fmt::format("{} h ago", d / 3600);
}

Response admin_page(const Study& study, const std::string& token,
                    const std::optional<ServerState::WriteFailure>& failure) {
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
  put("{{banner}}",
      failure ? fmt::format("<p id=\"write-failure\" class=\"alarm\" role=\"alert\"><b>Saving "
                            "fails</b> since {} ({} attempt{}): {}. Participants see &ldquo;could "
                            "not save, please wait&rdquo; and their pages retry; nothing they were "
                            "told is saved is lost. Free disk space (or fix the folder) and the "
                            "study carries on by itself.</p>",
                            failure->since_utc, failure->attempts, failure->attempts == 1 ? "" : "s",
                            html_escape(failure->what))
              : std::string());
  return {200, "text/html; charset=utf-8", page};
}

Response admin_json(const Study& study,
                    const std::optional<ServerState::WriteFailure>& failure) {
  std::string body = fmt::format(
      "{{\"write_failure\":{},\"participants\":[",
      failure ? fmt::format("{{\"since\":{},\"attempts\":{},\"what\":{}}}",
                            io::json_quote(failure->since_utc), failure->attempts,
                            io::json_quote(failure->what))
              : std::string("null"));
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

// Calls f(line number, line) for each non-empty line of a trace body (LF or CRLF).
template <typename F>
void for_each_body_line(std::string_view body, F&& f) {
  std::size_t line = 0;
  while (!body.empty()) {
    ++line;
    const auto nl = body.find('\n');
    std::string_view l = body.substr(0, nl);
    body = nl == std::string_view::npos ? std::string_view() : body.substr(nl + 1);
    if (!l.empty() && l.back() == '\r') l.remove_suffix(1);
    if (!l.empty()) f(line, l);
  }
}

std::vector<PadSample> parse_trace(std::string_view body) {
  std::vector<PadSample> out;
  for_each_body_line(body, [&](std::size_t line, std::string_view l) {
    const auto comma = l.find(',');
    const auto t =
        comma == std::string_view::npos ? std::nullopt : io::parse_double(l.substr(0, comma));
    const auto pad =
        comma == std::string_view::npos ? std::nullopt : io::parse_double(l.substr(comma + 1));
    if (!t || !pad) {
      throw Rejection(400, "malformed", fmt::format("trace line {}: expected 't,pad'", line));
    }
    out.push_back({*t, *pad});
  });
  return out;
}

/// A pointer study's body: lines `t,x,y` (metres on the map).
std::vector<PointerSample> parse_pointer_trace(std::string_view body) {
  std::vector<PointerSample> out;
  for_each_body_line(body, [&](std::size_t line, std::string_view l) {
    const auto c1 = l.find(',');
    const auto c2 = c1 == std::string_view::npos ? c1 : l.find(',', c1 + 1);
    std::optional<double> v[3];
    if (c2 != std::string_view::npos) {
      v[0] = io::parse_double(l.substr(0, c1));
      v[1] = io::parse_double(l.substr(c1 + 1, c2 - c1 - 1));
      v[2] = io::parse_double(l.substr(c2 + 1));
    }
    if (!v[0] || !v[1] || !v[2])
      throw Rejection(400, "malformed", fmt::format("trace line {}: expected 't,x,y'", line));
    out.push_back({*v[0], *v[1], *v[2]});
  });
  return out;
}

bool constant_time_equal(const std::string& a, const std::string& b) {
  if (a.size() != b.size()) return false;
  unsigned char d = 0;
  for (std::size_t i = 0; i < a.size(); ++i) d |= static_cast<unsigned char>(a[i] ^ b[i]);
  return d == 0;
}

std::string lower(std::string_view s) {
  std::string out(s);
  for (auto& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

/// NAME and PORT of a Host header value or an allowed-host entry ("[::1]:8080" -> "[::1]", "8080").
std::pair<std::string, std::string> split_host(std::string_view h) {
  std::string_view name = h, port;
  if (!h.empty() && h.front() == '[') {
    const auto close = h.find(']');
    if (close != std::string_view::npos) {
      name = h.substr(0, close + 1);
      if (close + 1 < h.size() && h[close + 1] == ':') port = h.substr(close + 2);
    }
  } else if (const auto colon = h.rfind(':'); colon != std::string_view::npos &&
                                               h.find(':') == colon) {
    name = h.substr(0, colon);
    port = h.substr(colon + 1);
  }
  return {lower(name), std::string(port)};
}

}  // namespace

bool host_allowed(const std::vector<std::string>& allowed, std::string_view host) {
  const auto [name, port] = split_host(host);
  if (name.empty()) return false;
  for (const auto& a : allowed) {
    const auto [an, ap] = split_host(a);
    if (an == name && (ap.empty() || port.empty() || ap == port)) return true;
  }
  return false;
}

std::string client_address(const std::string& peer, std::string_view forwarded_for,
                           const std::vector<std::string>& trusted) {
  auto is_trusted = [&](std::string_view a) {
    return std::find(trusted.begin(), trusted.end(), a) != trusted.end();
  };
  if (!is_trusted(peer) || forwarded_for.empty()) return peer;
  std::string_view rest = forwarded_for;
  while (!rest.empty()) {
    const auto comma = rest.rfind(',');
    std::string_view a = comma == std::string_view::npos ? rest : rest.substr(comma + 1);
    rest = comma == std::string_view::npos ? std::string_view() : rest.substr(0, comma);
    while (!a.empty() && (a.front() == ' ' || a.front() == '\t')) a.remove_prefix(1);
    while (!a.empty() && (a.back() == ' ' || a.back() == '\t')) a.remove_suffix(1);
    if (a.empty() || is_trusted(a)) continue;
    beast::error_code ec;
    const auto ip = net::ip::make_address(std::string(a), ec);
    return ec ? peer : ip.to_string();  // a forged, non-address entry is not believed
  }
  return peer;
}

std::size_t reserved_descriptors(unsigned threads) noexcept {
  // The files of one commit group are open together until its sync.
  return 32 + detail::GroupCommitter::kMaxGroupFiles + 4 * std::size_t{threads};
}

struct ServerState::Impl {
  int per_minute;
  struct Client {
    std::int64_t minute = 0;
    long count = 0;
  };
  std::mutex mu;
  std::map<std::string, Client> clients;
  mutable std::mutex health_mu;
  std::optional<WriteFailure> failure;
};

ServerState::ServerState(int per_minute) : impl_(std::make_unique<Impl>()) {
  impl_->per_minute = std::max(1, per_minute);
}
ServerState::~ServerState() = default;

void ServerState::record_rejection(Study& study, const std::string& client,
                                   const std::string& participant, const std::string& detail,
                                   std::function<void()> then) {
  constexpr std::size_t kMaxClients = 4096;  // beyond, the clients share one count
  const std::int64_t minute = detail::unix_now() / 60;
  long count = 0, not_logged = 0;
  {
    std::lock_guard lock(impl_->mu);
    if (impl_->clients.size() >= kMaxClients) {
      for (auto it = impl_->clients.begin(); it != impl_->clients.end();)
        it = it->second.minute == minute ? std::next(it) : impl_->clients.erase(it);
    }
    const std::string key = impl_->clients.size() >= kMaxClients && !impl_->clients.count(client)
                                ? std::string("(other clients)")
                                : client;
    auto& c = impl_->clients[key];
    if (c.minute != minute) {
      not_logged = std::max(0L, c.count - impl_->per_minute - 1);
      c = {minute, 0};
    }
    count = ++c.count;
  }
  const std::string from = client.empty() ? "" : "from " + client + ": ";
  std::vector<std::pair<std::string, std::string>> events;  // event, detail
  if (not_logged > 0) {
    events.emplace_back("rate_limited",
                        fmt::format("{}{} more rejections in an earlier minute were not logged",
                                    from, not_logged));
  }
  if (count <= impl_->per_minute) {
    events.emplace_back("rejected", from + detail);
  } else if (count == impl_->per_minute + 1) {
    events.emplace_back("rate_limited",
                        fmt::format("{}more than {} rejections this minute; the rest of the minute "
                                    "is counted, not logged",
                                    from, impl_->per_minute));
  }
  if (!then) {
    for (const auto& [event, text] : events) {
      try {
        study.record_event(participant, event, text);
      } catch (const std::exception&) {
        // The events log could not be written: the client still gets its answer.
      }
    }
    return;
  }
  if (events.empty()) return then();
  // Appends are written and synced in the order they are queued: once the last is synced, so
  // are the ones before it. A failure is ignored (the client still gets its answer).
  for (std::size_t i = 0; i + 1 < events.size(); ++i)
    study.note_event(participant, events[i].first, events[i].second);
  study.record_event(participant, events.back().first, events.back().second,
                     [then = std::move(then)](std::exception_ptr) { then(); });
}

void ServerState::write_failed(const std::string& what) {
  std::lock_guard lock(impl_->health_mu);
  if (!impl_->failure) impl_->failure = WriteFailure{what, detail::utc_now(), 0};
  impl_->failure->what = what;
  ++impl_->failure->attempts;
}

void ServerState::write_succeeded() {
  std::lock_guard lock(impl_->health_mu);
  impl_->failure.reset();
}

std::optional<ServerState::WriteFailure> ServerState::write_failure() const {
  std::lock_guard lock(impl_->health_mu);
  return impl_->failure;
}

namespace {

/// The answer to a request that failed: a refusal (recorded in the events log, rate-limited) or
/// a write that failed (503; the page retries). The answer is given once its event is synced.
void answer_failure(Study& study, const RequestInfo& info, const std::string& method,
                    const std::string& path, const std::string& participant,
                    std::exception_ptr error, const Reply& reply) {
  try {
    std::rethrow_exception(error);
  } catch (const Rejection& r) {
    const std::string who = valid_participant_id(participant) ? participant : "";
    Response answer{r.status(), "application/json",
                    fmt::format("{{\"error\":{},\"message\":{}}}", io::json_quote(r.code()),
                                io::json_quote(r.what()))};
    if (r.status() == 404 && path.rfind("/api/", 0) != 0) return reply(std::move(answer));
    const std::string detail =
        fmt::format("{} {} {} {}: {}", method, path, r.status(), r.code(), r.what());
    auto then = [reply, answer = std::move(answer)]() mutable { reply(std::move(answer)); };
    if (info.state) return info.state->record_rejection(study, info.client, who, detail, then);
    // The events log may fail to be written: the client still gets its answer.
    study.record_event(who, "rejected", detail, [then](std::exception_ptr) mutable { then(); });
  } catch (const std::exception& e) {
    // A file could not be written (disk full...): nothing was acknowledged, the page retries.
    // The participant is told to wait (the reason, with server paths, is for the admin only).
    if (info.state) info.state->write_failed(e.what());
    study.record_event(valid_participant_id(participant) ? participant : "", "server_error",
                       e.what(), [reply](std::exception_ptr) {
                         reply({503, "application/json",
                                "{\"error\":\"could_not_save\",\"message\":\"could not save, "
                                "please wait: the page tries again by itself\"}"});
                       });
  }
}

using Form = std::map<std::string, std::string>;

std::string form_value(const Form& form, const char* name) {
  auto it = form.find(name);
  return it == form.end() ? std::string() : it->second;
}

/// The pages and the admin views (GET or HEAD): answers or throws the Rejection to answer with.
void serve_page(Study& study, const std::string& admin_token, const std::string& path,
                const Form& query, const RequestInfo& info, const Reply& reply) {
  if (path == "/" || path == "/index.html")
    return reply({200, "text/html; charset=utf-8", std::string(asset("game.html"))});
  if (path == "/game.js")
    return reply({200, "text/javascript; charset=utf-8", std::string(asset("game.js"))});
  if (path == "/game.css")
    return reply({200, "text/css; charset=utf-8", std::string(asset("game.css"))});
  if (path == "/favicon.ico") return reply({204, "image/x-icon", ""});  // browsers ask for it
  if (path == "/admin" || path == "/api/admin") {
    if (!constant_time_equal(form_value(query, "token"), admin_token)) {
      throw Rejection(403, "forbidden", "the admin page needs the token printed at start-up");
    }
    const auto failure = info.state ? info.state->write_failure() : std::nullopt;
    return reply(path == "/admin" ? admin_page(study, admin_token, failure)
                                  : admin_json(study, failure));
  }
  if (path.rfind("/api/", 0) == 0) throw Rejection(405, "method", "use POST for " + path);
  throw Rejection(404, "not_found", "no such page");
}

/// The answer of a write: its status, or the failure's.
Then<ParticipantStatus> status_answer(Study& study, const RequestInfo& info,
                                      const std::string& method, const std::string& path,
                                      const std::string& who, const Reply& reply) {
  return [&study, info, method, path, who, reply](std::exception_ptr e, ParticipantStatus st) {
    if (e) return answer_failure(study, info, method, path, who, e, reply);
    if (info.state) info.state->write_succeeded();
    reply({200, "application/json", status_json(study, st)});
  };
}

/// The answer of a join: as a write's, and the client's address noted in the events log.
Then<ParticipantStatus> join_answer(Study& study, const RequestInfo& info,
                                    const std::string& method, const std::string& path,
                                    const std::string& who, const Reply& reply) {
  return [&study, info, method, path, who, reply](std::exception_ptr e, ParticipantStatus st) {
    if (e) return answer_failure(study, info, method, path, who, e, reply);
    if (!info.client.empty()) study.note_event(st.id, "joined", "from " + info.client);
    if (info.state) info.state->write_succeeded();
    reply({200, "application/json", status_json(study, st)});
  };
}

/// The answer of a round start: the round's robot path for the page to play.
Then<Round> round_answer(Study& study, const RequestInfo& info, const std::string& method,
                         const std::string& path, const std::string& participant,
                         const Reply& reply) {
  return [&study, info, method, path, participant, reply](std::exception_ptr e, Round r) {
    if (e) return answer_failure(study, info, method, path, participant, e, reply);
    const int total =
        r.kind == RoundKind::practice ? study.settings().practice : study.settings().iterations;
    std::string out =
        fmt::format("{{\"kind\":\"{}\",\"iteration\":{},\"of\":{},\"duration\":{}",
                    to_string(r.kind), r.iteration, total, io::json_number(r.duration()));
    json_array(out, "t", r.path, &sim::TrajectorySample::t);
    json_array(out, "x", r.path, &sim::TrajectorySample::x);
    json_array(out, "y", r.path, &sim::TrajectorySample::y);
    if (study.settings().belief == BeliefInput::pointer) {  // the round's map
      out += fmt::format(",\"start\":[{},{}],\"layout\":[", io::json_number(r.layout.start.x),
                         io::json_number(r.layout.start.y));
      for (std::size_t k = 0; k < r.layout.targets.size(); ++k)
        out += fmt::format("{}[{},{}]", k ? "," : "", io::json_number(r.layout.targets[k].x),
                           io::json_number(r.layout.targets[k].y));
      out += ']';
    }
    out += '}';
    reply({200, "application/json", std::move(out)});
  };
}

/// A round's submission: its kind and iteration from the query, its trace from the body.
void submit_round_request(Study& study, const Form& query, const std::string& participant,
                          const std::string& body, Then<ParticipantStatus> then) {
  const std::string kind = form_value(query, "kind");
  if (kind != "practice" && kind != "main")
    throw Rejection(400, "malformed", "kind must be practice or main");
  const auto it = io::parse_integer(form_value(query, "iteration"));
  if (!it || *it < 1 || *it > 100000)
    throw Rejection(400, "malformed", "iteration must be a whole number >= 1");
  const RoundKind k = kind == "practice" ? RoundKind::practice : RoundKind::main;
  if (study.settings().belief == BeliefInput::pointer)
    return study.submit_round(participant, k, static_cast<int>(*it), parse_pointer_trace(body),
                              std::move(then));
  study.submit_round(participant, k, static_cast<int>(*it), parse_trace(body), std::move(then));
}

}  // namespace

void handle_request(Study& study, const std::string& admin_token, const std::string& method,
                    const std::string& target, std::string body, const RequestInfo& info,
                    Reply reply) {
  const auto q = target.find('?');
  const std::string path = target.substr(0, q);
  std::string participant;
  try {
    const auto query = parse_form(q == std::string::npos ? std::string_view()
                                                         : std::string_view(target).substr(q + 1));
    participant = form_value(query, "participant");
    if (method == "GET" || method == "HEAD")
      return serve_page(study, admin_token, path, query, info, reply);
    if (method != "POST") throw Rejection(405, "method", "only GET and POST are served");
    if (path == "/api/join") {
      if (participant.empty()) participant = form_value(query, "PROLIFIC_PID");
      return study.join(participant, join_answer(study, info, method, path, participant, reply));
    }
    if (path == "/api/round/start")
      return study.start_round(participant,
                               round_answer(study, info, method, path, participant, reply));
    if (path == "/api/round/submit") {
      return submit_round_request(study, query, participant, body,
                                  status_answer(study, info, method, path, participant, reply));
    }
    if (path == "/api/questionnaire") {
      return study.submit_questionnaire(
          participant, parse_form(body),
          status_answer(study, info, method, path, participant, reply));
    }
    throw Rejection(404, "not_found", "no such page");
  } catch (...) {
    answer_failure(study, info, method, path, participant, std::current_exception(), reply);
  }
}

Response handle_request(Study& study, const std::string& admin_token, const std::string& method,
                        const std::string& target, const std::string& body,
                        const RequestInfo& info) {
  std::promise<Response> promise;
  auto answer = promise.get_future();
  auto shared = std::make_shared<std::promise<Response>>(std::move(promise));
  handle_request(study, admin_token, method, target, body, info,
                 [shared](Response r) { shared->set_value(std::move(r)); });
  return answer.get();
}

}  // namespace feint::collect
