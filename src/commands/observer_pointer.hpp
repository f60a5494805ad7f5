// src/commands/observer_pointer.hpp - `feint observer fit` on logs of K targets and a pointer
// (docs/observer.md, "Fitting the observer to pointer traces (K targets)"): which kind the logs
// are, and the K-goal observer's fit and report (observer_pointer.cpp).
#pragma once

#include <string>
#include <vector>

#include "feint/commands/observer_power.hpp"
#include "feint/io/trace.hpp"

namespace feint::commands::detail {

/// True when every file is a log of K targets and a pointer (io::is_pointer_log), false when none
/// is. Throws InvalidData naming the first file of the other kind when they are mixed (one data
/// set is one kind).
bool pointer_logs(const std::vector<std::string>& files, const io::TraceOptions& reading);

/// The K-goal observer fitted to the pointer logs `files` and rendered (text or JSON). Throws
/// UsageError for --fit-prior, --prior or --pad-speed set away from their defaults (the pad's
/// options), InvalidData when no trial is left to fit, IoError.
std::string pointer_observer_fit_report(const ObserverFitCommand& command, const std::vector<std::string>& files,
                                        io::TraceOptions reading);

}  // namespace feint::commands::detail
