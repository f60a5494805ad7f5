#include <gtest/gtest.h>
#include <sys/stat.h>
#include <zlib.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>

#include "feint/error.hpp"
#include "feint/io/csv.hpp"
#include "feint/io/number.hpp"
#include "feint/io/output.hpp"

namespace fs = std::filesystem;
using feint::io::CsvOptions;
using feint::io::CsvReader;

namespace {

fs::path temp_file(const std::string& name, const std::string& content) {
  const fs::path dir = fs::temp_directory_path() / "feint-test-csv";
  fs::create_directories(dir);
  const fs::path p = dir / name;
  std::ofstream(p, std::ios::binary) << content;
  return p;
}

std::vector<std::vector<std::string>> read_all(const fs::path& p, CsvOptions opt = {}) {
  CsvReader r(p.string(), opt);
  std::vector<std::vector<std::string>> rows;
  while (r.next()) rows.emplace_back(r.fields().begin(), r.fields().end());
  return rows;
}

}  // namespace

TEST(CsvReader, ReadsHeaderAndRecords) {
  const auto p = temp_file("plain.csv", "a,b,c\n1,2,3\n4,5,6\n");
  CsvReader r(p.string());
  EXPECT_EQ(r.header(), (std::vector<std::string>{"a", "b", "c"}));
  ASSERT_TRUE(r.next());
  EXPECT_EQ(r.line(), 2u);
  EXPECT_EQ(r.field(2), "3");
  ASSERT_TRUE(r.next());
  EXPECT_EQ(r.line(), 3u);
  EXPECT_EQ(r.field(0), "4");
  EXPECT_FALSE(r.next());
  EXPECT_EQ(r.records(), 2u);
}

TEST(CsvReader, HandlesQuotesCrlfBomAndMissingFinalNewline) {
  const auto p = temp_file("quoted.csv",
                           "\xEF\xBB\xBFName,Text\r\n\"P,01\",\"say \"\"hi\"\"\"\r\n"
                           "P02,\"two\nlines\"\r\nP03,last");
  CsvReader r(p.string());
  EXPECT_EQ(r.header()[0], "Name");
  EXPECT_EQ(r.column("name"), 0);
  EXPECT_EQ(r.column(" TEXT "), 1);
  ASSERT_TRUE(r.next());
  EXPECT_EQ(r.field(0), "P,01");
  EXPECT_EQ(r.field(1), "say \"hi\"");
  ASSERT_TRUE(r.next());
  EXPECT_EQ(r.field(1), "two\nlines");
  EXPECT_EQ(r.line(), 3u);
  ASSERT_TRUE(r.next());
  EXPECT_EQ(r.line(), 5u);  // the quoted line break moved it down one line
  EXPECT_EQ(r.field(1), "last");
  EXPECT_FALSE(r.next());
}

TEST(CsvReader, DetectsSemicolonAndTab) {
  EXPECT_EQ(read_all(temp_file("semi.csv", "a;b\n1,5;2\n"))[0][0], "1,5");
  CsvReader tab(temp_file("tab.csv", "a\tb\n1\t2\n").string());
  EXPECT_EQ(tab.delimiter(), '\t');
  CsvOptions explicit_comma;
  explicit_comma.delimiter = ',';
  explicit_comma.require_header_width = false;
  EXPECT_EQ(read_all(temp_file("semi2.csv", "a;b\n1;2\n"), explicit_comma)[0].size(), 1u);
}

TEST(CsvReader, ReadsGzipTransparently) {
  const fs::path p = fs::temp_directory_path() / "feint-test-csv" / "z.csv.gz";
  fs::create_directories(p.parent_path());
  gzFile f = gzopen(p.c_str(), "wb");
  ASSERT_NE(f, nullptr);
  std::string content = "t,pad\n";
  for (int i = 0; i < 100000; ++i) content += std::to_string(i) + ",0.5\n";
  gzwrite(f, content.data(), static_cast<unsigned>(content.size()));
  gzclose(f);
  CsvReader r(p.string());
  std::size_t n = 0;
  while (r.next()) ++n;
  EXPECT_TRUE(r.compressed());
  EXPECT_EQ(n, 100000u);
  EXPECT_EQ(r.line(), 100001u);
}

TEST(CsvReader, RecordsLongerThanTheBufferSurvive) {
  std::string big(3'000'000, 'x');
  const auto rows = read_all(temp_file("big.csv", "a,b\n" + big + ",\"" + big + "\"\n1,2\n"));
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[0][0].size(), big.size());
  EXPECT_EQ(rows[0][1], big);
  EXPECT_EQ(rows[1][1], "2");
}

