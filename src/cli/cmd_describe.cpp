// feint describe FILE.csv --column NAME [--by GROUP]: descriptive statistics (docs/tables.md).
#include <memory>

#include "commands.hpp"
#include "feint/io/scores.hpp"
#include "feint/tables/describe.hpp"
#include "options.hpp"

namespace feint::cli {

namespace {

struct DescribeArgs {
  std::string input;
  std::string column;
  std::string by;
  double conf_level = 0.95;
  ReportOptions report;
};

}  // namespace

void add_describe_command(CLI::App& app) {
  auto args = std::make_shared<DescribeArgs>();
  auto* cmd = app.add_subcommand(
      "describe",
      "Descriptive statistics of a numeric column, optionally by group: n, mean, sd, se, min, "
      "quartiles, max, CI of the mean, lag-1 autocorrelation.");
  cmd->option_defaults()->always_capture_default();  // each option shows its default
  cmd->add_option("FILE", args->input, "Any CSV (gzip, ; and TAB too; - = standard input)")
      ->required();
  cmd->add_option("--column", args->column, "The numeric column to describe")->required();
  cmd->add_option("--by", args->by, "Grouping column: one row per group");
  cmd->add_option("--conf-level", args->conf_level,
                  "Confidence level of the mean's interval, in (0, 1)");
  add_report_options(*cmd, args->report, ReportOptionSet{false});
  cmd->callback([args] {
    ReportOptions ro = args->report;
    ro.conf_level = args->conf_level;
    const ResolvedReportOptions r = resolve_report_options(ro);
    const auto column = io::load_numeric_column(args->input, args->column, args->by);
    const auto table = tables::build_describe(column, r.test.conf_level);
    write_report(r.output, tables::render_describe(table, r.format));
  });
}

}  // namespace feint::cli
