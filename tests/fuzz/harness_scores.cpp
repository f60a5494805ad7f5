// The scores loader (`feint table`'s input) and the numeric-column loader (`feint describe`).
#include <cmath>
#include <set>
#include <string>
#include <tuple>

#include "feint/error.hpp"
#include "feint/io/scores.hpp"
#include "harness.hpp"

namespace feint::fuzz {

int scores(const std::uint8_t* data, std::size_t size) {
  if (size > 1 << 16) return 0;
  using detail::check;
  const std::string path = detail::as_file(data, size);
  try {
    const auto t = io::load_scores(path);
    check(!t.records.empty(), "a scores table without rows");
    std::set<std::tuple<std::string, std::string, long long>> keys;
    for (const auto& r : t.records) {
      check(!r.participant.empty(), "empty participant");
      check(r.values.size() == t.metrics.size(), "one value per metric");
      for (const auto& v : r.values) check(!v || std::isfinite(*v), "metric value not finite");
      check(keys.emplace(r.participant, r.condition, r.iteration).second, "duplicate key");
      check(t.has_condition || r.condition.empty(), "condition without a condition column");
    }
  } catch (const Error&) {
  }
  try {
    const auto c = io::load_numeric_column(path, "error", "condition");
    check(c.groups.size() == c.values.size() && c.values.size() == c.texts.size(),
          "groups, values and texts differ in number");
    for (std::size_t g = 0; g < c.values.size(); ++g) {
      check(c.values[g].size() == c.texts[g].size(), "a value without its text");
      for (const double v : c.values[g]) check(std::isfinite(v), "value not finite");
    }
  } catch (const Error&) {
  }
  return 0;
}

}  // namespace feint::fuzz
