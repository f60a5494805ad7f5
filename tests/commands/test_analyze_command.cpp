// The command line as the study report shows it (commands::quoted_command_line): run from the
// report's folder, with no one's folder layout in it.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <unistd.h>

#include "feint/commands/analyze_command.hpp"

namespace fs = std::filesystem;
using feint::commands::quoted_command_line;

namespace {

struct Folders {
  fs::path root;
  Folders() {
    root = fs::temp_directory_path() / ("feint-test-cmdline-" + std::to_string(::getpid()));
    fs::create_directories(root / "lab" / "study");
    fs::create_directories(root / "papers");
  }
  ~Folders() {
    std::error_code ec;
    fs::remove_all(root, ec);
  }
};

}  // namespace

TEST(QuotedCommandLine, PathsAreRelativeToTheOutputFolderAndTheProgramByItsName) {
  Folders f;
  const std::string study = (f.root / "lab" / "study").string();
  const std::string out = (f.root / "papers" / "results").string();  // not there yet
  EXPECT_EQ(quoted_command_line({"/usr/local/bin/feint", "analyze", study, "-o", out, "--alpha",
                                 "0.01"},
                                out),
            "feint analyze ../../lab/study -o ../results --alpha 0.01");
  // --option=PATH, a path with a space (quoted), and the command's name never rewritten.
  fs::create_directories(f.root / "lab" / "my settings");
  const std::string config = (f.root / "lab" / "my settings").string();
  EXPECT_EQ(quoted_command_line({"feint", "analyze", "--config=" + config, study, "-o", out}, out),
            "feint analyze '--config=../../lab/my settings' ../../lab/study -o ../results");
}

TEST(QuotedCommandLine, APathSharingOnlyTheRootWithTheReportIsAPlaceholder) {
  Folders f;
  const std::string study = (f.root / "lab" / "study").string();
  const std::string out = "/feint-no-such-folder/out";
  EXPECT_EQ(quoted_command_line({"feint", "analyze", study, "-o", out}, out),
            "feint analyze PATH_TO/study -o ../out");
}

TEST(QuotedCommandLine, WithoutAnOutputFolderAbsolutePathsAreShownFromTheCurrentFolder) {
  const std::string here = fs::current_path().string();
  EXPECT_EQ(quoted_command_line({"./feint", "table", here + "/x.csv", "a b"}), "feint table x.csv 'a b'");
  EXPECT_EQ(quoted_command_line({}), "");
}
