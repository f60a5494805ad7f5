#include "feint/io/output_folder.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <set>
#include <sstream>

#include "feint/error.hpp"
#include "feint/io/number.hpp"

namespace feint::io {

namespace fs = std::filesystem;

namespace detail {

std::vector<std::string> parse_manifest_files(const std::string& json) {
  const auto key = json.find("\"files\"");
  const auto open = key == std::string::npos ? key : json.find('[', key);
  if (open == std::string::npos) throw InvalidData("no \"files\" list");
  std::vector<std::string> files;
  std::size_t i = open + 1;
  while (i < json.size()) {
    const char c = json[i];
    if (c == ']') return files;
    if (c == '"') {
      std::string s;
      ++i;
      for (; i < json.size() && json[i] != '"'; ++i) {
        if (json[i] == '\\' && i + 1 < json.size()) {
          ++i;
          switch (json[i]) {
            case 'n':
              s += '\n';
              break;
            case 't':
              s += '\t';
              break;
            case 'r':
              s += '\r';
              break;
            case 'b':
              s += '\b';
              break;
            case 'f':
              s += '\f';
              break;
            case 'u':
              throw InvalidData("\\u escapes are not expected in a file list");
            default:
              s += json[i];
          }
        } else {
          s += json[i];
        }
      }
      if (i >= json.size()) break;
      files.push_back(std::move(s));
    } else if (c != ',' && c != ' ' && c != '\n' && c != '\r' && c != '\t') {
      throw InvalidData(fmt::format("unexpected '{}' in the file list", c));
    }
    ++i;
  }
  throw InvalidData("unterminated \"files\" list");
}

}  // namespace detail

namespace {

// `inner` is `outer` or lies below it (both canonical).
bool is_within(const fs::path& inner, const fs::path& outer) {
  auto i = inner.begin(), o = outer.begin();
  for (; o != outer.end(); ++o, ++i) {
    if (i == inner.end() || *i != *o) return false;
  }
  return true;
}

fs::path canonical_of(const std::string& p) {
  std::error_code ec;
  fs::path c = fs::weakly_canonical(fs::absolute(p, ec), ec);
  return ec ? fs::absolute(p).lexically_normal() : c;
}

// Every entry below `dir`, relative, files and folders (folders with a trailing '/').
std::vector<std::string> entries_below(const fs::path& dir) {
  std::vector<std::string> out;
  std::error_code ec;
  for (auto it = fs::recursive_directory_iterator(dir, ec); !ec && it != fs::end(it);
       it.increment(ec)) {
    std::string rel = it->path().lexically_relative(dir).generic_string();
    if (it->is_directory(ec) && !it->is_symlink(ec)) rel += '/';
    out.push_back(std::move(rel));
  }
  if (ec) throw IoError(fmt::format("cannot list '{}': {}", dir.string(), ec.message()));
  std::sort(out.begin(), out.end());
  return out;
}

// The first few entries of a folder, for a message: "'logs/', 'questionnaire.csv' and 61 more".
std::string some_entries(const std::vector<std::string>& entries) {
  std::string out;
  const std::size_t shown = std::min<std::size_t>(entries.size(), 3);
  for (std::size_t i = 0; i < shown; ++i) out += fmt::format("{}'{}'", i == 0 ? "" : ", ", entries[i]);
  if (entries.size() > shown) out += fmt::format(" and {} more", entries.size() - shown);
  return out;
}

// Refuses (before any work) a folder holding anything an earlier run of the writer did not write,
// and a non-empty folder that a writer asking before replacing was not told to replace.
void check_replaceable(const fs::path& dir, const std::string& shown, const FolderWriter& w) {
  const auto entries = entries_below(dir);
  if (entries.empty()) return;
  if (w.ask_before_replacing && !w.replace) {
    throw UsageError(fmt::format(
        "output folder '{}' is not empty (it holds {}): {} writes a whole new folder and never "
        "mixes two runs; choose a new or empty folder, or give {} to replace the folder of an "
        "earlier {} whole",
        shown, some_entries(entries), w.command, w.replace_option, w.command));
  }
  const fs::path manifest = dir / w.manifest;
  std::set<std::string> ours;
  bool legacy = false;
  if (fs::exists(manifest)) {
    std::ifstream in(manifest, std::ios::binary);
    std::ostringstream ss;
    ss << in.rdbuf();
    try {
      for (auto& f : detail::parse_manifest_files(ss.str())) ours.insert(std::move(f));
    } catch (const InvalidData& e) {
      throw UsageError(
          fmt::format("output folder '{}': its {} is not feint's ({}); choose a new "
                      "or empty folder",
                      shown, w.manifest, e.what()));
    }
    ours.insert(w.manifest);
  } else {
    legacy = true;
  }
  const auto legacy_output = [&](const std::string& e) {
    return legacy && w.legacy_output != nullptr && w.legacy_output(e);
  };
  for (const auto& e : entries) {
    if (e.back() == '/') {
      // A folder is ours when everything in it is (checked entry by entry below).
      const bool holds_ours = std::any_of(ours.begin(), ours.end(), [&](const std::string& f) {
        return f.compare(0, e.size(), e) == 0;
      });
      if (holds_ours || legacy_output(e)) continue;
    } else if (legacy ? legacy_output(e) : ours.count(e) != 0) {
      continue;
    }
    throw UsageError(fmt::format(
        "output folder '{}' holds '{}', which {} did not write{}; feint replaces the "
        "whole folder and never deletes files it did not write: move it away, or choose a new or "
        "empty folder",
        shown, e, w.command, legacy ? fmt::format(" (the folder has no {})", w.manifest) : ""));
  }
}

}  // namespace

OutputFolder::OutputFolder(std::string target, const std::vector<std::string>& inputs,
                           FolderWriter writer)
    : target_(std::move(target)), writer_(std::move(writer)) {
  if (target_.empty() || target_ == "-") {
    throw UsageError(fmt::format("{}: {} writes a folder; name one (e.g. {} out)", writer_.option,
                                 writer_.command, writer_.option));
  }
  resolved_ = canonical_of(target_);
  for (const auto& in : inputs) {
    if (in.empty() || in == "-") continue;
    const fs::path c = canonical_of(in);
    std::error_code ec;
    const bool folder = fs::is_directory(c, ec);
    if (is_within(c, resolved_)) {
      throw UsageError(
          fmt::format("output folder '{}' {} the input '{}': feint never writes over "
                      "or mixes into its inputs; choose another folder",
                      target_, c == resolved_ ? "is" : "contains", in));
    }
    if (folder && is_within(resolved_, c)) {
      throw UsageError(
          fmt::format("output folder '{}' is inside the input folder '{}': a later "
                      "run would read the outputs as inputs; choose another folder",
                      target_, in));
    }
  }
  std::error_code ec;
  if (fs::exists(resolved_, ec)) {
    if (!fs::is_directory(resolved_, ec)) {
      throw UsageError(fmt::format("output '{}' exists and is not a folder", target_));
    }
    check_replaceable(resolved_, target_, writer_);
  }
  const fs::path parent = resolved_.parent_path();
  fs::create_directories(parent, ec);
  if (ec) {
    throw IoError(fmt::format("cannot create the folder '{}': {}", parent.string(), ec.message()));
  }
  std::string templ =
      (parent / ("." + resolved_.filename().string() + ".feint-staging-XXXXXX")).string();
  if (::mkdtemp(templ.data()) == nullptr) {
    throw IoError(
        fmt::format("cannot create a folder beside '{}': {}", target_, std::strerror(errno)));
  }
  staging_ = templ;
}

OutputFolder::~OutputFolder() {
  if (!committed_) {
    std::error_code ec;
    fs::remove_all(staging_, ec);
  }
}

std::string OutputFolder::path(std::string_view name) const {
  return (staging_ / fs::path(std::string(name))).string();
}

std::vector<std::string> OutputFolder::commit(std::string_view tool_version) {
  std::vector<std::string> files;
  for (auto& e : entries_below(staging_)) {
    if (e.back() != '/' && e != writer_.manifest) files.push_back(std::move(e));
  }
  std::string json = fmt::format(
      "{{\n  \"written_by\": {},\n  \"version\": {},\n  \"note\": \"{} "
      "replaces this folder as a whole and refuses a folder holding files not listed here\",\n  "
      "\"files\": [",
      json_quote(writer_.command), json_quote(tool_version), writer_.command);
  for (std::size_t i = 0; i < files.size(); ++i) {
    json += fmt::format("{}\n    {}", i == 0 ? "" : ",", json_quote(files[i]));
  }
  json += "\n  ]\n}\n";
  {
    std::ofstream m(staging_ / writer_.manifest, std::ios::binary);
    m << json;
    m.flush();
    if (!m) throw IoError(fmt::format("cannot write '{}' in '{}'", writer_.manifest, target_));
  }
  // mkdtemp makes a private (0700) folder; give it a new folder's usual permissions.
  const mode_t mask = ::umask(0);
  ::umask(mask);
  ::chmod(staging_.c_str(), 0777 & ~mask);

  std::error_code ec;
  if (!fs::exists(resolved_, ec)) {
    if (std::rename(staging_.c_str(), resolved_.c_str()) != 0) {
      throw IoError(fmt::format("cannot create '{}': {}", target_, std::strerror(errno)));
    }
    committed_ = true;
    return files;
  }
  // The folder may have changed since the constructor looked: look again before replacing it.
  check_replaceable(resolved_, target_, writer_);
  if (::renameat2(AT_FDCWD, staging_.c_str(), AT_FDCWD, resolved_.c_str(), RENAME_EXCHANGE) != 0) {
    // A filesystem without RENAME_EXCHANGE: two renames (a short window without the folder).
    const fs::path old = staging_.string() + "-old";
    if (std::rename(resolved_.c_str(), old.c_str()) != 0) {
      throw IoError(fmt::format("cannot replace '{}': {}", target_, std::strerror(errno)));
    }
    if (std::rename(staging_.c_str(), resolved_.c_str()) != 0) {
      const int err = errno;
      std::rename(old.c_str(), resolved_.c_str());
      throw IoError(fmt::format("cannot replace '{}': {}", target_, std::strerror(err)));
    }
    committed_ = true;
    fs::remove_all(old, ec);
    return files;
  }
  committed_ = true;
  fs::remove_all(staging_, ec);  // now the previous run's folder
  return files;
}

}  // namespace feint::io
