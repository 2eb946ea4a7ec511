#pragma once
// The flags of `hba optimize` that set settings, made from the setting table
// (hba/settings/setting_table.hpp): each declared flag becomes an option with
// the setting's help, default and range.
#include <CLI/CLI.hpp>
#include <optional>
#include <vector>

#include "hba/settings/setting_table.hpp"

namespace hba::cli {

class SettingFlags {
 public:
  // Adds an option for every setting with a flag, in a "Settings" group.
  // The object must outlive the parse (the options write into it).
  void addTo(CLI::App* command);
  // The values given on the command line, on top of `settings`
  // (shorthands first, so that --voxel-local beside --voxel wins).
  void applyTo(HbaSettings& settings) const;

 private:
  std::vector<std::optional<settings::SettingValue>> given_;  // by table index
};

}  // namespace hba::cli
