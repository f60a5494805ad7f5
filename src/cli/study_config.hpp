// src/cli/study_config.hpp - the study's settings file (feint.toml), shared by `feint analyze`
// (top-level keys and [analyze]) and `feint collect` ([collect]).
#pragma once

#include <CLI/CLI.hpp>
#include <filesystem>
#include <string>

namespace feint::cli {

/// The settings file of a run: `given` (--config) when set, else STUDY/feint.toml when it exists,
/// else "" (no settings file).
std::string settings_file(const std::string& given, const std::filesystem::path& study);

/// Which keys of the settings file a command takes.
enum class SettingsSection {
  analyze,  ///< top-level keys and [analyze]; [collect] is skipped, any other section is an error
  collect,  ///< [collect] only; everything else belongs to feint analyze and is skipped
};

/// Applies the settings file `path` (TOML/INI, CLI11's parser) to every option of `cmd` that the
/// command line left unset: the command line wins. A key that is no option of `cmd` (without
/// dashes) or a value the option rejects is InvalidData naming the file and the key; an unreadable
/// file is IoError.
void apply_settings_file(CLI::App& cmd, const std::string& path, SettingsSection section);

}  // namespace feint::cli