TEST(CsvReader, RejectsMalformedInputWithFileAndLine) {
  const auto expect_invalid = [](const std::string& name, const std::string& content,
                                 const std::string& fragment) {
    const auto p = temp_file(name, content);
    try {
      read_all(p);
      ADD_FAILURE() << "no error for " << name;
    } catch (const feint::InvalidData& e) {
      EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(p.string()), std::string::npos) << e.what();
      EXPECT_EQ(e.code(), feint::ExitCode::invalid_data);
    }
  };
  expect_invalid("width.csv", "a,b\n1,2\n1,2,3\n", ":3: 3 fields where the header has 2");
  expect_invalid("unterminated.csv", "a,b\n1,\"2\n", ":2: unterminated quoted field");
  expect_invalid("after.csv", "a,b\n\"1\"x,2\n", ":2: field 1: text after a closing quote");
  expect_invalid("stray.csv", "a,b\n1,2\"x\"\n3,4\n", ":2: field 2: a quote inside an unquoted field");
  expect_invalid("empty.csv", "", "empty file: a header row is required");
}

TEST(CsvReader, MissingFileIsAnIoError) {
  try {
    CsvReader r("/nonexistent/feint/x.csv");
    FAIL();
  } catch (const feint::IoError& e) {
    EXPECT_EQ(e.code(), feint::ExitCode::io);
    EXPECT_NE(std::string(e.what()).find("/nonexistent/feint/x.csv"), std::string::npos);
  }
}

TEST(Number, ParsesOnlyWhatTheContractAllows) {
  using feint::io::parse_double;
  EXPECT_EQ(parse_double("0.5"), 0.5);
  EXPECT_EQ(parse_double(" -1e-3 "), -1e-3);
  EXPECT_EQ(parse_double("+2"), 2.0);
  EXPECT_EQ(parse_double(".25"), 0.25);
  for (const char* bad : {"", " ", "nan", "NaN", "inf", "-inf", "1,5", "1,000", "0x10", "1.5x",
                          "1e999", "abc"}) {
    EXPECT_FALSE(parse_double(bad).has_value()) << bad;
  }
  EXPECT_EQ(feint::io::parse_integer("12"), 12);
  EXPECT_FALSE(feint::io::parse_integer("1.5").has_value());
}

TEST(Number, FormatsRoundTrip) {
  for (const double x : {0.1, 1.0 / 3.0, 1e-300, 123456789.125, -0.0, 5e-324}) {
    EXPECT_EQ(*feint::io::parse_double(feint::io::format_double(x)), x);
  }
  EXPECT_EQ(feint::io::format_double(0.5), "0.5");
  EXPECT_EQ(feint::io::format_double(std::nan("")), "");
}

TEST(AtomicOutput, NothingAppearsUntilCommit) {
  const fs::path dir = fs::temp_directory_path() / "feint-test-out";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path target = dir / "table.csv";
  {
    feint::io::AtomicOutput out(target.string());
    out.stream() << "half a table";
    EXPECT_FALSE(fs::exists(target));
  }  // destroyed without commit: as a failing run
  EXPECT_FALSE(fs::exists(target));
  EXPECT_TRUE(fs::is_empty(dir)) << "temporary file left behind";
  {
    feint::io::AtomicOutput out(target.string());
    out.stream() << "whole table\n";
    out.commit();
  }
  std::ifstream in(target);
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "whole table");
}

TEST(AtomicOutput, UnwritableDirectoryIsAnIoError) {
  EXPECT_THROW(feint::io::AtomicOutput("/nonexistent/feint/out.csv"), feint::IoError);
}

TEST(CsvReader, BackgroundReadingKeepsEveryRecordAcrossManyBlocks) {
  // Larger than several 1 MB read-ahead blocks; records straddle block boundaries.
  std::string content = "i,text\n";
  for (int i = 0; i < 200000; ++i) content += std::to_string(i) + ",row number " + std::to_string(i) + "\n";
  const auto p = temp_file("blocks.csv", content);
  CsvReader r(p.string());
  long expected = 0;
  while (r.next()) {
    ASSERT_EQ(r.field(0), std::to_string(expected));
    ++expected;
  }
  EXPECT_EQ(expected, 200000);
  EXPECT_EQ(r.bytes_consumed(), content.size());
  // A reader abandoned early (an error in the middle of a file) stops its thread cleanly.
  for (int k = 0; k < 20; ++k) {
    CsvReader early(p.string());
    ASSERT_TRUE(early.next());
  }
}

TEST(AtomicOutput, WritesDevicesAndFifosInPlaceInsteadOfReplacingThem) {
  const fs::path dir = fs::temp_directory_path() / "feint-test-out-fifo";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path fifo = dir / "pipe";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  std::string received;
  std::thread reader([&] {
    std::ifstream in(fifo);
    std::getline(in, received);
  });
  {
    feint::io::AtomicOutput out(fifo.string());
    out.stream() << "through the pipe\n";
    out.commit();
  }
  reader.join();
  EXPECT_EQ(received, "through the pipe");
  EXPECT_TRUE(fs::is_fifo(fifo)) << "the FIFO was replaced by a regular file";
  EXPECT_THROW(feint::io::AtomicOutput(dir.string()), feint::IoError);  // a folder
}

