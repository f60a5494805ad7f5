// Append-only, synced file writes for `feint collect` (src/collect/durable.hpp).
#include "durable.hpp"

#include <fcntl.h>
#include <fmt/compile.h>
#include <fmt/format.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <fstream>
#include <sstream>

#include "feint/error.hpp"

namespace feint::collect::detail {

namespace fs = std::filesystem;

namespace {

[[noreturn]] void fail(const fs::path& path, const char* what) {
  throw IoError(fmt::format("{}: {}: {}", path.string(), what, std::strerror(errno)));
}

void write_all(int fd, std::string_view data, const fs::path& path) {
  while (!data.empty()) {
    const ssize_t n = ::write(fd, data.data(), data.size());
    if (n < 0) {
      if (errno == EINTR) continue;
      fail(path, "cannot write");
    }
    data.remove_prefix(static_cast<std::size_t>(n));
  }
}

struct Fd {
  int fd = -1;
  ~Fd() {
    if (fd >= 0) ::close(fd);
  }
};

}  // namespace

void sync_directory(const fs::path& dir) {
  Fd d{::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC)};
  if (d.fd < 0) fail(dir, "cannot open folder");
  if (::fsync(d.fd) != 0) fail(dir, "cannot sync folder");
}

std::uint64_t append_durably(const fs::path& path, std::string_view header, std::string_view data) {
  Fd f{::open(path.c_str(), O_WRONLY | O_APPEND | O_CLOEXEC)};
  bool created = false;
  if (f.fd < 0 && errno == ENOENT) {
    f.fd = ::open(path.c_str(), O_WRONLY | O_APPEND | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
    created = f.fd >= 0;
  }
  if (f.fd < 0) fail(path, "cannot open for appending");
  struct stat st {};
  if (::fstat(f.fd, &st) != 0) fail(path, "cannot stat");
  const auto before = static_cast<std::uint64_t>(st.st_size);
  // An empty file (new, or left empty by a crash between its creation and its first write) gets
  // the header, in the same write as the first data: a file never holds rows without a header.
  std::string first;
  if (before == 0) {
    first.reserve(header.size() + data.size());
    first.append(header).append(data);
    data = first;
  }
  try {
    write_all(f.fd, data, path);
    if (::fdatasync(f.fd) != 0) fail(path, "cannot sync");
  } catch (const IoError&) {
    // Disk full, file too large, I/O error: this append is not acknowledged. Its own partial
    // bytes (never acknowledged; the page still has them and retries) are cut back at once, so
    // that the file ends with the last acknowledged line. If even that fails, the restart
    // recovery (or the next append's size check) sets the tail aside.
    const int saved = errno;
    if (::ftruncate(f.fd, static_cast<off_t>(before)) == 0) (void)::fdatasync(f.fd);
    errno = saved;
    throw;
  }
  if (created) sync_directory(path.parent_path());
  return before + data.size();
}

// ---- group commit ----

constexpr std::size_t kSyncThreads = 16;  // fdatasync() calls in flight at once
constexpr std::chrono::milliseconds kNoteDelay{500};  // the longest an unawaited append waits

struct GroupCommitter::Group {
  std::vector<Append> items;
  std::vector<Result> results;
  Done done;  // empty: nobody waits (enqueue())
  bool direct = false;  // `done` only wakes a waiting thread: called on the writer's thread
};

/// Threads kept for the parallel fdatasync() of a group (started once, not per group).
struct GroupCommitter::SyncPool {
  std::mutex mu;
  std::condition_variable cv, finished;
  std::function<void(std::size_t)> task;
  std::size_t count = 0;
  std::atomic<std::size_t> next{0};
  std::size_t active = 0;
  std::uint64_t generation = 0;
  bool stop = false;
  std::vector<std::thread> threads;

  explicit SyncPool(std::size_t n) {
    for (std::size_t i = 0; i < n; ++i) threads.emplace_back([this] { loop(); });
  }
  ~SyncPool() {
    {
      std::lock_guard lock(mu);
      stop = true;
    }
    cv.notify_all();
    for (auto& t : threads) t.join();
  }
  void work(const std::function<void(std::size_t)>& f, std::size_t n) {
    for (std::size_t i; (i = next++) < n;) f(i);
  }
  void loop() {
    std::uint64_t seen = 0;
    std::unique_lock lock(mu);
    for (;;) {
      cv.wait(lock, [&] { return stop || generation != seen; });
      if (stop) return;
      seen = generation;
      ++active;
      const auto f = task;
      const std::size_t n = count;
      lock.unlock();
      work(f, n);
      lock.lock();
      if (--active == 0) finished.notify_all();
    }
  }
  /// f(0) ... f(n - 1), spread over the pool and the calling thread; returns when all are done.
  void run(std::size_t n, std::function<void(std::size_t)> f) {
    {
      std::lock_guard lock(mu);
      task = std::move(f);
      count = n;
      next = 0;
      ++generation;
    }
    // Only as many helpers as there are calls besides the caller's own (each wake is a switch).
    for (std::size_t i = 1; i < std::min(n, threads.size() + 1); ++i) cv.notify_one();
    std::function<void(std::size_t)> mine;
    {
      std::lock_guard lock(mu);
      mine = task;
    }
    work(mine, n);
    std::unique_lock lock(mu);
    finished.wait(lock, [&] { return active == 0; });
  }
};

GroupCommitter::GroupCommitter()
    : pool_(std::make_unique<SyncPool>(kSyncThreads - 1)),
      thread_([this] { writer(); }),
      completion_thread_([this] { completer(); }) {}

GroupCommitter::~GroupCommitter() {
  {
    std::lock_guard lock(mu_);
    stop_ = true;
  }
  work_.notify_all();
  thread_.join();  // writes and syncs everything queued, then hands it to the completer
  completed_.notify_all();
  completion_thread_.join();
}

void GroupCommitter::commit_async(std::vector<Append> items, Done done) {
  auto g = std::make_shared<Group>();
  g->items = std::move(items);
  g->results.resize(g->items.size());
  g->done = std::move(done);
  std::lock_guard lock(mu_);
  if (g->done) ++waiters_;
  queue_.push_back(std::move(g));
  work_.notify_one();
}

std::vector<GroupCommitter::Result> GroupCommitter::commit(std::vector<Append> items) {
  std::mutex m;
  std::condition_variable cv;
  bool finished = false;
  std::vector<Result> out;
  auto g = std::make_shared<Group>();
  g->items = std::move(items);
  g->results.resize(g->items.size());
  // Woken from the writer's thread, not the completer's: a completion callback may wait here.
  g->direct = true;
  g->done = [&](std::vector<Result> r) {
    std::lock_guard lock(m);
    out = std::move(r);
    finished = true;
    cv.notify_one();
  };
  {
    std::lock_guard lock(mu_);
    ++waiters_;
    queue_.push_back(std::move(g));
    work_.notify_one();
  }
  std::unique_lock lock(m);
  cv.wait(lock, [&] { return finished; });
  return out;
}

void GroupCommitter::enqueue(std::vector<Append> items) { commit_async(std::move(items), {}); }

std::uint64_t GroupCommitter::append(const fs::path& path, std::string_view header,
                                     std::string data) {
  std::vector<Append> one;
  one.push_back({path, std::string(header), std::move(data)});
  const auto r = commit(std::move(one));
  if (!r[0].error.empty()) throw IoError(r[0].error);
  return r[0].size;
}

std::uint64_t GroupCommitter::groups() const noexcept {
  std::lock_guard lock(mu_);
  return groups_;
}
std::uint64_t GroupCommitter::appends() const noexcept {
  std::lock_guard lock(mu_);
  return appends_;
}
double GroupCommitter::busy_seconds() const noexcept {
  std::lock_guard lock(mu_);
  return busy_seconds_;
}

void GroupCommitter::set_sync_delay(std::chrono::milliseconds delay) noexcept {
  sync_delay_ms_ = delay.count();
}

void GroupCommitter::writer() {
  std::unique_lock lock(mu_);
  for (;;) {
    // Appends that nobody waits for (enqueue(): audit lines) do not start a group of their own:
    // they go with the next one that somebody waits for, or after kNoteDelay at the latest.
    // (At a study's pace, a group for every `round_shown` line doubled the syncs.)
    work_.wait_for(lock, kNoteDelay, [&] { return stop_ || waiters_ > 0; });
    if (queue_.empty()) {
      if (stop_) break;  // stopping, nothing left
      continue;
    }
    // Everything that arrived while the previous group was being written and synced, up to
    // kMaxGroupFiles distinct files (each is open until the group's sync).
    std::vector<std::shared_ptr<Group>> batch;
    std::vector<const fs::path*> files;
    while (!queue_.empty()) {
      const auto& g = *queue_.front();
      std::size_t more = 0;
      for (const auto& item : g.items)
        if (std::none_of(files.begin(), files.end(), [&](const fs::path* f) { return *f == item.path; }))
          ++more;
      if (!batch.empty() && files.size() + more > kMaxGroupFiles) break;
      for (const auto& item : g.items)
        if (std::none_of(files.begin(), files.end(), [&](const fs::path* f) { return *f == item.path; }))
          files.push_back(&item.path);
      if (queue_.front()->done) --waiters_;
      batch.push_back(std::move(queue_.front()));
      queue_.pop_front();
    }
    lock.unlock();
    const auto t0 = std::chrono::steady_clock::now();
    write_batch(batch);
    const std::chrono::duration<double> busy = std::chrono::steady_clock::now() - t0;
    lock.lock();
    busy_seconds_ += busy.count();
    ++groups_;
    for (auto& g : batch) appends_ += g->items.size();
    lock.unlock();
    for (auto& g : batch)
      if (g->direct) g->done(std::move(g->results));
    lock.lock();
    done_.push_back(std::move(batch));
    completed_.notify_one();
  }
  writer_stopped_ = true;
  completed_.notify_all();
}

void GroupCommitter::completer() {
  std::unique_lock lock(mu_);
  for (;;) {
    completed_.wait(lock, [&] { return writer_stopped_ || !done_.empty(); });
    if (done_.empty()) return;  // the writer has stopped and everything is answered
    auto batch = std::move(done_.front());
    done_.pop_front();
    lock.unlock();
    // Outside the lock: a callback may commit again (even synchronously: the writer goes on).
    for (auto& g : batch)
      if (g->done && !g->direct) g->done(std::move(g->results));
    lock.lock();
  }
}

namespace {

/// A file of a group: opened once for the group, its size followed through the group's appends.
struct BatchFile {
  Fd fd;
  std::uint64_t size = 0;
  bool created = false;
  std::string error;
  std::vector<GroupCommitter::Result*> results;  // the appends to it, for a failed sync
};
using BatchFiles = std::vector<std::pair<fs::path, std::unique_ptr<BatchFile>>>;

/// The group's file for `path`, opened (created when missing) on its first append.
BatchFile& file_of(BatchFiles& files, const fs::path& path) {
  for (auto& [p, f] : files)
    if (p == path) return *f;
  auto f = std::make_unique<BatchFile>();
  f->fd.fd = ::open(path.c_str(), O_WRONLY | O_APPEND | O_CLOEXEC);
  if (f->fd.fd < 0 && errno == ENOENT) {
    f->fd.fd = ::open(path.c_str(), O_WRONLY | O_APPEND | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
    f->created = f->fd.fd >= 0;
  }
  struct stat st {};
  if (f->fd.fd < 0) {
    f->error = fmt::format("{}: cannot open for appending: {}", path.string(), std::strerror(errno));
  } else if (::fstat(f->fd.fd, &st) != 0) {
    f->error = fmt::format("{}: cannot stat: {}", path.string(), std::strerror(errno));
  } else {
    f->size = static_cast<std::uint64_t>(st.st_size);
  }
  files.emplace_back(path, std::move(f));
  return *files.back().second;
}

/// Writes one commit's appends in order; after a failed one, the rest are not written.
void write_commit(std::vector<GroupCommitter::Append>& items,
                  std::vector<GroupCommitter::Result>& results, BatchFiles& files) {
  bool failed = false;
  for (std::size_t i = 0; i < items.size(); ++i) {
    auto& item = items[i];
    auto& res = results[i];
    if (failed) {
      res.error = "not written: an earlier append of the same commit failed";
      continue;
    }
    BatchFile& f = file_of(files, item.path);
    if (!f.error.empty()) {
      res.error = f.error;
      failed = true;
      continue;
    }
    std::string_view data = item.data;
    std::string first;
    if (f.size == 0) {  // an empty file gets its header first, in the same write
      first.append(item.header).append(item.data);
      data = first;
    }
    try {
      write_all(f.fd.fd, data, item.path);
      f.size += data.size();
      res.size = f.size;
      f.results.push_back(&res);
    } catch (const IoError& e) {
      // Not acknowledged: its own partial bytes are cut back (see append_durably).
      (void)::ftruncate(f.fd.fd, static_cast<off_t>(f.size));
      res.error = e.what();
      failed = true;
    }
  }
}

/// Marks every append to `f` that has not failed yet as failed, for `why`.
void fail_all(BatchFile& f, const std::string& why) {
  for (GroupCommitter::Result* r : f.results)
    if (r->error.empty()) r->error = why;
}

/// The sync of a group that touched a single file (and its folder, when it created it).
void sync_one(const BatchFiles& files, BatchFile& f) {
  if (::fdatasync(f.fd.fd) != 0) fail_all(f, fmt::format("cannot sync: {}", std::strerror(errno)));
  for (auto& [p, fp] : files) {
    if (fp.get() != &f || !f.created) continue;
    try {
      sync_directory(p.parent_path());
    } catch (const IoError& e) {
      fail_all(f, e.what());
    }
  }
}

// fdatasync() of every file at once, from several threads: the file system joins them into
// one journal commit (ext4, xfs), so the group costs about one sync, and only these files'
// data is flushed (syncfs() would flush everything else on the disk too). (A template: the pool's
// type is private to GroupCommitter.)
template <class Pool>
void sync_together(const BatchFiles& files, const std::vector<BatchFile*>& touched, Pool& pool) {
  std::vector<fs::path> dirs;
  for (auto& [p, f] : files)
    if (f->created && std::find(dirs.begin(), dirs.end(), p.parent_path()) == dirs.end())
      dirs.push_back(p.parent_path());
  std::vector<std::string> errors(touched.size() + dirs.size());
  auto work = [&](std::size_t i) {
    if (i < touched.size()) {
      if (::fdatasync(touched[i]->fd.fd) != 0)
        errors[i] = fmt::format("cannot sync: {}", std::strerror(errno));
    } else {
      try {
        sync_directory(dirs[i - touched.size()]);
      } catch (const IoError& e) {
        errors[i] = e.what();
      }
    }
  };
  pool.run(errors.size(), work);
  for (std::size_t i = 0; i < touched.size(); ++i)
    if (!errors[i].empty()) fail_all(*touched[i], errors[i]);
  for (std::size_t d = 0; d < dirs.size(); ++d) {
    if (errors[touched.size() + d].empty()) continue;
    for (auto& [p, f] : files)
      if (f->created && p.parent_path() == dirs[d]) fail_all(*f, errors[touched.size() + d]);
  }
}

}  // namespace

void GroupCommitter::write_batch(std::vector<std::shared_ptr<Group>>& batch) {
  BatchFiles files;
  // 1. Write, in queue order.
  for (auto& g : batch) write_commit(g->items, g->results, files);
  // 2. One sync for the whole group.
  std::vector<BatchFile*> touched;
  for (auto& [p, f] : files)
    if (!f->results.empty() || f->created) touched.push_back(f.get());
  if (touched.empty()) return;
  if (const auto ms = sync_delay_ms_.load(); ms > 0)
    std::this_thread::sleep_for(std::chrono::milliseconds(ms));
  if (touched.size() == 1) {
    sync_one(files, *touched.front());
  } else {
    sync_together(files, touched, *pool_);
  }
}

fs::path unique_aside(const fs::path& dir, const std::string& name) {
  std::error_code ec;
  fs::path p = dir / name;
  for (int i = 1; fs::exists(p, ec); ++i) p = dir / fmt::format("{}.{}", name, i);
  return p;
}

std::string read_all(const fs::path& path) {
  std::error_code ec;
  if (!fs::exists(path, ec)) return {};
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IoError(fmt::format("{}: cannot open for reading", path.string()));
  std::ostringstream ss;
  ss << in.rdbuf();
  if (in.bad()) throw IoError(fmt::format("{}: cannot read", path.string()));
  return ss.str();
}

std::uint64_t file_size_or_zero(const fs::path& path) {
  std::error_code ec;
  const auto n = fs::file_size(path, ec);
  return ec ? 0 : static_cast<std::uint64_t>(n);
}

void replace_with_prefix(const fs::path& path, std::uint64_t keep, const fs::path& aside) {
  const std::string content = read_all(path);
  replace_with_content(path, std::string_view(content).substr(0, keep), aside);
}

void replace_with_content(const fs::path& path, std::string_view content, const fs::path& aside) {
  const fs::path tmp = path.parent_path() / ("." + path.filename().string() + ".recovering");
  std::error_code ec;
  fs::create_directories(aside.parent_path(), ec);
  if (ec)
    throw IoError(
        fmt::format("{}: cannot create folder: {}", aside.parent_path().string(), ec.message()));
  fs::remove(tmp, ec);
  const bool keep = !content.empty();
  if (keep) {
    Fd f{::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644)};
    if (f.fd < 0) fail(tmp, "cannot create");
    write_all(f.fd, content, tmp);
    if (::fsync(f.fd) != 0) fail(tmp, "cannot sync");
  }
  fs::rename(path, aside, ec);
  if (ec)
    throw IoError(fmt::format("{}: cannot move aside to {}: {}", path.string(), aside.string(),
                              ec.message()));
  if (keep) {
    fs::rename(tmp, path, ec);
    if (ec)
      throw IoError(fmt::format("{}: cannot rename into place: {}", path.string(), ec.message()));
  }
  sync_directory(path.parent_path());
  sync_directory(aside.parent_path());
}

std::string utc_now() {
  const std::time_t now = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&now, &tm);
  return fmt::format("{:04}-{:02}-{:02}T{:02}:{:02}:{:02}Z", tm.tm_year + 1900, tm.tm_mon + 1,
                     tm.tm_mday, tm.tm_hour, tm.tm_min, tm.tm_sec);
}

