#include "feint/io/csv.hpp"

#include <unistd.h>
#include <zlib.h>

#include <sys/stat.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <condition_variable>
#include <cstring>
#include <deque>
#include <mutex>
#include <thread>

#include <fmt/format.h>

#include "feint/error.hpp"
#include "feint/io/number.hpp"

namespace feint::io {

namespace {

// Bytes asked of zlib per read. The fuzz build (tests/fuzz/run.sh) makes it tiny, so that records
// cross block boundaries in small inputs and each input does not allocate megabytes.
#ifndef FEINT_CSV_CHUNK
#define FEINT_CSV_CHUNK (std::size_t{1} << 20)
#endif
constexpr std::size_t kChunk = FEINT_CSV_CHUNK;
#ifndef FEINT_GZ_BUFFER
#define FEINT_GZ_BUFFER (1U << 18)
#endif

std::string display_name(const std::string& path) { return path == "-" ? "<stdin>" : path; }

// Reads (and decompresses) a regular file on a background thread, a few blocks ahead of the
// parser, so that reading/inflating and parsing use two cores. Standard input is read on the
// caller's thread instead (a thread blocked on an open terminal could not be joined).
class Prefetcher {
 public:
  static constexpr std::size_t kMaxQueued = 4;

  Prefetcher(gzFile file, std::string name) : file_(file), name_(std::move(name)) {
    thread_ = std::thread([this] { run(); });
  }
  ~Prefetcher() {
    {
      std::lock_guard<std::mutex> lock(m_);
      stop_ = true;
    }
    cv_.notify_all();
    thread_.join();
  }
  Prefetcher(const Prefetcher&) = delete;
  Prefetcher& operator=(const Prefetcher&) = delete;

  // Appends the next block to `out` at `at` (out has room for kChunk bytes). Returns the number
  // of bytes (0 = end of input). Throws IoError when the thread failed to read.
  std::size_t take(char* at) {
    std::unique_lock<std::mutex> lock(m_);
    cv_.wait(lock, [&] { return !full_.empty() || done_; });
    if (full_.empty()) {
      if (!error_.empty()) throw IoError(error_);
      return 0;
    }
    std::vector<char> block = std::move(full_.front());
    full_.pop_front();
    lock.unlock();
    std::memcpy(at, block.data(), block.size());
    const std::size_t n = block.size();
    lock.lock();
    free_.push_back(std::move(block));
    lock.unlock();
    cv_.notify_all();
    return n;
  }
  std::uint64_t offset() const noexcept { return offset_.load(std::memory_order_relaxed); }
  bool is_gzip() const noexcept { return is_gzip_.load(std::memory_order_relaxed); }

 private:
  void run() {
    bool first = true;
    for (;;) {
      std::vector<char> block;
      {
        std::unique_lock<std::mutex> lock(m_);
        cv_.wait(lock, [&] { return stop_ || full_.size() < kMaxQueued; });
        if (stop_) return;
        if (!free_.empty()) {
          block = std::move(free_.back());
          free_.pop_back();
        }
      }
      std::string error;
      int n = 0;
      try {
        block.resize(kChunk);
        n = gzread(file_, block.data(), static_cast<unsigned>(kChunk));
        int errnum = 0;
        if (n < 0) {
          const char* msg = gzerror(file_, &errnum);
          error = fmt::format("cannot read '{}': {}", name_,
                              errnum == Z_ERRNO ? std::strerror(errno) : msg);
        } else if (n == 0) {
          // A truncated gzip stream reads as a short file: say so instead of parsing half a record.
          const char* msg = gzerror(file_, &errnum);
          if (errnum != Z_OK && errnum != Z_STREAM_END) {
            error = fmt::format("cannot read '{}': {}", name_, msg);
          }
        }
        if (first && n > 0) is_gzip_.store(gzdirect(file_) == 0, std::memory_order_relaxed);
        first = false;
        const auto off = gzoffset(file_);
        if (off >= 0) offset_.store(static_cast<std::uint64_t>(off), std::memory_order_relaxed);
      } catch (const std::exception& e) {
        error = fmt::format("cannot read '{}': {}", name_, e.what());
        n = -1;
      }
      {
        std::lock_guard<std::mutex> lock(m_);
        if (n > 0) {
          block.resize(static_cast<std::size_t>(n));
          full_.push_back(std::move(block));
        } else {
          error_ = error;
          done_ = true;
        }
      }
      cv_.notify_all();
      if (n <= 0) return;
    }
  }

