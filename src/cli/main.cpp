// feint - deception user-study logs to the statistics a paper reports.
#include <cstdio>
#include <exception>
#include <new>

#include <fmt/format.h>

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
  feint::cli::add_model_command(app);

  try {
    app.parse(argc, argv);
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
