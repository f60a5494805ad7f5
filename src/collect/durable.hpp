// src/collect/durable.hpp - append-only, synced file writes (details of the collect module).
#pragma once

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <filesystem>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <string_view>
#include <thread>
#include <vector>

namespace feint::collect::detail {

/// Appends `data` to `path` with one write() loop and fdatasync() before returning; writes
/// `header` first (in the same write) when the file does not exist or is empty, and syncs the
/// folder of a new file. Returns the file size after the append. Throws IoError; a failed append
/// cuts its own partial bytes back, so the file still ends with the last acknowledged line.
std::uint64_t append_durably(const std::filesystem::path& path, std::string_view header,
                             std::string_view data);

/// Group commit: the appends of concurrent requests are written by one writer thread and made
/// durable together: everything that arrived while the previous group was being synced is
/// written (each append one write(), in queue order), then the files touched are fdatasync()ed
/// at once from up to 16 threads, which the file system joins into one journal commit (ext4,
/// xfs); only then is any of the group's callers answered. A file gets its header when it is
/// empty, and a failed append cuts its own partial bytes back (as append_durably()), so the
/// crash guarantees are those of one append at a time.
///
/// Callers do not wait: commit_async() queues the appends and returns; its callback runs once
/// they are synced, on the committer's completion thread (not the writer's: the next group's
/// writes go on meanwhile, and a callback may commit again, even synchronously, as commit()
/// wakes its caller from the writer's thread). A group holds
/// at most kMaxGroupFiles distinct files (so that the descriptors it opens are bounded); what
/// does not fit goes to the next group, in order.
class GroupCommitter {
 public:
  struct Append {
    std::filesystem::path path;
    std::string header;  // written first when the file is empty
    std::string data;
  };
  struct Result {
    std::uint64_t size = 0;  // the file's size after this append
    std::string error;       // empty: written and synced
  };
  using Done = std::function<void(std::vector<Result>)>;
  static constexpr std::size_t kMaxGroupFiles = 64;
  GroupCommitter();
  ~GroupCommitter();
  GroupCommitter(const GroupCommitter&) = delete;
  GroupCommitter& operator=(const GroupCommitter&) = delete;
  /// Appends every item, in order, durably, then calls `done` (on the completion thread); an item
  /// after a failed one is not written (its error says so). Never throws for I/O errors.
  void commit_async(std::vector<Append> items, Done done);
  /// The same, blocking until synced (also from a completion callback).
  std::vector<Result> commit(std::vector<Append> items);
  /// Queues appends for the next group without waiting for their sync (for audit lines that
  /// acknowledge nothing); an error is ignored. They do not start a group by themselves: they are
  /// written with the next appends somebody waits for, or within half a second.
  void enqueue(std::vector<Append> items);
  /// One append; throws IoError when it fails.
  std::uint64_t append(const std::filesystem::path& path, std::string_view header,
                       std::string data);
  /// Groups synced so far, and appends in them (for the benchmark's figures).
  std::uint64_t groups() const noexcept;
  std::uint64_t appends() const noexcept;
  /// Seconds spent writing and syncing groups (the writer's busy time).
  double busy_seconds() const noexcept;
  /// Test hook: a pause before every group's sync (a slow disk).
  void set_sync_delay(std::chrono::milliseconds delay) noexcept;

 private:
  struct Group;
  struct SyncPool;
  void writer();
  void completer();
  void write_batch(std::vector<std::shared_ptr<Group>>& batch);
  mutable std::mutex mu_;
  std::condition_variable work_, completed_;
  std::deque<std::shared_ptr<Group>> queue_;
  std::deque<std::vector<std::shared_ptr<Group>>> done_;  // synced groups, for the completer
  bool stop_ = false, writer_stopped_ = false;
  std::size_t waiters_ = 0;  // groups queued that somebody waits for
  std::uint64_t groups_ = 0, appends_ = 0;
  double busy_seconds_ = 0;
  std::atomic<long long> sync_delay_ms_{0};
  std::unique_ptr<SyncPool> pool_;
  std::thread thread_, completion_thread_;
};

/// The whole file ("" when it does not exist). Throws IoError when it exists but cannot be read.
std::string read_all(const std::filesystem::path& path);

/// Size of a file (0 when it does not exist).
std::uint64_t file_size_or_zero(const std::filesystem::path& path);

/// `dir/name`, or `dir/name.1`, `.2`... when taken: a file set aside never replaces another.
std::filesystem::path unique_aside(const std::filesystem::path& dir, const std::string& name);

/// Keeps only the first `keep` bytes of `path` without truncating anything: the prefix is written
/// to a new file that is synced and renamed into place; the original is moved to `aside`.
void replace_with_prefix(const std::filesystem::path& path, std::uint64_t keep,
                         const std::filesystem::path& aside);

/// Replaces `path` by `content` the same way: written to a new file, synced, renamed into place;
/// the original is moved whole to `aside`.
void replace_with_content(const std::filesystem::path& path, std::string_view content,
                          const std::filesystem::path& aside);

/// fsync() of a folder, so that a created or renamed entry survives a crash.
void sync_directory(const std::filesystem::path& dir);

/// Now as `2026-11-23T16:05:00Z`, and as Unix seconds.
std::string utc_now();
std::int64_t unix_now();

/// An events-log detail of at most kMaxDetail bytes, so that an events line stays under 512 bytes
/// whatever a client sends: control characters become '?', double quotes become single ones (no
/// CSV quote doubling), and a longer text is cut (at a UTF-8 character boundary) and ends with
/// "... [N bytes in all]".
inline constexpr std::size_t kMaxDetail = 380;
std::string bounded_detail(std::string_view text);

/// Appends a finite `v` as io::format_double() writes it (fmt's shortest round-trip form), with
/// no temporary string: the log rows are mostly numbers.
void append_double(std::string& out, double v);

/// Appends `metres` as sim::format_metres() writes it (to 0.1 mm, -0 as 0), from its integer
/// count of 0.1 mm instead of a floating-point formatting.
void append_metres(std::string& out, double metres);

/// A CSV field, quoted when it holds a comma, quote or line break (RFC 4180).
std::string csv_field(std::string_view text);

}  // namespace feint::collect::detail
