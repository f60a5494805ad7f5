#include <sys/mman.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <string>

#include "harness.hpp"

namespace feint::fuzz::detail {

std::string as_file(const std::uint8_t* data, std::size_t size) {
  // One memory-backed file per process: no disk traffic, nothing left behind.
  static const int fd = ::memfd_create("feint-fuzz", 0);
  check(fd >= 0, "memfd_create failed");
  check(::ftruncate(fd, 0) == 0, "ftruncate failed");
  std::size_t done = 0;
  while (done < size) {
    const ssize_t n = ::pwrite(fd, data + done, size - done, static_cast<off_t>(done));
    check(n > 0, "pwrite failed");
    done += static_cast<std::size_t>(n);
  }
  return "/proc/self/fd/" + std::to_string(fd);
}

void check(bool ok, const char* what) {
  if (ok) return;
  std::fprintf(stderr, "fuzz invariant broken: %s\n", what);
  std::abort();
}

}  // namespace feint::fuzz::detail