  gzFile file_;
  std::string name_;
  std::thread thread_;
  std::mutex m_;
  std::condition_variable cv_;
  std::deque<std::vector<char>> full_;
  std::vector<std::vector<char>> free_;
  bool done_ = false;
  bool stop_ = false;
  std::string error_;
  std::atomic<std::uint64_t> offset_{0};
  std::atomic<bool> is_gzip_{false};
};

}  // namespace

struct CsvReader::Impl {
  std::string path;
  CsvOptions options;
  gzFile file = nullptr;
  bool is_gzip = false;
  bool eof = false;

  std::vector<char> buf;
  std::size_t pos = 0;  // start of unparsed data
  std::size_t end = 0;  // end of valid data

  std::vector<std::string> header;
  std::vector<std::string> header_key;  // trimmed, lower-case
  std::vector<std::string_view> fields;
  std::string scratch;  // unescaped quoted fields of the current record
  char delimiter = ',';
  std::uint64_t line = 0;
  std::uint64_t next_line = 1;
  bool header_seen = false;  // the first non-blank record (the header) has been read
  bool replay = false;       // no_header: next() returns the record already read first
  std::uint64_t records = 0;
  std::unique_ptr<Prefetcher> prefetch;  // regular files only

  ~Impl() {
    prefetch.reset();  // joins the reading thread before the file is closed
    if (file != nullptr) gzclose(file);
  }

  [[noreturn]] void fail(std::uint64_t at_line, const std::string& what) const {
    throw InvalidData(fmt::format("{}:{}: {}", display_name(path), at_line, what));
  }

  void open() {
    if (path == "-") {
      const int fd = dup(STDIN_FILENO);
      file = fd < 0 ? nullptr : gzdopen(fd, "rb");
    } else {
      file = gzopen(path.c_str(), "rb");
    }
    if (file == nullptr) {
      throw IoError(fmt::format("cannot open '{}': {}", display_name(path), std::strerror(errno)));
    }
    gzbuffer(file, FEINT_GZ_BUFFER);
    buf.resize(2 * kChunk);
    struct stat st {};
    if (path != "-" && ::stat(path.c_str(), &st) == 0 && S_ISREG(st.st_mode)) {
      prefetch = std::make_unique<Prefetcher>(file, display_name(path));
    }
  }

  // Moves unparsed bytes to the front, grows the buffer when full, reads more.
  // Returns false when nothing more could be read (end of input).
  bool refill() {
    if (eof) return false;
    if (pos > 0) {
      std::memmove(buf.data(), buf.data() + pos, end - pos);
      end -= pos;
      pos = 0;
    }
    if (buf.size() - end < kChunk) buf.resize(std::max(buf.size() * 2, end + kChunk));
    if (prefetch) {
      const std::size_t got = prefetch->take(buf.data() + end);
      if (got == 0) {
        eof = true;
        return false;
      }
      if (!is_gzip) is_gzip = prefetch->is_gzip();
      end += got;
      return true;
    }
    const int n = gzread(file, buf.data() + end, static_cast<unsigned>(kChunk));
    if (n < 0) {
      int errnum = 0;
      const char* msg = gzerror(file, &errnum);
      throw IoError(fmt::format("cannot read '{}': {}", display_name(path),
                                errnum == Z_ERRNO ? std::strerror(errno) : msg));
    }
    if (n == 0) {
      eof = true;
      // A truncated gzip stream reads as a short file: say so instead of parsing half a record.
      int errnum = 0;
      const char* msg = gzerror(file, &errnum);
      if (errnum != Z_OK && errnum != Z_STREAM_END) {
        throw IoError(fmt::format("cannot read '{}': {}", display_name(path), msg));
      }
      return false;
    }
    if (!is_gzip && end == 0 && pos == 0) is_gzip = gzdirect(file) == 0;
    end += static_cast<std::size_t>(n);
    return true;
  }

  // Finds the end of the record starting at `pos` (quote-aware). On success `len` is the record's
  // length without its line feed, `newlines` the line feeds inside quoted fields, `quoted` whether
  // the record contains a quote. Returns false at end of input.
  bool find_record(std::size_t& len, std::uint64_t& newlines, bool& quoted) {
    std::size_t scan = 0;
    bool in_quotes = false;
    newlines = 0;
    quoted = false;
    for (;;) {
      const char* base = buf.data() + pos;
      const char* p = base + scan;
      const char* e = buf.data() + end;
      while (p < e) {
        if (!in_quotes) {
          const char* nl = static_cast<const char*>(std::memchr(p, '\n', static_cast<std::size_t>(e - p)));
          const char* stop = nl != nullptr ? nl : e;
          const char* q = static_cast<const char*>(std::memchr(p, '"', static_cast<std::size_t>(stop - p)));
          if (q != nullptr) {
            quoted = in_quotes = true;
            p = q + 1;
            continue;
          }
          if (nl != nullptr) {
            len = static_cast<std::size_t>(nl - base);
            return true;
          }
          p = e;
        } else {
          const char* q = static_cast<const char*>(std::memchr(p, '"', static_cast<std::size_t>(e - p)));
          const char* stop = q != nullptr ? q : e;
          newlines += static_cast<std::uint64_t>(std::count(p, stop, '\n'));
          if (q != nullptr) {
            in_quotes = false;
            p = q + 1;
            continue;
          }
          p = e;
        }
      }
      scan = static_cast<std::size_t>(p - base);
      if (!refill()) {
        if (in_quotes) fail(next_line, "unterminated quoted field (a '\"' is never closed)");
        len = end - pos;
        return len > 0;
      }
    }
  }

