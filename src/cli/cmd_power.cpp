// feint power: placeholder replaced below.
#include "commands.hpp"
namespace feint::cli {
void add_power_command(CLI::App&) {}
}  // namespace feint::cli
