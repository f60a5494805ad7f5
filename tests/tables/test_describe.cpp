// `feint describe`'s table (report/describe.hpp): values of the file, accurate means, no rejection
// of what the loader reads, and numbers rounded for print only in text/Markdown/LaTeX.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "feint/io/number.hpp"
#include "feint/io/scores.hpp"
#include "feint/tables/describe.hpp"

namespace fs = std::filesystem;

namespace {

feint::io::NumericColumn column_of(const std::string& name, const std::string& csv) {
  const fs::path p = fs::temp_directory_path() /
                     ("feint-test-describe-" + std::to_string(::getpid()) + "-" + name);
  std::ofstream(p, std::ios::binary) << csv;
  auto c = feint::io::load_numeric_column(p.string(), "x");
  fs::remove(p);
  return c;
}

}  // namespace

TEST(Describe, FarApartScalesAndLongMantissasAreDescribedNotRejected) {
  const auto c = column_of("far.csv", "x\n1e-300\n1e300\n0.5\n1e-400\n"
                                       "0.12345678901234567890123456789012345678901234567890\n");
  const auto t = feint::tables::build_describe(c);
  ASSERT_EQ(t.descriptions.size(), 1u);
  const auto& d = t.descriptions[0];
  EXPECT_EQ(d.n, 5u);
  EXPECT_EQ(d.min, 0.0);  // 1e-400 reads as strtod reads it: 0
  EXPECT_EQ(d.max, 1e300);
  EXPECT_EQ(d.median, 0.12345678901234567890123456789012345678901234567890);
  EXPECT_DOUBLE_EQ(*d.mean, 1e300 / 5);
  // Its squared deviations overflow a double: not computable, with the reason, never Inf.
  EXPECT_FALSE(d.sd.has_value());
  EXPECT_FALSE(d.conf_low.has_value());
  EXPECT_NE(d.note.find("exceeds the largest double"), std::string::npos) << d.note;
  EXPECT_EQ(feint::tables::render_describe(t, feint::tables::OutputFormat::csv).find("Inf"),
            std::string::npos);
}

TEST(Describe, MinMaxAndMeanAreExactInEveryFormat) {
  const auto c = column_of("exact.csv", "x\n1e9\n-1e9\n1\n0.3\n");
  const auto t = feint::tables::build_describe(c);
  EXPECT_EQ(t.descriptions[0].mean, (1.0 + 0.3) / 4);
  const std::string csv = feint::tables::render_describe(t, feint::tables::OutputFormat::csv);
  EXPECT_NE(csv.find(",0.325,"), std::string::npos) << csv;
  EXPECT_NE(csv.find(",-1000000000,"), std::string::npos) << csv;
}

TEST(Describe, TextMarkdownAndLatexRoundForPrintCsvAndJsonDoNot) {
  const auto c = column_of("print.csv", "x\n0.1\n0.2\n0.3\n0.4\n1\n");
  const auto t = feint::tables::build_describe(c);
  const double sd = *t.descriptions[0].sd;  // 0.35355339059327379
  const std::string full = feint::io::format_double(sd);
  for (const auto f : {feint::tables::OutputFormat::text, feint::tables::OutputFormat::markdown,
                       feint::tables::OutputFormat::latex}) {
    const std::string out = feint::tables::render_describe(t, f);
    EXPECT_NE(out.find("0.3536"), std::string::npos) << out;
    EXPECT_EQ(out.find(full), std::string::npos) << out;
    EXPECT_NE(out.find("4 significant digits"), std::string::npos) << out;
  }
  for (const auto f : {feint::tables::OutputFormat::csv, feint::tables::OutputFormat::json}) {
    const std::string out = feint::tables::render_describe(t, f);
    EXPECT_NE(out.find(full), std::string::npos) << out;
  }
}

TEST(Describe, FormatForPrintIsRsSignif) {
  using feint::tables::format_for_print;
  EXPECT_EQ(format_for_print(1.0 / 3), "0.3333");
  EXPECT_EQ(format_for_print(0.3), "0.3");
  EXPECT_EQ(format_for_print(12345.6), "12350");
  EXPECT_EQ(format_for_print(-0.000123456), "-0.0001235");
  EXPECT_EQ(format_for_print(1.23456e-7), "1.235e-07");
  EXPECT_EQ(format_for_print(0.99996), "1");
  EXPECT_EQ(format_for_print(0), "0");
}
