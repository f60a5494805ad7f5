#include "feint/io/output.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <mutex>

#include <fmt/format.h>

#include "feint/error.hpp"

namespace feint::io {

namespace {

// Temporary files still open, so a signal handler can remove them (unlink is async-signal-safe).
constexpr std::size_t kMaxPending = 64;
std::array<std::atomic<const char*>, kMaxPending> g_pending{};
std::once_flag g_handlers_installed;

extern "C" void remove_pending_and_reraise(int sig) {
  for (auto& slot : g_pending) {
    if (const char* p = slot.load()) ::unlink(p);
  }
  std::signal(sig, SIG_DFL);
  std::raise(sig);
}

void install_handlers() {
  std::call_once(g_handlers_installed, [] {
    for (const int sig : {SIGINT, SIGTERM, SIGHUP}) {
      if (std::signal(sig, remove_pending_and_reraise) == SIG_IGN) std::signal(sig, SIG_IGN);
    }
  });
}

std::atomic<const char*>* register_pending(const char* path) {
  for (auto& slot : g_pending) {
    const char* expected = nullptr;
    if (slot.compare_exchange_strong(expected, path)) return &slot;
  }
  return nullptr;  // too many at once: still atomic, just not cleaned on a signal
}

}  // namespace

struct AtomicOutput::Impl {
  std::string path;
  std::string tmp;
  std::ofstream file;
  std::atomic<const char*>* slot = nullptr;
  bool to_stdout = false;
  bool direct = false;  // an existing device or FIFO (/dev/null, a pipe): written in place
  std::string target;   // the file renamed over (the path, or the file a symbolic link names)
  bool done = false;

  void discard() noexcept {
    if (slot != nullptr) slot->store(nullptr);
    slot = nullptr;
    if (file.is_open()) file.close();
    if (!tmp.empty()) ::unlink(tmp.c_str());
    tmp.clear();
  }
};

AtomicOutput::AtomicOutput(std::string path) : impl_(std::make_unique<Impl>()) {
  impl_->path = std::move(path);
  if (impl_->path == "-") {
    impl_->to_stdout = true;
    return;
  }
  // Renaming over a device or FIFO would replace it (as root, even /dev/null) with a regular file:
  // such targets are written in place. A symbolic link is followed, so the file it names is
  // replaced and the link stays.
  struct stat st {};
  std::string target = impl_->path;
  if (::stat(target.c_str(), &st) == 0 && !S_ISREG(st.st_mode)) {
    if (S_ISDIR(st.st_mode)) throw IoError(fmt::format("cannot write '{}': it is a folder", target));
    impl_->direct = true;
    impl_->file.open(target, std::ios::binary | std::ios::out);
    if (!impl_->file) throw IoError(fmt::format("cannot write '{}'", target));
    return;
  }
  std::error_code ec;
  if (std::filesystem::is_symlink(target, ec)) {
    const auto resolved = std::filesystem::weakly_canonical(target, ec);
    if (!ec) target = resolved.string();
  }
  install_handlers();
  const auto slash = target.find_last_of('/');
  const std::string dir = slash == std::string::npos ? "" : target.substr(0, slash + 1);
  const std::string base = slash == std::string::npos ? target : target.substr(slash + 1);
  std::string templ = dir + "." + base + ".feint-tmp-XXXXXX";
  const int fd = ::mkstemp(templ.data());
  if (fd < 0) {
    throw IoError(fmt::format("cannot write '{}': {}", impl_->path, std::strerror(errno)));
  }
  ::close(fd);
  impl_->tmp = templ;
  impl_->target = target;
  impl_->slot = register_pending(impl_->tmp.c_str());
  impl_->file.open(impl_->tmp, std::ios::binary | std::ios::trunc);
  if (!impl_->file) {
    impl_->discard();
    throw IoError(fmt::format("cannot write '{}'", impl_->path));
  }
}

AtomicOutput::~AtomicOutput() {
  if (!impl_->done && !impl_->to_stdout && !impl_->direct) impl_->discard();
}

std::ostream& AtomicOutput::stream() noexcept {
  return impl_->to_stdout ? std::cout : static_cast<std::ostream&>(impl_->file);
}

void AtomicOutput::commit() {
  if (impl_->done) return;
  if (impl_->to_stdout) {
    std::cout.flush();
    impl_->done = true;
    if (!std::cout) throw IoError("cannot write to standard output");
    return;
  }
  if (impl_->direct) {
    impl_->file.flush();
    const bool ok = static_cast<bool>(impl_->file);
    impl_->file.close();
    impl_->done = true;
    if (!ok) throw IoError(fmt::format("cannot write '{}'", impl_->path));
    return;
  }
  impl_->file.flush();
  const bool ok = static_cast<bool>(impl_->file);
  impl_->file.close();
  if (!ok || impl_->file.fail()) {
    impl_->discard();
    throw IoError(fmt::format("cannot write '{}' (disk full?)", impl_->path));
  }
  // Keep the usual permissions of a new file (mkstemp creates 0600).
  const mode_t mask = ::umask(0);
  ::umask(mask);
  ::chmod(impl_->tmp.c_str(), 0666 & ~mask);
  if (std::rename(impl_->tmp.c_str(), impl_->target.c_str()) != 0) {
    const int err = errno;
    impl_->discard();
    throw IoError(fmt::format("cannot write '{}': {}", impl_->path, std::strerror(err)));
  }
  if (impl_->slot != nullptr) impl_->slot->store(nullptr);
  impl_->slot = nullptr;
  impl_->tmp.clear();
  impl_->done = true;
}

const std::string& AtomicOutput::path() const noexcept { return impl_->path; }
const std::string& AtomicOutput::target() const noexcept {
  return impl_->target.empty() ? impl_->path : impl_->target;
}
bool AtomicOutput::is_stdout() const noexcept { return impl_->to_stdout; }
bool AtomicOutput::in_place() const noexcept { return impl_->direct; }

void commit_together(const std::vector<AtomicOutput*>& outputs) {
  // The folders of the targets, each locked once, in sorted order (no deadlock between runs).
  std::vector<std::string> dirs;
  for (const AtomicOutput* o : outputs) {
    if (o == nullptr || o->is_stdout() || o->in_place()) continue;
    const std::filesystem::path p(o->target());
    std::error_code ec;
    auto dir = std::filesystem::weakly_canonical(p, ec).parent_path();
    if (ec || dir.empty()) dir = p.parent_path().empty() ? std::filesystem::path(".") : p.parent_path();
    dirs.push_back(dir.string());
  }
  std::sort(dirs.begin(), dirs.end());
  dirs.erase(std::unique(dirs.begin(), dirs.end()), dirs.end());
  std::vector<int> fds;
  struct Unlock {
    std::vector<int>& fds;
    ~Unlock() {
      for (const int fd : fds) {
        ::flock(fd, LOCK_UN);
        ::close(fd);
      }
    }
  } unlock{fds};
  for (const auto& d : dirs) {
    const int fd = ::open(d.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd < 0) continue;  // cannot lock (e.g. no read permission): the renames are still atomic
    fds.push_back(fd);
    while (::flock(fd, LOCK_EX) != 0 && errno == EINTR) {
    }
  }
  for (AtomicOutput* o : outputs) {
    if (o != nullptr) o->commit();
  }
}

void write_file_atomically(const std::string& path, const std::string& content) {
  AtomicOutput out(path);
  out.stream() << content;
  out.commit();
}

}  // namespace feint::io