  void split(const char* rec, std::size_t len, bool quoted) {
    fields.clear();
    const char* p = rec;
    const char* e = rec + len;
    if (!quoted) {
      // Fields are short (a few bytes): a plain byte loop beats one memchr call per field.
      const char delim = delimiter;
      const char* start = p;
      for (; p < e; ++p) {
        if (*p == delim) {
          fields.emplace_back(start, static_cast<std::size_t>(p - start));
          start = p + 1;
        }
      }
      fields.emplace_back(start, static_cast<std::size_t>(e - start));
      return;
    }
    scratch.clear();
    scratch.reserve(len);  // views into scratch must not move
    for (;;) {
      if (p < e && *p == '"') {
        const std::size_t start = scratch.size();
        ++p;
        for (;;) {
          const char* q = static_cast<const char*>(std::memchr(p, '"', static_cast<std::size_t>(e - p)));
          if (q == nullptr) fail(line, "unterminated quoted field");
          scratch.append(p, q);
          if (q + 1 < e && q[1] == '"') {
            scratch.push_back('"');
            p = q + 2;
            continue;
          }
          p = q + 1;
          break;
        }
        fields.emplace_back(scratch.data() + start, scratch.size() - start);
        if (p == e) return;
        if (*p != delimiter) {
          fail(line, fmt::format("field {}: text after a closing quote", fields.size()));
        }
        ++p;
        continue;
      }
      const char* d = static_cast<const char*>(std::memchr(p, delimiter, static_cast<std::size_t>(e - p)));
      const char* stop = d != nullptr ? d : e;
      if (std::memchr(p, '"', static_cast<std::size_t>(stop - p)) != nullptr) {
        fail(line, fmt::format("field {}: a quote inside an unquoted field (quote the whole field "
                               "and double the inner quotes)", fields.size() + 1));
      }
      fields.emplace_back(p, static_cast<std::size_t>(stop - p));
      if (d == nullptr) return;
      p = d + 1;
    }
  }

  // Reads the next non-blank record into `fields`; false at end of input.
  bool read_record() {
    for (;;) {
      std::size_t len = 0;
      std::uint64_t newlines = 0;
      bool quoted = false;
      if (!find_record(len, newlines, quoted)) return false;
      line = next_line;
      next_line = line + 1 + newlines;
      const char* rec = buf.data() + pos;
      const bool has_lf = pos + len < end;  // the last record may lack a line feed
      pos += len + (has_lf ? 1 : 0);
      if (len > 0 && rec[len - 1] == '\r') --len;
      if (len == 0) continue;  // blank line: carries no data
      if (line == 1 && len >= 3 && std::memcmp(rec, "\xEF\xBB\xBF", 3) == 0) {
        rec += 3;
        len -= 3;
      }
      if (!header_seen) {
        // Blank lines (or only blanks) before the header carry nothing: skip them, so that the
        // delimiter is detected from the header itself, wherever it starts.
        std::size_t k = 0;
        while (k < len && (rec[k] == ' ' || rec[k] == '\t')) ++k;
        if (k == len) continue;
        if (options.delimiter == 0) delimiter = detect(rec, len);
        header_seen = true;
      }
      split(rec, len, quoted);
      return true;
    }
  }

