// feint likert's Cronbach's alpha with missing answers: psych::alpha's default (pairwise
// covariances) unless --alpha-missing complete; the note says which ran. Values from
// tests/golden/alpha/alpha_missing.csv (psych::alpha, see make_alpha_missing_golden.R).
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "feint/tables/likert.hpp"
#include "stats/golden_csv.hpp"

using feint::tables::analyze_likert_file;
using feint::tables::LikertSettings;

namespace {

// The golden case as a wide questionnaire file (items i1..ik, NA -> empty answer).
std::string golden_case_as_csv(const std::string& name, double* pairwise, double* complete) {
  const feint::test::GoldenCsv golden(std::string(FEINT_SOURCE_DIR) +
                                      "/tests/golden/alpha/alpha_missing.csv");
  for (const auto& row : golden.rows()) {
    if (row.str("case") != name) continue;
    *pairwise = row.number("pairwise_raw_alpha");
    *complete = row.number("complete_raw_alpha");
    std::vector<std::vector<std::string>> items;
    std::istringstream in(row.str("items"));
    std::string item;
    while (std::getline(in, item, '|')) items.push_back(feint::test::split_commas(item, ';'));
    std::ostringstream csv;
    csv << "participant";
    for (std::size_t j = 0; j < items.size(); ++j) csv << ",i" << j + 1;
    csv << "\n";
    for (std::size_t r = 0; r < items[0].size(); ++r) {
      csv << "P" << r;
      for (const auto& it : items) csv << "," << (it[r] == "NA" ? "" : it[r]);
      csv << "\n";
    }
    const std::string path = (std::filesystem::temp_directory_path() /
                              ("feint-alpha-" + std::to_string(::getpid()) + ".csv"))
                                 .string();
    std::ofstream(path) << csv.str();
    return path;
  }
  ADD_FAILURE() << "no golden case " << name;
  return {};
}

std::string all_notes(const feint::tables::LikertAnalysis& a) {
  std::string s;
  for (const auto& n : a.notes) s += n + "\n";
  return s;
}

}  // namespace

TEST(LikertAlpha, MissingAnswersUsePsychsPairwiseDefaultOrCompleteCases) {
  double pairwise = 0, complete = 0;
  const std::string path = golden_case_as_csv("k3_n30_few_missing", &pairwise, &complete);
  ASSERT_FALSE(path.empty());
  LikertSettings s;
  s.composites.push_back(feint::tables::parse_composite("scale=i1,i2,i3"));
  auto a = analyze_likert_file(path, s);
  ASSERT_EQ(a.reliability.size(), 1u);
  ASSERT_TRUE(a.reliability[0].alpha.has_value()) << a.reliability[0].note;
  EXPECT_NEAR(*a.reliability[0].alpha, pairwise, 1e-10);
  EXPECT_NE(all_notes(a).find("pairwise covariances"), std::string::npos) << all_notes(a);

  s.alpha_missing = feint::stats::AlphaMissing::complete_cases;
  a = analyze_likert_file(path, s);
  ASSERT_TRUE(a.reliability[0].alpha.has_value()) << a.reliability[0].note;
  EXPECT_NEAR(*a.reliability[0].alpha, complete, 1e-10);
  EXPECT_EQ(a.reliability[0].n, 26u);
  EXPECT_NE(all_notes(a).find("on complete cases"), std::string::npos) << all_notes(a);
  EXPECT_NE(pairwise, complete);
  std::remove(path.c_str());
}
