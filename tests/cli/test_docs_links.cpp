// The user's documentation points only to files a clone has: README.md, docs/*.md and
// every `--help` name no file outside the repository (the specification in ../shared is not
// shipped), and every page they name exists. The README says where the binary is.
#include <gtest/gtest.h>

#include <filesystem>
#include <regex>
#include <set>
#include <string>
#include <vector>

#include "cli/cli_helpers.hpp"

namespace fs = std::filesystem;
using feint::test::read_text;
using feint::test::run_feint;

namespace {

const fs::path kRoot(FEINT_SOURCE_DIR);

// Every `name.md` mentioned in `text` (links and bare names).
std::set<std::string> md_names(const std::string& text) {
  std::set<std::string> out;
  const std::regex md(R"(([A-Za-z0-9_./-]+)\.md\b)");
  for (auto it = std::sregex_iterator(text.begin(), text.end(), md); it != std::sregex_iterator();
       ++it) {
    out.insert((*it)[1].str() + ".md");
  }
  return out;
}

// A page name resolves when it exists relative to the page's folder, the root, or docs/.
bool resolves(const std::string& name, const fs::path& page_dir) {
  for (const auto& base : {page_dir, kRoot, kRoot / "docs"}) {
    if (fs::exists(base / name)) return true;
  }
  return false;
}

std::vector<fs::path> user_pages() {
  std::vector<fs::path> pages{kRoot / "README.md"};
  for (const auto& e : fs::directory_iterator(kRoot / "docs")) {
    if (e.path().extension() == ".md") pages.push_back(e.path());
  }
  return pages;
}

}  // namespace

TEST(UserDocs, PagesNameOnlyFilesTheCloneHas) {
  for (const auto& page : user_pages()) {
    SCOPED_TRACE(page.string());
    const std::string text = read_text(page);
    ASSERT_FALSE(text.empty());
    EXPECT_EQ(text.find("shared/spec"), std::string::npos);
    EXPECT_EQ(text.find("spec/"), std::string::npos);
    for (const auto& name : md_names(text)) {
      EXPECT_TRUE(resolves(name, page.parent_path())) << name;
    }
  }
}

TEST(UserDocs, HelpNamesOnlyFilesTheCloneHas) {
  // Every command's --help (and the top-level one, "").
  for (const std::string cmd : {"", "score", "table", "describe", "likert", "analyze", "simulate",
                                "simulate selection", "simulate study", "plot", "anova", "power",
                                "power t-test", "power simulate", "model", "collect"}) {
    SCOPED_TRACE("feint " + cmd + " --help");
    const auto r = run_feint(cmd + " --help");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(r.out.find("shared/"), std::string::npos) << r.out;
    EXPECT_EQ(r.out.find("spec/"), std::string::npos) << r.out;
    for (const auto& name : md_names(r.out)) EXPECT_TRUE(resolves(name, kRoot)) << name;
  }
}

TEST(UserDocs, TheReadmeSaysWhereTheBinaryIsAndHowToPutItOnThePath) {
  const std::string readme = read_text(kRoot / "README.md");
  EXPECT_NE(readme.find("build/feint"), std::string::npos);
  EXPECT_NE(readme.find("PATH"), std::string::npos);
  EXPECT_NE(readme.find("cmake --install"), std::string::npos);
}
