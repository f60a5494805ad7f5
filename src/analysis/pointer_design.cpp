// The Design row of a study of K targets (see pointer_design.hpp).
#include "pointer_design.hpp"

#include <set>
#include <tuple>

#include <fmt/format.h>

#include "feint/io/pointer_trace.hpp"

namespace feint::analysis::detail {

std::string pointer_design_note(const std::vector<std::string>& logs, io::TraceOptions options) {
  const auto files = io::expand_inputs(logs);
  if (files.empty() || !io::is_pointer_log(files.front(), options)) return {};
  options.on_reject = [](const io::Rejection&) {};
  options.require_pad_speed = false;
  io::PointerTraceReader reader(files, options);
  // Distinct layouts (start and targets, as read): one = a fixed layout, more = placed per round.
  std::set<std::vector<double>> layouts;
  io::Trial t;
  while (reader.next(t)) {
    std::vector<double> l = {t.start_x, t.start_y};
    for (std::size_t k = 0; k < t.targets_x.size(); ++k) {
      l.push_back(t.targets_x[k]);
      l.push_back(t.targets_y[k]);
    }
    layouts.insert(std::move(l));
  }
  if (layouts.empty()) return {};
  return layouts.size() == 1
             ? fmt::format("{} targets and a pointer (belief as a point on the map), one fixed layout",
                           reader.targets())
             : fmt::format("{} targets and a pointer (belief as a point on the map), targets placed per round "
                           "({} layouts)",
                           reader.targets(), layouts.size());
}

}  // namespace feint::analysis::detail
