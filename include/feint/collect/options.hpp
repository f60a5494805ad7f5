// feint/collect/options.hpp - `feint collect`'s options as given (command line or the [collect]
// section of STUDY/feint.toml; docs/collect.md), turned into the study's Settings and the
// server's ServerOptions, and the lines the command prints when the server starts.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "feint/collect/server.hpp"
#include "feint/collect/study.hpp"

namespace CLI {
class App;
}

namespace feint::collect {

/// The options with their defaults (the paper's study on this computer).
struct CollectOptions {
  std::string host = "127.0.0.1";
  int port = 8080;
  std::vector<std::string> conditions{"adaptive", "random"};  // NAME or NAME:LAMBDA
  double lambda = 0.5;
  int iterations = 20;
  int practice = 2;
  double pad_speed = 0.8;
  double robot_speed = 1.0;
  double target_distance = 4.0;
  double target_height = 4.0;
  double sample_rate = 25.0;
  std::uint64_t seed = 1;
  std::vector<std::string> items;  // NAME=QUESTION; empty: the paper's four
  std::string yes_no = "intentional=Did the robot's movement look intentional?";  // '' for none
  std::string consent;
  std::string consent_file;  // relative to the study folder
  std::string completion_url;
  std::string admin_token;
  unsigned threads = 4;  // connection threads (none waits for a disk)
  std::vector<std::string> allowed_hosts;
  std::vector<std::string> trusted_proxies;
  std::size_t max_connections = 0;
  int idle_timeout = 10;
  std::size_t targets = 2;       // K
  std::string layout = "fixed";  // fixed | random
  std::string belief;            // pad | pointer; empty: pad for K = 2, pointer for K > 2
};

/// Registers --targets, --layout and --belief on `feint collect` (kept here so that the command
/// line stays thin).
void add_design_options(CLI::App& cmd, CollectOptions& o);

/// The study's settings: conditions parsed, NAME=QUESTION items split, the consent file read
/// (relative to `study`). Throws UsageError naming the option (--item, --yes-no,
/// --completion-url, --layout, --belief: --belief pad with --targets > 2 or --layout random),
/// IoError when the consent file cannot be read.
Settings study_settings(const CollectOptions& o, const std::filesystem::path& study);

/// The server's options (signals stop it). Throws UsageError for a port outside [0, 65535].
ServerOptions server_options(const CollectOptions& o);

/// A warning for standard error when `host` is not a loopback address; empty otherwise.
std::string network_warning(const std::string& host);

/// What the command prints once the server listens: the study, the URLs of the participants'
/// and the admin page, the connection cap, how to stop.
std::string start_message(const std::filesystem::path& study, const Settings& s,
                          const std::string& host, const Server& server);

/// The study's feint.toml as `feint collect` writes it at its first start: the design that
/// `feint analyze STUDY` reads. The comparison of the first two conditions (none with three or
/// more), confusion on the raw scale with the paper's references (so the scores and the reference
/// are on one scale), the questionnaire's 1-7 scale; the collection's own settings as comments.
std::string study_toml(const Settings& s, std::string_view tool_version);

/// Writes STUDY/feint.toml (study_toml) unless the study has one: an existing file is never
/// replaced, even by a start racing this one (the file is linked into place, which fails when the
/// name exists). Returns true when it wrote the file. Throws IoError when it cannot write.
bool write_study_toml(const std::filesystem::path& study, const Settings& s,
                      std::string_view tool_version);

}  // namespace feint::collect