std::int64_t unix_now() { return static_cast<std::int64_t>(std::time(nullptr)); }

std::string bounded_detail(std::string_view text) {
  std::string out;
  const std::string suffix = text.size() > kMaxDetail
                                 ? fmt::format("... [{} bytes in all]", text.size())
                                 : std::string();
  std::size_t keep = suffix.empty() ? text.size() : kMaxDetail - suffix.size();
  while (keep > 0 && keep < text.size() && (static_cast<unsigned char>(text[keep]) & 0xC0) == 0x80)
    --keep;  // not inside a UTF-8 character
  out.reserve(keep + suffix.size());
  for (std::size_t i = 0; i < keep; ++i) {
    const auto c = static_cast<unsigned char>(text[i]);
    out += c < 0x20 || c == 0x7F ? '?' : c == '"' ? '\'' : text[i];
  }
  return out + suffix;
}

void append_double(std::string& out, double v) {
  char buf[32];  // the longest shortest form is 24 characters (-2.2250738585072014e-308)
  const char* end = fmt::format_to(buf, FMT_COMPILE("{}"), v);
  out.append(buf, static_cast<std::size_t>(end - buf));
}

void append_metres(std::string& out, double metres) {
  const double tenths = std::round(metres * 1e4);
  if (!(std::fabs(tenths) < 1e15)) {  // far beyond any geometry: the general form
    append_double(out, tenths / 1e4 + 0.0);
    return;
  }
  // k / 10^4 with at most 4 decimals, trailing zeros dropped: the shortest form that reads back
  // as the double nearest to it, which is what fmt writes for round(m * 1e4) / 1e4.
  auto k = static_cast<long long>(tenths);
  if (k < 0) {
    out += '-';
    k = -k;
  }
  out += fmt::format_int(k / 10000).c_str();
  int frac = static_cast<int>(k % 10000);
  if (frac == 0) return;
  char digits[5] = {'.', 0, 0, 0, 0};
  int n = 4;
  while (frac % 10 == 0) {
    frac /= 10;
    --n;
  }
  for (int i = n; i >= 1; --i) {
    digits[i] = static_cast<char>('0' + frac % 10);
    frac /= 10;
  }
  out.append(digits, static_cast<std::size_t>(n) + 1);
}

std::string csv_field(std::string_view text) {
  if (text.find_first_of(",\"\r\n") == std::string_view::npos) return std::string(text);
  std::string out = "\"";
  for (char c : text) {
    if (c == '"') out += '"';
    out += c;
  }
  out += '"';
  return out;
}

}  // namespace feint::collect::detail
