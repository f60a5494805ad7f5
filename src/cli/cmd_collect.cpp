// `feint collect STUDY`: serves the data-collection game (docs/collect.md). Settings come from the
// [collect] section of STUDY/feint.toml, each also an option here (the command line wins).
#include <fmt/format.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "commands.hpp"
#include "feint/collect/server.hpp"
#include "feint/collect/study.hpp"
#include "feint/error.hpp"
#include "feint/io/number.hpp"
#include "study_config.hpp"

namespace feint::cli {

namespace {

namespace fs = std::filesystem;

struct CollectArgs {
  std::string study;
  std::string config;
  std::string host = "127.0.0.1";
  int port = 8080;
  std::vector<std::string> conditions{"adaptive", "random"};
  double lambda = 0.5;
  int iterations = 20;
  int practice = 2;
  double pad_speed = 0.8;
  double robot_speed = 1.0;
  double target_distance = 4.0;
  double target_height = 4.0;
  double sample_rate = 25.0;
  std::uint64_t seed = 1;
  std::vector<std::string> items;
  std::string yes_no = "intentional=Did the robot's movement look intentional?";
  std::string consent;
  std::string consent_file;
  std::string completion_url;
  std::string admin_token;
  unsigned threads = 16;
  std::vector<std::string> allowed_hosts;
  std::vector<std::string> trusted_proxies;
  std::size_t max_connections = 0;
  int idle_timeout = 10;
};

std::pair<std::string, std::string> name_and_question(const std::string& text, const char* what) {
  const auto eq = text.find('=');
  if (eq == std::string::npos || eq == 0) {
    throw UsageError(fmt::format("{} '{}': expected NAME=QUESTION", what, text));
  }
  return {text.substr(0, eq), text.substr(eq + 1)};
}

void run(CLI::App& cmd, CollectArgs& a) {
  const fs::path study(a.study);
  if (!fs::is_directory(study)) {
    throw IoError(fmt::format(
        "study folder '{}' does not exist or is not a folder (create it first)", a.study));
  }
  const std::string config = settings_file(a.config, study);
  if (!config.empty()) apply_settings_file(cmd, config, SettingsSection::collect);

  collect::Settings s;
  s.conditions.clear();
  for (const auto& c : a.conditions) s.conditions.push_back(collect::parse_condition(c, a.lambda));
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
  if (a.port < 0 || a.port > 65535) throw UsageError("--port must be in [0, 65535]");

  collect::Study st(study, s);
  collect::ServerOptions o;
  o.host = a.host;
  o.port = static_cast<unsigned short>(a.port);
  o.admin_token = a.admin_token;
  o.threads = a.threads;
  o.allowed_hosts = a.allowed_hosts;
  o.trusted_proxies = a.trusted_proxies;
  o.max_connections = a.max_connections;
  o.idle_timeout = std::chrono::seconds(a.idle_timeout);
  o.stop_on_signals = true;
  collect::Server server(st, o);
  const std::string shown_host =
      a.host.find(':') != std::string::npos ? "[" + a.host + "]" : a.host;
  if (a.host != "127.0.0.1" && a.host != "::1" && a.host.rfind("127.", 0) != 0) {
    fmt::print(stderr,
               "feint collect: WARNING: listening on {}: the study is REACHABLE FROM THE NETWORK.\n"
               "  Anyone who can reach this address can join; keep the admin token secret; use a\n"
               "  firewall or a TLS reverse proxy for an online study (docs/collect.md).\n",
               a.host);
  }
  const auto conditions = [&] {
    std::string c;
    for (const auto& x : s.conditions) c += (c.empty() ? "" : ", ") + x.name;
    return c;
  }();
  fmt::print("feint collect: study {} ({}; {} practice + {} rounds; pad speed {}/s)\n",
             study.string(), conditions, s.practice, s.iterations, io::format_double(s.pad_speed));
  fmt::print("port: {}\n", server.port());
  fmt::print("participants: http://{}:{}/\n", shown_host, server.port());
  fmt::print("admin:        http://{}:{}/admin?token={}\n", shown_host, server.port(),
             server.admin_token());
  fmt::print("connections: at most {} at once\n", server.max_connections());
  fmt::print("Stop with Ctrl-C; a restart resumes from the files in {}.\n", study.string());
  std::fflush(stdout);
  server.run();
  fmt::print("feint collect: stopped\n");
}

}  // namespace

void add_collect_command(CLI::App& app) {
  auto args = std::make_shared<CollectArgs>();
  auto* cmd = app.add_subcommand(
      "collect",
      "Run a study: serve the paper's data-collection game (Fig. 8) to participants' browsers, "
      "choose each round's strategy with the condition's algorithm, and write pad-trace logs and "
      "the questionnaire into STUDY in the layout 'feint analyze STUDY' reads. Settings may also "
      "be "
      "given in the [collect] section of STUDY/feint.toml (see docs/collect.md).");
  cmd->add_option("study", args->study,
                  "Study folder (created files: logs/, practice/, collect/, questionnaire*.csv)")
      ->required();
  cmd->add_option("--config", args->config,
                  "Settings file (default STUDY/feint.toml when present; section [collect])");
  cmd->add_option("--host", args->host,
                  "Address to listen on (default 127.0.0.1: this computer only)");
  cmd->add_option("--port", args->port,
                  "TCP port (default 8080; 0 = any free port, printed at start)");
  cmd->add_option("--conditions", args->conditions,
                  "Conditions: adaptive, random, fixed-block, fixed-balanced, each optionally "
                  ":LAMBDA (default adaptive,random)")
      ->delimiter(',');
  cmd->add_option("--lambda", args->lambda,
                  "Lambda of adaptive conditions without their own (default 0.5)");
  cmd->add_option("--iterations", args->iterations, "Analysed rounds per participant (default 20)");
  cmd->add_option("--practice", args->practice,
                  "Practice rounds before them, optimal strategy, logged in practice/ (default 2)");
  cmd->add_option("--pad-speed", args->pad_speed,
                  "Pad speed while an arrow key is held, pad units per second (default 0.8)");
  cmd->add_option("--robot-speed", args->robot_speed, "Robot speed, m/s (default 1)");
  cmd->add_option("--target-distance", args->target_distance,
                  "Distance between the targets, m (default 4)");
  cmd->add_option("--target-height", args->target_height,
                  "Height of the targets above the start, m (default 4)");
  cmd->add_option("--sample-rate", args->sample_rate,
                  "Trajectory samples per second sent to the page (default 25)");
  cmd->add_option("--seed", args->seed, "Seed of the assignment and of every round (default 1)");
  cmd->add_option("--item", args->items,
                  "A 1-7 questionnaire item as NAME=QUESTION (repeatable; default the paper's "
                  "entertainment, deception, intelligence, trust)");
  cmd->add_option("--yes-no", args->yes_no, "The yes/no question as NAME=QUESTION ('' for none)");
  cmd->add_option("--consent", args->consent, "Consent text shown before the first round");
  cmd->add_option("--consent-file", args->consent_file,
                  "File with the consent text (relative to STUDY)");
  cmd->add_option("--completion-url", args->completion_url,
                  "Where the completion page sends participants (e.g. Prolific's)");
  cmd->add_option("--admin-token", args->admin_token,
                  "Token of the admin page (default: random, printed at start)");
  cmd->add_option("--threads", args->threads, "Server threads (default 16; each waits for its group's sync, so more threads make bigger commit groups)")
      ->check(CLI::Range(1u, 64u));
  cmd->add_option("--allowed-host", args->allowed_hosts,
                  "Accepted Host header, NAME or NAME:PORT (repeatable). On 127.0.0.1/::1, "
                  "localhost, 127.0.0.1 and [::1] are always accepted and other hosts refused "
                  "(421: DNS-rebinding defence)");
  cmd->add_option("--trusted-proxy", args->trusted_proxies,
                  "IP address of a reverse proxy whose X-Forwarded-For gives the client's address "
                  "in the events log (repeatable; e.g. 127.0.0.1 for nginx on this computer)");
  cmd->add_option("--max-connections", args->max_connections,
                  "Simultaneous connections (default: the descriptor limit, ulimit -n, less a "
                  "reserve for the files written); more wait in the listen queue");
  cmd->add_option("--idle-timeout", args->idle_timeout,
                  "Seconds a kept-alive connection may wait for its next request (default 10)")
      ->check(CLI::Range(1, 3600));
  cmd->callback([cmd, args] { run(*cmd, *args); });
}

}  // namespace feint::cli
