// Logs of K targets and a pointer in `feint analyze`: what the report's Design row says of them.
#pragma once

#include <string>
#include <vector>

#include "feint/io/trace.hpp"

namespace feint::analysis::detail {

/// For logs of K targets (io::is_pointer_log of the first file): "K targets and a pointer, layout
/// fixed" or "..., placed per round (N layouts)"; empty for pad logs. Invalid trials are skipped
/// (the scorer has judged them already).
std::string pointer_design_note(const std::vector<std::string>& logs, io::TraceOptions options);

}  // namespace feint::analysis::detail
