// `feint collect STUDY`: serves the data-collection game (docs/collect.md). Settings come from the
// [collect] section of STUDY/feint.toml, each also an option here (the command line wins).
#include <fmt/format.h>

#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>

#include "commands.hpp"
#include "feint/collect/options.hpp"
#include "feint/error.hpp"
#include "options.hpp"

namespace feint::cli {

namespace {

namespace fs = std::filesystem;

struct CollectArgs {
  std::string study;
  std::string config;
  collect::CollectOptions o;
};

void run(CLI::App& cmd, CollectArgs& a) {
  const fs::path study(a.study);
  if (!fs::is_directory(study)) {
    throw IoError(fmt::format(
        "study folder '{}' does not exist or is not a folder (create it first)", a.study));
  }
  const std::string config = settings_file(a.config, study);
  if (!config.empty()) apply_settings_file(cmd, config, SettingsSection::collect);
  const collect::Settings s = collect::study_settings(a.o, study);
  const collect::ServerOptions o = collect::server_options(a.o);
  collect::Study st(study, s);
  if (collect::write_study_toml(study, s, FEINT_VERSION))  // the design, for feint analyze
    fmt::print(stderr, "feint collect: wrote {} (the study's design for feint analyze)\n",
               (study / "feint.toml").string());
  collect::Server server(st, o);
  fmt::print(stderr, "{}", collect::network_warning(a.o.host));
  fmt::print("{}", collect::start_message(study, s, a.o.host, server));
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
      "be given in the [collect] section of STUDY/feint.toml (see docs/collect.md).");
  cmd->add_option("study", args->study,
                  "Study folder (created files: logs/, practice/, collect/, questionnaire*.csv)")
      ->required();
  cmd->add_option("--config", args->config,
                  "Settings file (default STUDY/feint.toml when present; section [collect])");
  cmd->add_option("--host", args->o.host,
                  "Address to listen on (default 127.0.0.1: this computer only)");
  cmd->add_option("--port", args->o.port,
                  "TCP port (default 8080; 0 = any free port, printed at start)");
  cmd->add_option("--conditions", args->o.conditions,
                  "Conditions: adaptive, random, fixed-block, fixed-balanced, each optionally "
                  ":LAMBDA (default adaptive,random)")
      ->delimiter(',');
  cmd->add_option("--lambda", args->o.lambda,
                  "Lambda of adaptive conditions without their own (default 0.5)");
  cmd->add_option("--iterations", args->o.iterations,
                  "Analysed rounds per participant (default 20)");
  cmd->add_option("--practice", args->o.practice,
                  "Practice rounds before them, optimal strategy, logged in practice/ (default 2)");
  cmd->add_option("--pad-speed", args->o.pad_speed,
                  "Pad speed while an arrow key is held, pad units per second (default 0.8)");
  cmd->add_option("--robot-speed", args->o.robot_speed, "Robot speed, m/s (default 1)");
  cmd->add_option("--target-distance", args->o.target_distance,
                  "Distance between the targets, m (default 4)");
  cmd->add_option("--target-height", args->o.target_height,
                  "Height of the targets above the start, m (default 4)");
  cmd->add_option("--sample-rate", args->o.sample_rate,
                  "Trajectory samples per second sent to the page (default 25)");
  cmd->add_option("--seed", args->o.seed, "Seed of the assignment and of every round (default 1)");
  cmd->add_option("--item", args->o.items,
                  "A 1-7 questionnaire item as NAME=QUESTION (repeatable; default the paper's "
                  "entertainment, deception, intelligence, trust)");
  cmd->add_option("--yes-no", args->o.yes_no, "The yes/no question as NAME=QUESTION ('' for none)");
  cmd->add_option("--consent", args->o.consent, "Consent text shown before the first round");
  cmd->add_option("--consent-file", args->o.consent_file,
                  "File with the consent text (relative to STUDY)");
  cmd->add_option("--completion-url", args->o.completion_url,
                  "Where the completion page sends participants (e.g. Prolific's)");
  cmd->add_option("--admin-token", args->o.admin_token,
                  "Token of the admin page (default: random, printed at start)");
  cmd->add_option("--threads", args->o.threads,
                  "Connection threads (default 4; none waits for a disk: a save is answered "
                  "when its commit group is synced)")
      ->check(CLI::Range(1u, 64u));
  cmd->add_option("--allowed-host", args->o.allowed_hosts,
                  "Accepted Host header, NAME or NAME:PORT (repeatable). On 127.0.0.1/::1, "
                  "localhost, 127.0.0.1 and [::1] are always accepted and other hosts refused "
                  "(421: DNS-rebinding defence)");
  cmd->add_option("--trusted-proxy", args->o.trusted_proxies,
                  "IP address of a reverse proxy whose X-Forwarded-For gives the client's address "
                  "in the events log (repeatable; e.g. 127.0.0.1 for nginx on this computer)");
  cmd->add_option("--max-connections", args->o.max_connections,
                  "Simultaneous connections (at most ulimit -n less a reserve); the quietest makes way");
  cmd->add_option("--idle-timeout", args->o.idle_timeout,
                  "Seconds a kept-alive connection may wait for its next request (default 10)")
      ->check(CLI::Range(1, 3600));
  collect::add_design_options(*cmd, args->o);  // --targets, --layout, --belief
  cmd->callback([cmd, args] { run(*cmd, *args); });
}

}  // namespace feint::cli
