#pragma once
// Settings from YAML (the `hba optimize --config FILE` format), as JSON
// (report.json) and as a Markdown table (docs/settings.md). Every key, its
// range and its meaning come from the setting table (setting_table.hpp):
// unknown keys are an error with a "did you mean", so typos never pass
// silently; a key named like a flag (iterations, voxel_local) is the same
// setting as its YAML key, and giving both is an error.
#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "hba/settings/settings.hpp"

namespace hba::settings {

// Applies the keys present in `yaml_text` on top of `settings`. Throws
// hba::Error naming `source` (a file name, for messages) and the bad key.
void applySettingsYaml(const std::string& yaml_text, const std::string& source, HbaSettings& settings);
void applySettingsFile(const std::filesystem::path& path, HbaSettings& settings);

// Throws hba::Error if the settings are out of range (negative voxel, ...).
void checkSettings(const HbaSettings& settings);

nlohmann::json settingsToJson(const HbaSettings& settings);

// Every setting as a commented YAML file that applySettingsYaml reads back
// to the same settings (`hba optimize --print-config`).
std::string settingsToYaml(const HbaSettings& settings);

// Every setting as a Markdown table: key, flag, default, range, meaning.
std::string settingsMarkdown();

}  // namespace hba::settings
