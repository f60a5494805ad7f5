// The settings file of a study (see options.hpp).
#include <fmt/format.h>

#include <vector>

#include "feint/error.hpp"
#include "options.hpp"

namespace feint::cli {

std::string settings_file(const std::string& given, const std::filesystem::path& study) {
  if (!given.empty()) return given;
  if (std::filesystem::exists(study / "feint.toml")) return (study / "feint.toml").string();
  return "";
}

namespace {

// Whether `item` is a setting of the command reading `section`; a section that no command owns is
// InvalidData (reported by feint analyze, which owns the file's top level).
bool is_own(const CLI::ConfigItem& item, SettingsSection section, const std::string& path) {
  const auto& p = item.parents;
  if (section == SettingsSection::collect) return p.size() == 1 && p[0] == "collect";
  if (p.empty()) return true;
  if (p[0] == "collect") return false;  // feint collect's own
  if ((p.size() == 1 && p[0] == "analyze") || (p.size() == 2 && p[0] == "hypotheses")) return true;
  throw InvalidData(
      fmt::format("{}: section [{}] is not a feint analyze section", path, fmt::join(p, ".")));
}

}  // namespace

void apply_settings_file(CLI::App& cmd, const std::string& path, SettingsSection section) {
  std::vector<CLI::ConfigItem> items;
  try {
    items = CLI::ConfigTOML().from_file(path);
  } catch (const CLI::Error& e) {
    throw IoError(fmt::format("cannot read settings '{}': {}", path, e.what()));
  }
  const bool collect = section == SettingsSection::collect;
  const char* command = collect ? "collect" : "analyze";
  const bool hypotheses_given = !collect && cmd.get_option_no_throw("--hypothesis")->count() > 0;
  for (const auto& item : items) {
    if (!is_own(item, section, path)) continue;
    if (item.name == "++" || item.name == "--") continue;  // section markers of CLI11's parser
    const bool hypothesis = !collect && item.parents.size() == 2;  // [hypotheses.ID] KEY = VALUE
    CLI::Option* opt = cmd.get_option_no_throw(hypothesis ? "--hypothesis" : "--" + item.name);
    if (opt == nullptr || item.name == "config" || item.name == "help") {
      throw InvalidData(fmt::format(
          "{}: {}unknown setting '{}' (settings are the options of 'feint {} --help', without "
          "the dashes)",
          path, collect ? "[collect]: " : "", item.name, command));
    }
    if (hypothesis ? hypotheses_given : opt->count() > 0) continue;  // the command line wins
    try {
      if (!hypothesis) opt->add_result(item.inputs);
      else opt->add_result(fmt::format("{}:{}={}", item.parents[1], item.name, fmt::join(item.inputs, ",")));
      opt->run_callback();
    } catch (const CLI::Error& e) {
      throw InvalidData(fmt::format("{}: {}setting '{}': {}", path, collect ? "[collect] " : "",
                                    item.name, e.what()));
    }
  }
}

}  // namespace feint::cli
