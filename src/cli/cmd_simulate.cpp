// Placeholder registration; the command is implemented by its issue (see commands.hpp).
#include "commands.hpp"
#include "feint/error.hpp"

namespace feint::cli {

void add_simulate_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("simulate", "(not implemented yet)");
  cmd->allow_extras();
  cmd->callback([] { throw UsageError("'feint simulate' is not implemented yet"); });
}

}  // namespace feint::cli
