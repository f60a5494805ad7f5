// A trial's samples stored as JSON in one CSV cell (jsPsych's mouse/slider tracking data), read
// into parallel time and pad vectors. See io::TraceOptions::samples_column.
#include <cmath>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include <fmt/format.h>

#include "feint/io/number.hpp"
#include "feint/io/trace.hpp"

namespace feint::io::detail {

namespace {

// Just enough of RFC 8259 to find two keys' numbers: a small recursive-descent reader that
// collects, for the objects it is asked about, the numeric value (or null = NaN) of each key.
class JsonCursor {
 public:
  explicit JsonCursor(std::string_view s) : s_(s) {}

  void ws() {
    while (i_ < s_.size() && (s_[i_] == ' ' || s_[i_] == '\t' || s_[i_] == '\n' || s_[i_] == '\r')) ++i_;
  }
  bool eat(char c) {
    ws();
    if (i_ < s_.size() && s_[i_] == c) {
      ++i_;
      return true;
    }
    return false;
  }
  char peek() {
    ws();
    return i_ < s_.size() ? s_[i_] : '\0';
  }
  bool at_end() {
    ws();
    return i_ == s_.size();
  }
  std::size_t pos() const { return i_; }

  // A string (escapes are kept undecoded except \" and \\; keys are plain names).
  bool string(std::string& out) {
    if (!eat('"')) return false;
    out.clear();
    while (i_ < s_.size()) {
      const char c = s_[i_++];
      if (c == '"') return true;
      if (c == '\\') {
        if (i_ >= s_.size()) return false;
        out.push_back(s_[i_++]);
        continue;
      }
      out.push_back(c);
    }
    return false;
  }

  // A number or null (NaN); false for anything else.
  bool number(double& out) {
    ws();
    if (s_.substr(i_, 4) == "null") {
      i_ += 4;
      out = std::numeric_limits<double>::quiet_NaN();
      return true;
    }
    const std::size_t n = decimal_prefix(s_.substr(i_));
    if (n == 0) return false;
    const auto v = parse_double(s_.substr(i_, n));
    if (!v) return false;
    out = *v;
    i_ += n;
    return true;
  }

  // Skips any value (depth-limited, so hostile input cannot exhaust the stack).
  bool skip(int depth = 0) {
    if (depth > 64) return false;
    const char c = peek();
    std::string scratch;
    double d = 0;
    if (c == '"') return string(scratch);
    if (c == '[' || c == '{') {
      const char close = c == '[' ? ']' : '}';
      ++i_;
      if (eat(close)) return true;
      for (;;) {
        if (c == '{' && !(string(scratch) && eat(':'))) return false;
        if (!skip(depth + 1)) return false;
        if (eat(close)) return true;
        if (!eat(',')) return false;
      }
    }
    for (const char* word : {"true", "false"}) {
      const std::string_view w(word);
      if (s_.substr(i_, w.size()) == w) {
        i_ += w.size();
        return true;
      }
    }
    return number(d);
  }

