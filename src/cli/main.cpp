// feint - deception user-study logs to the statistics a paper reports.
#include <cstdio>
#include <exception>
#include <new>
#include <string>
#include <string_view>
#include <vector>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>

#include "commands.hpp"
#include "feint/error.hpp"

#ifndef FEINT_VERSION
#define FEINT_VERSION "dev"
#endif

int main(int argc, char** argv) {
  CLI::App app{
      "feint: turns the logs of deception user studies (pad traces, questionnaires) into the "
      "statistics a paper reports.\n"
      "Exit status: 0 success, 64 bad command line, 65 invalid data, 74 cannot read/write a file, "
      "70 internal error.",
      "feint"};
  app.set_version_flag("--version", FEINT_VERSION);
  app.require_subcommand(1);
  app.fallthrough(false);

  feint::cli::add_score_command(app);
  feint::cli::add_table_command(app);
  feint::cli::add_describe_command(app);
  feint::cli::add_analyze_command(app);
  feint::cli::add_likert_command(app);
  feint::cli::add_simulate_command(app);
  feint::cli::add_collect_command(app);
  feint::cli::add_anova_command(app);
  feint::cli::add_power_command(app);
  feint::cli::add_plot_command(app);
  feint::cli::add_model_command(app);
  feint::cli::add_observer_command(app);

  // `feint help [COMMAND]` is `feint [COMMAND] --help`; a first word that is no command is named
  // as such (CLI11 would only say "The following argument was not expected").
  std::vector<std::string> args(argv + 1, argv + argc);
  std::vector<std::string> names;
  for (const auto* sub : app.get_subcommands([](const CLI::App*) { return true; })) {
    names.push_back(sub->get_name());
  }
  if (!args.empty() && args[0] == "help") {
    args.erase(args.begin());
    if (args.size() > 1) {
      fmt::print(stderr, "feint: error: 'feint help' takes at most one command, e.g. 'feint help "
                         "table'\n");
      return static_cast<int>(feint::ExitCode::usage);
    }
    args.push_back("--help");
  }
  if (!args.empty() && !args[0].empty() && args[0][0] != '-' &&
      std::find(names.begin(), names.end(), args[0]) == names.end()) {
    fmt::print(stderr, "feint: error: unknown command '{}'; the commands are {} (feint --help "
                       "describes them)\n",
               args[0], fmt::join(names, ", "));
    return static_cast<int>(feint::ExitCode::usage);
  }
  std::vector<char*> new_argv{argv[0]};
  for (auto& a : args) new_argv.push_back(a.data());

  try {
    app.parse(static_cast<int>(new_argv.size()), new_argv.data());
  } catch (const CLI::ParseError& e) {
    // --help and --version are "errors" with exit code 0; everything else is a usage error.
    const int rc = app.exit(e);
    return rc == 0 ? 0 : static_cast<int>(feint::ExitCode::usage);
  } catch (const feint::Error& e) {
    std::fflush(stdout);
    fmt::print(stderr, "feint: error: {}\n", e.what());
    return static_cast<int>(e.code());
  } catch (const std::bad_alloc&) {
    fmt::print(stderr, "feint: error: out of memory\n");
    return static_cast<int>(feint::ExitCode::internal);
  } catch (const std::exception& e) {
    fmt::print(stderr, "feint: internal error: {}\n", e.what());
    return static_cast<int>(feint::ExitCode::internal);
  }
  return 0;
}
