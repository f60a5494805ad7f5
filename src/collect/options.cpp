#include "feint/collect/options.hpp"

#include <fmt/format.h>

#include <chrono>
#include <cstdio>
#include <utility>

#include "feint/error.hpp"
#include "feint/io/number.hpp"

namespace feint::collect {

namespace fs = std::filesystem;

namespace {

std::pair<std::string, std::string> name_and_question(const std::string& text, const char* what) {
  const auto eq = text.find('=');
  if (eq == std::string::npos || eq == 0) {
    throw UsageError(fmt::format("{} '{}': expected NAME=QUESTION", what, text));
  }
  return {text.substr(0, eq), text.substr(eq + 1)};
}

}  // namespace

Settings study_settings(const CollectOptions& a, const fs::path& study) {
  Settings s;
  s.conditions.clear();
  for (const auto& c : a.conditions) s.conditions.push_back(parse_condition(c, a.lambda));
  s.iterations = a.iterations;
  s.practice = a.practice;
  s.pad_speed = a.pad_speed;
  s.geometry.speed = a.robot_speed;
  s.geometry.target_distance = a.target_distance;
  s.geometry.target_height = a.target_height;
  s.geometry.sample_rate = a.sample_rate;
  s.seed = a.seed;
  if (!a.items.empty()) {
    s.items.clear();
    s.item_questions.clear();
    for (const auto& i : a.items) {
      auto [name, question] = name_and_question(i, "--item");
      s.items.push_back(name);
      s.item_questions.push_back(question);
    }
  }
  if (a.yes_no.empty()) {
    s.yes_no_item.clear();
  } else {
    auto [name, question] = name_and_question(a.yes_no, "--yes-no");
    s.yes_no_item = name;
    s.yes_no_question = question;
  }
  s.consent = a.consent;
  if (!a.consent_file.empty()) {
    const fs::path p =
        fs::path(a.consent_file).is_absolute() ? fs::path(a.consent_file) : study / a.consent_file;
    std::FILE* f = std::fopen(p.c_str(), "rb");
    if (!f) throw IoError(fmt::format("{}: cannot read the consent text", p.string()));
    char buf[4096];
    std::size_t n;
    while ((n = std::fread(buf, 1, sizeof buf, f)) > 0) s.consent.append(buf, n);
    std::fclose(f);
  }
  s.completion_url = a.completion_url;
  if (!s.completion_url.empty() && s.completion_url.rfind("https://", 0) != 0 &&
      s.completion_url.rfind("http://", 0) != 0) {
    throw UsageError("--completion-url must start with https:// or http://");
  }
  return s;
}

ServerOptions server_options(const CollectOptions& a) {
  if (a.port < 0 || a.port > 65535) throw UsageError("--port must be in [0, 65535]");
  ServerOptions o;
  o.host = a.host;
  o.port = static_cast<unsigned short>(a.port);
  o.admin_token = a.admin_token;
  o.threads = a.threads;
  o.allowed_hosts = a.allowed_hosts;
  o.trusted_proxies = a.trusted_proxies;
  o.max_connections = a.max_connections;
  o.idle_timeout = std::chrono::seconds(a.idle_timeout);
  o.stop_on_signals = true;
  return o;
}

std::string network_warning(const std::string& host) {
  if (host == "127.0.0.1" || host == "::1" || host.rfind("127.", 0) == 0) return {};
  return fmt::format(
      "feint collect: WARNING: listening on {}: the study is REACHABLE FROM THE NETWORK.\n"
      "  Anyone who can reach this address can join; keep the admin token secret; use a\n"
      "  firewall or a TLS reverse proxy for an online study (docs/collect.md).\n",
      host);
}

std::string start_message(const fs::path& study, const Settings& s, const std::string& host,
                          const Server& server) {
  const std::string shown_host = host.find(':') != std::string::npos ? "[" + host + "]" : host;
  std::string conditions;
  for (const auto& x : s.conditions) conditions += (conditions.empty() ? "" : ", ") + x.name;
  std::string out = fmt::format(
      "feint collect: study {} ({}; {} practice + {} rounds; pad speed {}/s)\n", study.string(),
      conditions, s.practice, s.iterations, io::format_double(s.pad_speed));
  out += fmt::format("port: {}\n", server.port());
  out += fmt::format("participants: http://{}:{}/\n", shown_host, server.port());
  out += fmt::format("admin:        http://{}:{}/admin?token={}\n", shown_host, server.port(),
                     server.admin_token());
  out += fmt::format("connections: at most {} at once\n", server.max_connections());
  out += fmt::format("Stop with Ctrl-C; a restart resumes from the files in {}.\n", study.string());
  return out;
}

}  // namespace feint::collect
