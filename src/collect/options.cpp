#include "feint/collect/options.hpp"

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <utility>

#include "feint/error.hpp"
#include "feint/io/number.hpp"
#include "feint/io/output.hpp"

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
  s.targets = a.targets;
  if (a.layout != "fixed" && a.layout != "random")
    throw UsageError(fmt::format("--layout '{}': expected fixed or random", a.layout));
  s.layout = a.layout == "random" ? LayoutMode::random : LayoutMode::fixed;
  if (!a.belief.empty() && a.belief != "pad" && a.belief != "pointer")
    throw UsageError(fmt::format("--belief '{}': expected pad or pointer", a.belief));
  const bool pointer =
      a.belief == "pointer" || (a.belief.empty() && (a.targets != 2 || a.layout == "random"));
  s.belief = pointer ? BeliefInput::pointer : BeliefInput::pad;
  if (a.belief == "pad" && a.targets != 2) {
    throw UsageError(fmt::format(
        "--belief pad with --targets {}: the pad shows a belief between two targets only; use "
        "--belief pointer (the participant points at the map)",
        a.targets));
  }
  if (a.belief == "pad" && a.layout == "random") {
    throw UsageError(
        "--belief pad with --layout random: the pad is for the paper's fixed two targets; use "
        "--belief pointer");
  }
  s.completion_url = a.completion_url;
  if (!s.completion_url.empty() && s.completion_url.rfind("https://", 0) != 0 &&
      s.completion_url.rfind("http://", 0) != 0) {
    throw UsageError("--completion-url must start with https:// or http://");
  }
  return s;
}

void add_design_options(CLI::App& cmd, CollectOptions& o) {
  cmd.add_option("--targets", o.targets, "Targets on the map, K >= 2 (default 2)")
      ->check(CLI::Range(std::size_t{2}, std::size_t{26}));
  cmd.add_option("--layout", o.layout,
                 "fixed (the targets in a row, K = 2: the paper's) or random (drawn per round)");
  cmd.add_option("--belief", o.belief,
                 "pad (the paper's 1-D pad; K = 2, the default) or pointer (a point held on the "
                 "map; the default and required for K > 2)");
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
  const std::string belief =
      s.belief == BeliefInput::pad
          ? fmt::format("pad speed {}/s", io::format_double(s.pad_speed))
          : fmt::format("{} targets, {} layout, belief a point held on the map", s.targets,
                        s.layout == LayoutMode::random ? "random" : "fixed");
  std::string out = fmt::format("feint collect: study {} ({}; {} practice + {} rounds; {})\n",
                                study.string(), conditions, s.practice, s.iterations, belief);
  out += fmt::format("port: {}\n", server.port());
  out += fmt::format("participants: http://{}:{}/\n", shown_host, server.port());
  out += fmt::format("admin:        http://{}:{}/admin?token={}\n", shown_host, server.port(),
                     server.admin_token());
  out += fmt::format("connections: at most {} at once\n", server.max_connections());
  out += fmt::format("Stop with Ctrl-C; a restart resumes from the files in {}.\n", study.string());
  return out;
}

std::string study_toml(const Settings& s, std::string_view tool_version) {
  std::vector<std::string> names;
  for (const auto& c : s.conditions) names.push_back(c.name);
  std::string out = fmt::format(
      "# The design of this study, written by feint collect (feint {}) at its first start, read by\n"
      "# `feint analyze STUDY` (names are its options without the dashes; the command line wins).\n"
      "# Collected with: conditions {}, {} iterations after {} practice rounds, pad speed {} per\n"
      "# second, {} samples per second, seed {}, questionnaire items {} (1-7).\n\n",
      tool_version, fmt::join(names, ", "), s.iterations, s.practice,
      io::format_double(s.pad_speed), io::format_double(s.geometry.sample_rate), s.seed,
      fmt::join(s.items, ", "));
  out += "# Each participant is given one condition: conditions between participants.\n"
         "design = \"between\"\n\n";
  if (names.size() == 2) {
    out += fmt::format(
        "# The comparison the study was run for (Table 1 two-sample, the models, the questionnaire).\n"
        "compare = \"{},{}\"\n\n",
        names[0], names[1]);
  } else {
    out += "# Three or more conditions: compared by the models' test of condition and then each pair,\n"
           "# and the questionnaire by Kruskal-Wallis and then each pair; to compare one pair only, name\n"
           "# it with compare = \"A,B\".\n\n";
  }
  out +=
      "# Confusion on the paper's scale (eq. 4 without normalisation), where the paper's reference\n"
      "# 0.95 lies: the scores and the reference are on one scale (docs/metrics.md).\n"
      "confusion-norm = \"raw\"\n"
      "metric = [\"error=0.5\", \"confusion=0.95@raw\"]\n\n"
      "# The questionnaire's answers are whole numbers 1-7.\n"
      "likert-scale = \"1-7\"\n";
  if (s.belief == BeliefInput::pointer) {
    out += fmt::format(
        "\n# Belief as a point held on the map, {} targets, layout {}: the logs have the columns\n"
        "# t, belief_x, belief_y, start_x, start_y, target0_x ... target{}_y, robot_x, robot_y (m),\n"
        "# target = the true target's index. The design, pinned for feint collect (a restart with\n"
        "# other values would mix two designs) and read by feint analyze:\n"
        "[collect]\ntargets = {}\nlayout = \"{}\"\nbelief = \"pointer\"\n",
        s.targets, s.layout == LayoutMode::random ? "random" : "fixed", s.targets - 1, s.targets,
        s.layout == LayoutMode::random ? "random" : "fixed");
  }
  return out;
}

bool write_study_toml(const fs::path& study, const Settings& s, std::string_view tool_version) {
  const fs::path target = study / "feint.toml";
  std::error_code ec;
  if (fs::exists(target, ec)) return false;
  const fs::path tmp = study / ".feint.toml.feint-tmp";
  io::write_file_atomically(tmp.string(), study_toml(s, tool_version));
  const bool linked = ::link(tmp.c_str(), target.c_str()) == 0;
  const int err = errno;
  fs::remove(tmp, ec);
  if (!linked && err != EEXIST) {
    throw IoError(fmt::format("cannot write '{}': {}", target.string(), std::strerror(err)));
  }
  return linked;
}

}  // namespace feint::collect
