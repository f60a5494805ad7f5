// feint/error.hpp - the error kinds every module throws and the exit code each maps to.
//
// The command line turns each kind into a distinct, documented exit status (sysexits.h values),
// so scripts can tell bad data from a bad command line from a file that cannot be read.
#pragma once

#include <stdexcept>
#include <string>

namespace feint {

enum class ExitCode : int {
  success = 0,
  usage = 64,         // EX_USAGE: bad command line (unknown option, bad value, missing argument)
  invalid_data = 65,  // EX_DATAERR: input read fine but violates the data contract (formats.md)
  internal = 70,      // EX_SOFTWARE: a bug in feint
  io = 74,            // EX_IOERR: a file cannot be opened, read or written
};

/// Base of every feint error; `code()` is the process exit status it stands for.
class Error : public std::runtime_error {
 public:
  Error(ExitCode code, const std::string& message) : std::runtime_error(message), code_(code) {}
  ExitCode code() const noexcept { return code_; }

 private:
  ExitCode code_;
};

/// Input that violates the data contract. The message names file, line, column, value, trial and
/// what was expected, e.g. `p07.csv:1184: column 'pad': 1.7 is outside [0, 1] (trial P07/adaptive/3)`.
class InvalidData : public Error {
 public:
  explicit InvalidData(const std::string& message) : Error(ExitCode::invalid_data, message) {}
};

/// A bad command line or an impossible combination of settings.
class UsageError : public Error {
 public:
  explicit UsageError(const std::string& message) : Error(ExitCode::usage, message) {}
};

/// A file that cannot be opened, read, written or renamed.
class IoError : public Error {
 public:
  explicit IoError(const std::string& message) : Error(ExitCode::io, message) {}
};

}  // namespace feint
