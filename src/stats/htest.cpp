#include "feint/stats/htest.hpp"

#include <fmt/format.h>

#include "feint/error.hpp"

namespace feint::stats {

std::string_view to_string(Alternative alternative) noexcept {
  switch (alternative) {
    case Alternative::greater: return "greater";
    case Alternative::less: return "less";
    case Alternative::two_sided: break;
  }
  return "two.sided";
}

Alternative parse_alternative(std::string_view text) {
  if (text == "two.sided" || text == "two-sided" || text == "two_sided") return Alternative::two_sided;
  if (text == "greater") return Alternative::greater;
  if (text == "less") return Alternative::less;
  throw UsageError(fmt::format("alternative '{}': expected two.sided, greater or less", text));
}

}  // namespace feint::stats
