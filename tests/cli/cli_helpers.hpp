// tests/cli/cli_helpers.hpp - run the feint binary (FEINT_EXE) from end-to-end tests.
//
// Stable API for every tests/cli/*.cpp (include read-only):
//   RunResult r = run_feint("score in.csv -o out.csv");   // exit code, stdout, stderr
//   RunResult r = run_feint("score - -o -", "stdin text");  // with text fed to stdin
//   TempDir dir;  dir.path() / "x.csv";  write_text(p, s);  read_text(p);  shell_quote(s)
// Arguments are passed through /bin/sh, so quote paths with spaces via shell_quote().
#pragma once

#include <sys/wait.h>

#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <unistd.h>

namespace feint::test {

/// What one run of the binary produced.
struct RunResult {
  int exit_code = -1;  // the process exit status (0..255); -1 if it did not exit normally
  std::string out;     // everything written to stdout
  std::string err;     // everything written to stderr
};

/// Reads a whole file (binary); empty string if it cannot be opened.
inline std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

/// Writes (replaces) a whole file, creating parent directories.
inline void write_text(const std::filesystem::path& path, const std::string& text) {
  if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path());
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (!out) throw std::runtime_error("cannot write " + path.string());
  out << text;
}

/// Single-quotes a string for /bin/sh.
/// The standard output of a shell command (its exit status is not checked).
inline std::string shell_output(const std::string& command) {
  std::string out;
  FILE* p = popen(command.c_str(), "r");
  if (p == nullptr) return out;
  char buf[4096];
  for (std::size_t n; (n = fread(buf, 1, sizeof buf, p)) > 0;) out.append(buf, n);
  pclose(p);
  return out;
}

inline std::string shell_quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) {
    if (c == '\'')
      q += "'\\''";
    else
      q += c;
  }
  return q + "'";
}

/// A fresh, empty temporary directory removed (recursively) when the object dies.
class TempDir {
 public:
  TempDir() {
    static std::atomic<int> counter{0};
    const auto base = std::filesystem::temp_directory_path();
    for (int attempt = 0; attempt < 1000; ++attempt) {
      auto p = base / ("feint-test-" + std::to_string(::getpid()) + "-" +
                       std::to_string(counter.fetch_add(1)));
      std::error_code ec;
      if (std::filesystem::create_directory(p, ec)) {
        path_ = p;
        return;
      }
    }
    throw std::runtime_error("cannot create a temporary directory");
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  const std::filesystem::path& path() const { return path_; }
  std::filesystem::path operator/(const std::string& name) const { return path_ / name; }

 private:
  std::filesystem::path path_;
};

/// Runs `FEINT_EXE <args>` through /bin/sh and captures stdout, stderr and the exit code.
/// `stdin_text`, if given, is fed to the process's standard input (otherwise stdin is /dev/null).
inline RunResult run_feint(const std::string& args, const std::string* stdin_text = nullptr) {
  TempDir tmp;
  const auto out_path = tmp / "stdout";
  const auto err_path = tmp / "stderr";
  std::string in_redirect = "/dev/null";
  if (stdin_text != nullptr) {
    write_text(tmp / "stdin", *stdin_text);
    in_redirect = (tmp / "stdin").string();
  }
  const std::string cmd = shell_quote(FEINT_EXE) + " " + args + " <" + shell_quote(in_redirect) +
                          " >" + shell_quote(out_path.string()) + " 2>" +
                          shell_quote(err_path.string());
  const int status = std::system(cmd.c_str());
  RunResult r;
  if (status != -1 && WIFEXITED(status)) r.exit_code = WEXITSTATUS(status);
  r.out = read_text(out_path);
  r.err = read_text(err_path);
  return r;
}

/// Overload: feed `stdin_text` to the process's standard input.
inline RunResult run_feint(const std::string& args, const std::string& stdin_text) {
  return run_feint(args, &stdin_text);
}

}  // namespace feint::test