 private:
  std::string_view s_;
  std::size_t i_ = 0;
};

// The fields of sample `index` (1-based) up to its closing '}', its '{' already read: the numbers
// (or null = NaN) of t_key into t and pad_key into p; other keys are skipped. `key` is the
// caller's scratch, reused so that a sample costs no allocation.
bool parse_sample_fields(JsonCursor& j, std::size_t index, std::string_view t_key,
                         std::string_view pad_key, std::string& key, double& t, double& p,
                         std::string& error) {
  bool has_t = false, has_p = false;
  if (!j.eat('}')) {
    for (;;) {
      if (!j.string(key) || !j.eat(':')) {
        error = fmt::format("sample {}: malformed JSON at character {}", index, j.pos() + 1);
        return false;
      }
      if (key == t_key || key == pad_key) {
        double v = 0;
        if (!j.number(v)) {
          error = fmt::format("sample {}: \"{}\" is not a number", index, key);
          return false;
        }
        (key == t_key ? t : p) = v;
        (key == t_key ? has_t : has_p) = true;
      } else if (!j.skip()) {
        error = fmt::format("sample {}: malformed JSON at character {}", index, j.pos() + 1);
        return false;
      }
      if (j.eat('}')) break;
      if (!j.eat(',')) {
        error = fmt::format("sample {}: malformed JSON at character {}", index, j.pos() + 1);
        return false;
      }
    }
  }
  if (!has_t || !has_p) {
    error = fmt::format("sample {}: no \"{}\" key (each sample needs \"{}\" and \"{}\"; "
                        "--map t=KEY / pad=KEY name other keys)",
                        index, has_t ? pad_key : t_key, t_key, pad_key);
    return false;
  }
  return true;
}

// [{"t": 0, "pad": 0.5}, ...]: one object per sample.
bool parse_sample_objects(JsonCursor& j, std::string_view t_key, std::string_view pad_key,
                          std::vector<double>& times, std::vector<double>& pads,
                          std::string& error) {
  j.eat('[');
  if (j.eat(']')) return true;
  std::string key;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (;;) {
    if (!j.eat('{')) {
      error = fmt::format("sample {}: expected an object {{\"{}\": ..., \"{}\": ...}}",
                          times.size() + 1, t_key, pad_key);
      return false;
    }
    double t = nan, p = nan;
    if (!parse_sample_fields(j, times.size() + 1, t_key, pad_key, key, t, p, error)) return false;
    times.push_back(t);
    pads.push_back(p);
    if (j.eat(']')) return true;
    if (!j.eat(',')) {
      error = fmt::format("after sample {}: malformed JSON at character {}", times.size(),
                          j.pos() + 1);
      return false;
    }
  }
}

// The array of numbers (null = NaN) under `key`, appended to `out`.
bool parse_number_array(JsonCursor& j, const std::string& key, std::vector<double>& out,
                        std::string& error) {
  if (!j.eat('[')) {
    error = fmt::format("\"{}\" is not an array", key);
    return false;
  }
  if (j.eat(']')) return true;
  for (;;) {
    double v = 0;
    if (!j.number(v)) {
      error = fmt::format("\"{}\"[{}] is not a number", key, out.size());
      return false;
    }
    out.push_back(v);
    if (j.eat(']')) return true;
    if (!j.eat(',')) {
      error = fmt::format("malformed JSON at character {}", j.pos() + 1);
      return false;
    }
  }
}

// {"t": [...], "pad": [...]}: parallel arrays, which must be equally long.
bool parse_parallel_arrays(JsonCursor& j, std::string_view t_key, std::string_view pad_key,
                           std::vector<double>& times, std::vector<double>& pads,
                           std::string& error) {
  j.eat('{');
  std::string key;
  bool has_t = false, has_p = false;
  if (!j.eat('}')) {
    for (;;) {
      if (!j.string(key) || !j.eat(':')) {
        error = fmt::format("malformed JSON at character {}", j.pos() + 1);
        return false;
      }
      if (key == t_key || key == pad_key) {
        (key == t_key ? has_t : has_p) = true;
        if (!parse_number_array(j, key, key == t_key ? times : pads, error)) return false;
      } else if (!j.skip()) {
        error = fmt::format("malformed JSON at character {}", j.pos() + 1);
        return false;
      }
      if (j.eat('}')) break;
      if (!j.eat(',')) {
        error = fmt::format("malformed JSON at character {}", j.pos() + 1);
        return false;
      }
    }
  }
  if (!has_t || !has_p) {
    error = fmt::format("no \"{}\" array (expected {{\"{}\": [...], \"{}\": [...]}})",
                        has_t ? pad_key : t_key, t_key, pad_key);
    return false;
  }
  if (times.size() != pads.size()) {
    error = fmt::format("\"{}\" has {} values and \"{}\" has {}", t_key, times.size(), pad_key,
                        pads.size());
    return false;
  }
  return true;
}

}  // namespace

bool parse_json_samples(std::string_view cell, std::string_view t_key, std::string_view pad_key,
                        std::vector<double>& times, std::vector<double>& pads, std::string& error) {
  times.clear();
  pads.clear();
  JsonCursor j(cell);
  if (j.peek() == '[') {
    if (!parse_sample_objects(j, t_key, pad_key, times, pads, error)) return false;
  } else if (j.peek() == '{') {
    if (!parse_parallel_arrays(j, t_key, pad_key, times, pads, error)) return false;
  } else {
    error = fmt::format("expected a JSON array of samples [{{\"{}\": ..., \"{}\": ...}}, ...] or "
                        "parallel arrays {{\"{}\": [...], \"{}\": [...]}}",
                        t_key, pad_key, t_key, pad_key);
    return false;
  }
  if (!j.at_end()) {
    error = fmt::format("text after the JSON value at character {}", j.pos() + 1);
    return false;
  }
  return true;
}

}  // namespace feint::io::detail
