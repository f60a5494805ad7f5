// src/cli/commands.hpp - each subcommand registers itself on the top-level app.
//
// A command's callback does the work and reports failure by throwing a feint::Error subclass;
// main() maps it to the exit code (see feint/error.hpp and the README).
#pragma once

#include <CLI/CLI.hpp>

#ifndef FEINT_VERSION  // CMake defines it as the project version
#define FEINT_VERSION "dev"
#endif

namespace feint::cli {

void add_score_command(CLI::App& app);             // cmd_score.cpp    (issue: trial scoring)
void add_table_command(CLI::App& app);             // cmd_table.cpp    (issue: Table 1)
void add_describe_command(CLI::App& app);          // cmd_describe.cpp (issue: Table 1)
void add_analyze_command(CLI::App& app);           // cmd_analyze.cpp  (issue: Table 1)
void add_likert_command(CLI::App& app);            // cmd_likert.cpp   (issue: Likert)
void add_simulate_command(CLI::App& app);          // cmd_simulate.cpp (issue: selection simulator)
void add_collect_command(CLI::App& app);           // cmd_collect.cpp  (data collection)
void add_anova_command(CLI::App& app);             // cmd_anova.cpp    (mixed ANOVA)
void add_power_command(CLI::App& app);             // cmd_power.cpp    (power)
void add_power_observer_command(CLI::App& power);  // cmd_power_observer.cpp
void add_plot_command(CLI::App& app);              // cmd_plot.cpp     (figures)
void add_model_command(CLI::App& app);             // cmd_model.cpp    (mixed model)
void add_observer_command(CLI::App& app);          // cmd_observer.cpp (observer fit)

}  // namespace feint::cli
