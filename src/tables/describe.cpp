// `feint describe`'s numbers: summary statistics of one column (see feint/tables/describe.hpp);
// its renderings are in describe_render.cpp.
#include "feint/tables/describe.hpp"

#include <cmath>
#include <cstdlib>
#include <optional>

#include <fmt/format.h>

#include "feint/error.hpp"
#include "feint/io/number.hpp"
#include "feint/stats/exact_decimal.hpp"

namespace feint::tables {

DescribeTable build_describe(const io::NumericColumn& column, double conf_level) {
  if (!(conf_level > 0.0 && conf_level < 1.0)) {
    throw UsageError(fmt::format("--conf-level {}: expected a number in (0, 1)", conf_level));
  }
  DescribeTable t;
  t.source = column.path;
  t.variable = column.column;
  t.by = column.by;
  t.conf_level = conf_level;
  t.groups = column.groups;
  t.missing = column.missing;
  // From the decimal text when the loader kept it: mean, sd and the CI then reach LRE >= 13 on
  // NIST StRD NumAcc4, which values already rounded to double cannot (statistics.md).
  // Text the exact reading cannot take (values 10^-300 and 10^300 apart in one column, exponents
  // beyond 400) falls back to the doubles the loader read: describe never rejects what loads.
  for (std::size_t g = 0; g < column.values.size(); ++g) {
    std::optional<stats::Description> d;
    if (g < column.texts.size()) {
      try {
        d = stats::describe_decimal(column.texts[g], conf_level);
      } catch (const InvalidData&) {
        d.reset();
      }
    }
    t.descriptions.push_back(d ? *d : stats::describe(column.values[g], conf_level));
  }
  return t;
}

}  // namespace feint::tables