  static char detect(const char* rec, std::size_t len) {
    std::size_t comma = 0, semicolon = 0, tab = 0;
    bool in_quotes = false;
    for (std::size_t i = 0; i < len; ++i) {
      const char c = rec[i];
      if (c == '"') in_quotes = !in_quotes;
      if (in_quotes) continue;
      comma += c == ',';
      semicolon += c == ';';
      tab += c == '\t';
    }
    if (semicolon > comma && semicolon >= tab) return ';';
    if (tab > comma && tab > semicolon) return '\t';
    return ',';
  }
};

CsvReader::CsvReader(std::string path, CsvOptions options) : impl_(std::make_unique<Impl>()) {
  impl_->path = std::move(path);
  impl_->options = options;
  if (options.delimiter != 0) impl_->delimiter = options.delimiter;
  impl_->open();
  if (!impl_->read_record()) {
    throw InvalidData(fmt::format("{}: empty file: a header row is required",
                                  display_name(impl_->path)));
  }
  if (options.no_header) {
    // The first record is data: name the columns and hand the record out again from next().
    for (std::size_t i = 0; i < impl_->fields.size() || i < options.column_names.size(); ++i) {
      impl_->header.push_back(i < options.column_names.size() ? options.column_names[i]
                                                              : std::to_string(i + 1));
    }
    impl_->replay = true;
  } else {
    for (const auto f : impl_->fields) impl_->header.emplace_back(f);
  }
  for (const auto& h : impl_->header) impl_->header_key.push_back(to_lower(trim(h)));
  for (std::size_t i = 0; i < options.skip_rows; ++i) {
    if (impl_->replay) {  // the first skipped row is the one already read
      impl_->replay = false;
      continue;
    }
    if (!impl_->read_record()) break;
  }
}

CsvReader::~CsvReader() = default;
CsvReader::CsvReader(CsvReader&&) noexcept = default;
CsvReader& CsvReader::operator=(CsvReader&&) noexcept = default;

const std::vector<std::string>& CsvReader::header() const noexcept { return impl_->header; }

int CsvReader::column(std::string_view name, std::string_view hint) const {
  const std::string_view want = trim(name);
  for (std::size_t i = 0; i < impl_->header.size(); ++i) {
    if (trim(impl_->header[i]) == want) return static_cast<int>(i);
  }
  const std::string key = to_lower(want);
  std::vector<std::size_t> found;
  for (std::size_t i = 0; i < impl_->header_key.size(); ++i) {
    if (impl_->header_key[i] == key) found.push_back(i);
  }
  if (found.empty()) return -1;
  if (found.size() == 1) return static_cast<int>(found[0]);
  // `T` (a millisecond timer) beside `Time`... taking the first silently once scored a 4.3 s trial
  // as 4,267 s: refuse instead.
  std::vector<std::string> names;
  for (const auto i : found) names.push_back(fmt::format("'{}' (column {})", impl_->header[i], i + 1));
  throw InvalidData(fmt::format("{}:1: columns {} differ only in case and none is exactly '{}': "
                                "ambiguous{}{}", display_name(impl_->path),
                                fmt::join(names, " and "), want, hint.empty() ? "" : "; ", hint));
}

bool CsvReader::next() {
  if (impl_->replay) {
    impl_->replay = false;
    ++impl_->records;
    return true;
  }
  if (!impl_->read_record()) return false;
  ++impl_->records;
  if (impl_->options.require_header_width && impl_->fields.size() != impl_->header.size()) {
    impl_->fail(impl_->line, fmt::format("{} fields where the header has {}",
                                         impl_->fields.size(), impl_->header.size()));
  }
  return true;
}

const std::vector<std::string_view>& CsvReader::fields() const noexcept { return impl_->fields; }
std::string_view CsvReader::field(std::size_t i) const noexcept {
  return i < impl_->fields.size() ? impl_->fields[i] : std::string_view{};
}
std::uint64_t CsvReader::line() const noexcept { return impl_->line; }
std::uint64_t CsvReader::records() const noexcept { return impl_->records; }
std::uint64_t CsvReader::bytes_consumed() const noexcept {
  if (impl_->prefetch) return impl_->prefetch->offset();
  const auto off = gzoffset(impl_->file);
  return off < 0 ? 0 : static_cast<std::uint64_t>(off);
}
const std::string& CsvReader::path() const noexcept { return impl_->path; }
char CsvReader::delimiter() const noexcept { return impl_->delimiter; }
bool CsvReader::compressed() const noexcept { return impl_->is_gzip; }

std::vector<std::string> split_csv_line(std::string_view line, char delimiter) {
  std::vector<std::string> out;
  std::string cur;
  bool in_quotes = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (in_quotes) {
      if (c == '"' && i + 1 < line.size() && line[i + 1] == '"') {
        cur.push_back('"');
        ++i;
      } else if (c == '"') {
        in_quotes = false;
      } else {
        cur.push_back(c);
      }
    } else if (c == '"') {
      in_quotes = true;
    } else if (c == delimiter) {
      out.push_back(std::move(cur));
      cur.clear();
    } else {
      cur.push_back(c);
    }
  }
  out.push_back(std::move(cur));
  return out;
}

std::string csv_escape(std::string_view field, char delimiter) {
  if (field.find_first_of(std::string{'"', '\n', '\r', delimiter}) == std::string_view::npos) {
    return std::string(field);
  }
  std::string out = "\"";
  for (const char c : field) {
    if (c == '"') out.push_back('"');
    out.push_back(c);
  }
  out.push_back('"');
  return out;
}

}  // namespace feint::io
