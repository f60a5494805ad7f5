// The group commit's acknowledgement: an append is acknowledged (its Result has no error, its
// callback runs) only after the file it went to was fdatasync()ed, and never when that sync
// failed. A SIGKILL cannot show a missing sync (the page cache survives it), so fdatasync() is
// interposed in this test program: it logs each sync and fails on demand with EIO, as a dying
// disk does. (Mutation guards, docs/testing.md: skipping the sync, or ignoring its error.)
#include <dlfcn.h>
#include <unistd.h>
#include <gtest/gtest.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <future>
#include <mutex>
#include <set>
#include <string>
#include <vector>

#include "../../src/collect/durable.hpp"
#include "collect_helpers.hpp"
#include "feint/error.hpp"

namespace {

std::mutex g_mu;
bool g_watch = false;              // log the syncs (only while a test here watches)
std::vector<std::string> g_log;    // "sync <path>", "ack", in order
int g_fail = 0;                    // the next g_fail syncs fail with EIO
std::set<std::string> g_failed;    // the files whose sync failed

std::string path_of(int fd) {
  char buf[4096];
  const std::string link = "/proc/self/fd/" + std::to_string(fd);
  const ssize_t n = ::readlink(link.c_str(), buf, sizeof buf - 1);
  return n > 0 ? std::string(buf, static_cast<std::size_t>(n)) : std::string();
}

void note(const std::string& event) {
  std::lock_guard lock(g_mu);
  if (g_watch) g_log.push_back(event);
}

}  // namespace

// Interposes libc's fdatasync() for the whole test program (the collect library calls it from
// its writer and sync threads); it forwards to the real one unless a failure is asked for.
extern "C" int fdatasync(int fd) {
  using Fn = int (*)(int);
  static const Fn real = [] {
    Fn f = nullptr;
    void* p = ::dlsym(RTLD_NEXT, "fdatasync");
    std::memcpy(&f, &p, sizeof f);
    return f;
  }();
  {
    std::lock_guard lock(g_mu);
    if (g_watch) {
      const std::string path = path_of(fd);
      g_log.push_back("sync " + path);
      if (g_fail > 0) {
        --g_fail;
        g_failed.insert(path);
        errno = EIO;
        return -1;
      }
    }
  }
  return real(fd);
}

namespace feint::collect {
namespace {

namespace fs = std::filesystem;
using detail::GroupCommitter;

struct Watch {
  explicit Watch(int fail = 0) {
    std::lock_guard lock(g_mu);
    g_watch = true;
    g_log.clear();
    g_failed.clear();
    g_fail = fail;
  }
  ~Watch() {
    std::lock_guard lock(g_mu);
    g_watch = false;
    g_fail = 0;
  }
  static std::vector<std::string> log() {
    std::lock_guard lock(g_mu);
    return g_log;
  }
};

GroupCommitter::Append line_to(const fs::path& p, const std::string& data) {
  return {p, "h\n", data + "\n"};
}

std::size_t position(const std::vector<std::string>& log, const std::string& event) {
  for (std::size_t i = 0; i < log.size(); ++i)
    if (log[i] == event) return i;
  return log.size();
}

TEST(CommitAcknowledgement, ACallbackRunsOnlyAfterEveryFileOfItsCommitWasSynced) {
  const fs::path dir = fs::canonical(testing::fresh_dir("ack_after_sync"));
  for (const std::size_t files : {1u, 3u}) {  // one file (sync_one) and several (sync_together)
    GroupCommitter c;
    Watch w;
    std::vector<GroupCommitter::Append> items;
    for (std::size_t i = 0; i < files; ++i)
      items.push_back(line_to(dir / ("f" + std::to_string(files) + "_" + std::to_string(i) + ".csv"), "x"));
    std::promise<std::vector<GroupCommitter::Result>> done;
    c.commit_async(items, [&](std::vector<GroupCommitter::Result> r) {
      note("ack");
      done.set_value(std::move(r));
    });
    const auto results = done.get_future().get();
    const auto log = Watch::log();
    const std::size_t ack = position(log, "ack");
    ASSERT_LT(ack, log.size());
    for (std::size_t i = 0; i < files; ++i) {
      EXPECT_TRUE(results[i].error.empty()) << results[i].error;
      EXPECT_LT(position(log, "sync " + items[i].path.string()), ack)
          << items[i].path << " acknowledged before (or without) its sync";
    }
  }
}

TEST(CommitAcknowledgement, ABlockingCommitReturnsOnlyAfterTheSync) {
  const fs::path dir = fs::canonical(testing::fresh_dir("ack_blocking"));
  GroupCommitter c;
  Watch w;
  const auto r = c.commit({line_to(dir / "a.csv", "1")});
  note("ack");
  ASSERT_EQ(r.size(), 1u);
  EXPECT_TRUE(r[0].error.empty());
  const auto log = Watch::log();
  EXPECT_LT(position(log, "sync " + (dir / "a.csv").string()), position(log, "ack"));
}

TEST(CommitAcknowledgement, AnAppendWhoseSyncFailedIsNotAcknowledged) {
  const fs::path dir = fs::canonical(testing::fresh_dir("ack_sync_failed"));
  {
    GroupCommitter c;
    Watch w(1);  // a single file: its one sync fails
    const auto r = c.commit({line_to(dir / "one.csv", "1")});
    ASSERT_EQ(r.size(), 1u);
    EXPECT_NE(r[0].error.find("cannot sync"), std::string::npos) << "acknowledged: '" << r[0].error << "'";
    {
      std::lock_guard lock(g_mu);
      g_fail = 1;  // append(): its sync fails too
    }
    EXPECT_THROW(c.append(dir / "two.csv", "h\n", "2\n"), feint::IoError);
  }
  {
    GroupCommitter c;
    Watch w;
    c.commit({line_to(dir / "p.csv", "0"), line_to(dir / "q.csv", "0")});  // both exist now
  }
  GroupCommitter c;
  Watch w(1);  // two files synced together: exactly the one whose sync failed is not acknowledged
  const auto r = c.commit({line_to(dir / "p.csv", "1"), line_to(dir / "q.csv", "1")});
  std::set<std::string> failed;
  {
    std::lock_guard lock(g_mu);
    failed = g_failed;
  }
  ASSERT_EQ(failed.size(), 1u);
  EXPECT_EQ(r[0].error.empty(), failed.count((dir / "p.csv").string()) == 0) << r[0].error;
  EXPECT_EQ(r[1].error.empty(), failed.count((dir / "q.csv").string()) == 0) << r[1].error;
}

}  // namespace
}  // namespace feint::collect
