// The round trip `feint score` -> `feint table` works for every file score accepts.
// Logs are generated with varied (valid) spellings: delimiters, column order and case, extra
// columns, with and without condition and pad_speed columns, quoted ids with delimiters and
// quotes, iterations written `01`/`+1`/` 2 `, targets as words and numbers, exponents, CRLF, a BOM,
// blank lines before the header, a clock that does not start at 0.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "cli/cli_helpers.hpp"
#include "feint/io/number.hpp"

using feint::test::run_feint;
using feint::test::shell_quote;
using feint::test::TempDir;
using feint::test::write_text;

namespace {

struct Log {
  std::string text;
  std::string options;  // extra `feint score` options
  std::string what;     // for failure messages
};

// 0.25 -> "2.5e-01": an exponent form strtod reads.
std::string fmt_exp(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6e", v);
  return buf;
}

std::string cell(const std::string& v, char delim) {
  if (v.find(delim) == std::string::npos && v.find('"') == std::string::npos) return v;
  std::string q = "\"";
  for (const char c : v) {
    q += c;
    if (c == '"') q += '"';
  }
  return q + "\"";
}

Log make_log(std::mt19937_64& rng) {
  auto pick = [&](std::size_t n) { return static_cast<std::size_t>(rng() % n); };
  const char delim = std::vector<char>{',', ';', '\t'}[pick(3)];
  const bool condition = pick(2) == 0, pad_speed = pick(2) == 0, extra = pick(2) == 0;
  const bool crlf = pick(3) == 0, bom = pick(4) == 0, blank_first = pick(3) == 0;
  std::vector<std::string> cols = {"participant", "iteration", "target", "t", "pad"};
  if (condition) cols.push_back("condition");
  if (pad_speed) cols.push_back("pad_speed");
  if (extra) cols.push_back("note");
  std::shuffle(cols.begin(), cols.end(), rng);
  const std::vector<std::string> ids = {"P1", "p 2", "Doe, J", "a\"b", "J\xC3\xB6rg", "P;6"};
  const std::vector<std::string> conds = {"adaptive", "random"};
  const std::vector<std::vector<std::string>> iteration_texts = {{"1", "01", "+1", " 1 "},
                                                                 {"2", "02", " 2"}};
  const std::vector<std::string> targets = {"left", "right", "RIGHT", "0", "1", "0.25", "1e-1"};
  const double clock = pick(2) == 0 ? 0 : 1e6;
  std::string nl = crlf ? "\r\n" : "\n";

  std::string text = bom ? "\xEF\xBB\xBF" : "";
  if (blank_first) text += nl;
  for (std::size_t i = 0; i < cols.size(); ++i) {
    std::string name = cols[i];
    if (pick(3) == 0) std::transform(name.begin(), name.end(), name.begin(), ::toupper);
    text += (i ? std::string(1, delim) : "") + name;
  }
  text += nl;
  const std::size_t participants = 2 + pick(3);
  for (std::size_t p = 0; p < participants; ++p) {
    for (std::size_t c = 0; c < (condition ? conds.size() : 1); ++c) {
      for (std::size_t it = 0; it < 2; ++it) {
        const std::string target = targets[pick(targets.size())];
        const std::string iteration = iteration_texts[it][pick(iteration_texts[it].size())];
        const std::size_t samples = 2 + pick(6);
        double t = clock + static_cast<double>(pick(5));
        for (std::size_t s = 0; s < samples; ++s) {
          t += 0.01 + static_cast<double>(pick(100)) / 1000;
          const double pad = static_cast<double>(pick(1001)) / 1000;
          std::string pad_text = feint::io::format_double(pad);
          if (pick(5) == 0) pad_text = fmt_exp(pad);
          std::string row;
          for (std::size_t i = 0; i < cols.size(); ++i) {
            std::string v;
            const std::string& col = cols[i];
            if (col == "participant") v = ids[p];
            if (col == "condition") v = conds[c];
            if (col == "iteration") v = iteration;
            if (col == "target") v = target;
            if (col == "t") v = feint::io::format_double(t);
            if (col == "pad") v = pad_text;
            if (col == "pad_speed") v = "0.8";
            if (col == "note") v = "free text, with \"quotes\"";
            row += (i ? std::string(1, delim) : "") + cell(v, delim);
          }
          text += row + nl;
        }
      }
    }
  }
  Log log;
  log.text = text;
  if (!pad_speed) log.options = pick(2) == 0 ? " --pad-speed 0.8" : " --confusion-norm raw";
  log.what = std::string("delimiter '") + (delim == '\t' ? "tab" : std::string(1, delim)) +
             "', condition " + (condition ? "yes" : "no") + ", pad_speed " +
             (pad_speed ? "yes" : "no") + (crlf ? ", CRLF" : "") + (bom ? ", BOM" : "") +
             (blank_first ? ", blank first line" : "");
  return log;
}

}  // namespace

TEST(ScoreTableRoundTrip, EveryLogScoreAcceptsTabulates) {
  std::mt19937_64 rng(8);
  TempDir d;
  for (int i = 0; i < 24; ++i) {
    const Log log = make_log(rng);
    SCOPED_TRACE(log.what + "\n" + log.text);
    const auto in = (d.path() / ("log" + std::to_string(i) + ".csv")).string();
    const auto out = (d.path() / ("scores" + std::to_string(i) + ".csv")).string();
    write_text(in, log.text);
    const auto scored = run_feint("score " + shell_quote(in) + " -o " + shell_quote(out) + log.options);
    ASSERT_EQ(scored.exit_code, 0) << scored.err;
    const auto table = run_feint("table " + shell_quote(out) + " --format csv");
    ASSERT_EQ(table.exit_code, 0) << table.err;
    EXPECT_NE(table.out.find("\nerror,1,"), std::string::npos) << table.out;
    EXPECT_NE(table.out.find("\nerror,2,"), std::string::npos) << table.out;
    const auto described = run_feint("describe " + shell_quote(out) + " --column confusion");
    ASSERT_EQ(described.exit_code, 0) << described.err;
  }
}

