#pragma once
// Settings from YAML (the `hba optimize --config FILE` format) and as JSON
// (printed at start and stored in report.json).
//
// YAML keys (all optional; unknown keys are an error, so typos never pass
// silently, and get a "did you mean"). Every setting that has a flag may also
// be named like it (iterations, voxel, voxel_scans, voxel_local, voxel_global,
// final_voxel, theta_local, theta_global, reject, ba_iterations, pairs):
//   window, stride, layers, outer_iterations, scan_voxel, keyframe_voxel, keyframe_voxel_growth,
//   top_down: pose_graph | direct_assign, factor_pairs: adjacent | all | from_first,
//   scan_window_voxel, point_sigma,
//   local:  { voxel_size, final_voxel_size, eigen_ratio, max_depth, min_points, max_iterations,
//             association_rounds, reject_ratio }
//   global: { same keys as local }
#include <filesystem>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "hba/pyramid/settings.hpp"

namespace hba::pyramid {

// Names of the modes, as in YAML ("pose_graph", "from_first"); the parsers
// also take the command line's dashes ("pose-graph", "from-first"). They
// return nothing for an unknown name.
std::string toString(TopDownMode mode);
std::string toString(FactorPairs pairs);
std::optional<TopDownMode> topDownModeFromString(std::string name);
std::optional<FactorPairs> factorPairsFromString(std::string name);

// Applies the keys present in `yaml_text` on top of `settings`. Throws
// hba::Error naming `source` (a file name, for messages) and the bad key.
void applySettingsYaml(const std::string& yaml_text, const std::string& source,
                       HbaSettings& settings);
void applySettingsFile(const std::filesystem::path& path, HbaSettings& settings);

// Throws hba::Error if the settings are out of range (negative voxel, ...).
void checkSettings(const HbaSettings& settings);

nlohmann::json settingsToJson(const HbaSettings& settings);

// Every setting as a commented YAML file that applySettingsYaml reads back
// to the same settings (`hba optimize --print-config`).
std::string settingsToYaml(const HbaSettings& settings);

}  // namespace hba::pyramid
