#include "feint/io/file_identity.hpp"

#include <fmt/format.h>
#include <sys/stat.h>

#include <filesystem>

#include "feint/error.hpp"

namespace feint::io {

bool same_file(const std::string& a, const std::string& b) {
  if (a.empty() || b.empty() || a == "-" || b == "-") return false;
  struct stat sa {
  }, sb{};
  const bool ea = ::stat(a.c_str(), &sa) == 0, eb = ::stat(b.c_str(), &sb) == 0;
  // A device or FIFO (/dev/stdout, a pipe) is written in place and destroys nothing; two names of
  // the same terminal are not "the same file" in the sense that matters here.
  if ((ea && !S_ISREG(sa.st_mode)) || (eb && !S_ISREG(sb.st_mode))) return false;
  if (ea && eb) return sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
  if (ea != eb) return false;  // one exists, the other does not
  std::error_code e1, e2;
  const auto ca = std::filesystem::weakly_canonical(a, e1);
  const auto cb = std::filesystem::weakly_canonical(b, e2);
  return !e1 && !e2 && ca == cb;
}

void refuse_overwriting_inputs(const std::vector<std::string>& inputs,
                               const std::vector<std::string>& outputs) {
  for (const auto& out : outputs) {
    for (const auto& in : inputs) {
      if (same_file(in, out)) {
        throw UsageError(
            fmt::format("the output '{}' is also an input ('{}'): feint never "
                        "overwrites its inputs",
                        out, in));
      }
    }
  }
}

}  // namespace feint::io
