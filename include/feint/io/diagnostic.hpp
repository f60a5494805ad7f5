// feint/io/diagnostic.hpp - a structured note about how input was read (a warning, not an error).
//
// Loaders return these instead of printing them, so that a pipeline can carry them into its
// results and a report can show them ("put the ms warning in the report"). Each has a
// stable code (for tests and machine readers), where it applies, and the full sentence a person
// reads, which names the option that changes the reading.
#pragma once

#include <cstdint>
#include <string>

namespace feint::io {

struct Diagnostic {
  /// Stable identifier, e.g. "time-unit-ms-suspected", "iteration-base-0", "nan-padding-dropped",
  /// "decimal-comma-detected".
  std::string code;
  std::string file;        ///< the file it concerns ("" = the whole input)
  std::uint64_t line = 0;  ///< physical line (0 = not one line)
  std::string column;      ///< the column as written in the header ("" = none)
  std::string message;     ///< the full sentence, naming the option that changes the reading
};

}  // namespace feint::io
