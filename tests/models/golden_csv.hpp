// The committed R goldens of tests/golden/models: plain CSV (no quoting), read the same way by
// every model golden test.
#pragma once

#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "feint/models/mixed_model.hpp"

namespace feint::test {

inline const std::string kModelGoldenDir = std::string(FEINT_SOURCE_DIR) + "/tests/golden/models/";

/// Rows of fields split at commas; a line ending in ',' has an empty last field.
inline std::vector<std::vector<std::string>> read_csv(const std::string& path) {
  std::ifstream in(path);
  EXPECT_TRUE(in) << path;
  std::vector<std::vector<std::string>> rows;
  std::string line;
  while (std::getline(in, line)) {
    std::vector<std::string> f;
    std::stringstream ss(line);
    std::string cell;
    while (std::getline(ss, cell, ',')) f.push_back(cell);
    if (!line.empty() && line.back() == ',') f.emplace_back();
    rows.push_back(f);
  }
  return rows;
}

/// tests/golden/models/lmm_NAME.csv as the model's long data (participant, condition, iteration,
/// error).
inline models::LongData load_lmm(const std::string& name) {
  const auto rows = read_csv(kModelGoldenDir + "lmm_" + name + ".csv");
  std::map<std::string, std::size_t> col;
  for (std::size_t i = 0; i < rows[0].size(); ++i) col[rows[0][i]] = i;
  models::LongData d;
  for (std::size_t r = 1; r < rows.size(); ++r) {
    d.participant.push_back(rows[r][col.at("participant")]);
    d.group.push_back(rows[r][col.at("condition")]);
    d.time.push_back(std::stod(rows[r][col.at("iteration")]));
    d.y.push_back(std::stod(rows[r][col.at("error")]));
  }
  return d;
}

}  // namespace feint::test
