#include "feint/io/csv.hpp"

#include <unistd.h>
#include <zlib.h>

#include <algorithm>
#include <cerrno>
#include <cstring>

#include <fmt/format.h>

#include "feint/error.hpp"
#include "feint/io/number.hpp"

namespace feint::io {

namespace {

constexpr std::size_t kChunk = std::size_t{1} << 20;  // bytes asked of zlib per read

std::string display_name(const std::string& path) { return path == "-" ? "<stdin>" : path; }

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
  std::uint64_t records = 0;

  ~Impl() {
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
    gzbuffer(file, 1U << 18);
    buf.resize(2 * kChunk);
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
      for (;;) {
        const char* d = static_cast<const char*>(std::memchr(p, delimiter, static_cast<std::size_t>(e - p)));
        if (d == nullptr) {
          fields.emplace_back(p, static_cast<std::size_t>(e - p));
          return;
        }
        fields.emplace_back(p, static_cast<std::size_t>(d - p));
        p = d + 1;
      }
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
      if (line == 1 && options.delimiter == 0) delimiter = detect(rec, len);
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
  for (const auto f : impl_->fields) {
    impl_->header.emplace_back(f);
    impl_->header_key.push_back(to_lower(trim(f)));
  }
  for (std::size_t i = 0; i < options.skip_rows; ++i) {
    if (!impl_->read_record()) break;
  }
}

CsvReader::~CsvReader() = default;
CsvReader::CsvReader(CsvReader&&) noexcept = default;
CsvReader& CsvReader::operator=(CsvReader&&) noexcept = default;

const std::vector<std::string>& CsvReader::header() const noexcept { return impl_->header; }

int CsvReader::column(std::string_view name) const noexcept {
  const std::string key = to_lower(trim(name));
  for (std::size_t i = 0; i < impl_->header_key.size(); ++i) {
    if (impl_->header_key[i] == key) return static_cast<int>(i);
  }
  return -1;
}

bool CsvReader::next() {
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