TEST(AtomicOutput, FollowsASymbolicLinkAndKeepsIt) {
  const fs::path dir = fs::temp_directory_path() / "feint-test-out-link";
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::ofstream(dir / "real.csv") << "old\n";
  fs::create_symlink("real.csv", dir / "link.csv");
  feint::io::AtomicOutput out((dir / "link.csv").string());
  out.stream() << "new\n";
  out.commit();
  EXPECT_TRUE(fs::is_symlink(dir / "link.csv"));
  std::ifstream in(dir / "real.csv");
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "new");
}

TEST(Json, QuotesStringsAndWritesNumbersOrNull) {
  EXPECT_EQ(feint::io::json_quote("a\"b\\c\nd\te\x01"), "\"a\\\"b\\\\c\\nd\\te\\u0001\"");
  EXPECT_EQ(feint::io::json_quote("≈ M"), "\"≈ M\"");
  EXPECT_EQ(feint::io::json_number(0.1), "0.1");
  EXPECT_EQ(feint::io::json_number(std::nan("")), "null");
  EXPECT_EQ(feint::io::json_number(HUGE_VAL), "null");
}

// A blank first line (or several, or a BOM then blank lines) must not turn off
// delimiter detection: blank lines before the header are skipped like blank lines anywhere.
TEST(CsvReader, BlankLinesBeforeTheHeaderKeepDelimiterDetection) {
  CsvReader semi(temp_file("blank_semi.csv", "\na;b\n1,5;2\n").string());
  EXPECT_EQ(semi.delimiter(), ';');
  EXPECT_EQ(semi.header().size(), 2u);
  ASSERT_TRUE(semi.next());
  EXPECT_EQ(semi.field(0), "1,5");
  EXPECT_EQ(semi.line(), 3u);
  CsvReader tab(temp_file("blank_tab.tsv", "\xEF\xBB\xBF\r\n \n\ta\tb\n1\t2\t3\n").string());
  EXPECT_EQ(tab.delimiter(), '\t');
  ASSERT_EQ(tab.header().size(), 3u);
  EXPECT_EQ(tab.header()[1], "a");
}

// A headerless (MATLAB) file, and column lookup that prefers the exact case.
TEST(CsvReader, NoHeaderNamesColumnsByPositionOrByTheGivenNames) {
  const auto p = temp_file("noheader.csv", "1,2,3\n4,5,6\n");
  CsvOptions opt;
  opt.no_header = true;
  CsvReader r(p.string(), opt);
  EXPECT_EQ(r.header(), (std::vector<std::string>{"1", "2", "3"}));
  EXPECT_EQ(r.column("2"), 1);
  ASSERT_TRUE(r.next());
  EXPECT_EQ(r.line(), 1u);  // the first row is data
  EXPECT_EQ(r.field(2), "3");
  ASSERT_TRUE(r.next());
  EXPECT_EQ(r.line(), 2u);
  EXPECT_EQ(r.field(0), "4");
  EXPECT_FALSE(r.next());
  EXPECT_EQ(r.records(), 2u);
  opt.column_names = {"participant", "t"};  // the rest keep their numbers
  CsvReader named(p.string(), opt);
  EXPECT_EQ(named.header(), (std::vector<std::string>{"participant", "t", "3"}));
  opt.skip_rows = 1;  // skipping starts with the first row
  EXPECT_EQ(read_all(p, opt), (std::vector<std::vector<std::string>>{{"4", "5", "6"}}));
}

TEST(CsvReader, ColumnPrefersExactCaseAndRefusesAmbiguity) {
  const auto p = temp_file("case.csv", "T,t,Pad,PAD,Error\n1,2,3,4,5\n");
  CsvReader r(p.string());
  EXPECT_EQ(r.column("t"), 1);
  EXPECT_EQ(r.column("T"), 0);
  EXPECT_EQ(r.column(" t "), 1);
  EXPECT_EQ(r.column("error"), 4);  // one case-insensitive match
  EXPECT_EQ(r.column("PAD"), 3);
  EXPECT_EQ(r.column("x"), -1);
  try {
    (void)r.column("pad", "use --map pad=COLUMN");
    FAIL();
  } catch (const feint::InvalidData& e) {
    EXPECT_NE(std::string(e.what()).find("case.csv:1: columns 'Pad' (column 3) and 'PAD' (column "
                                         "4) differ only in case and none is exactly 'pad': "
                                         "ambiguous; use --map pad=COLUMN"),
              std::string::npos) << e.what();
  }
}
