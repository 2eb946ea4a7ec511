#include "hba/pyramid/settings_file.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <charconv>
#include <fstream>
#include <set>
#include <sstream>
#include <type_traits>

#include "hba/core/did_you_mean.hpp"
#include "hba/core/error.hpp"

namespace hba::pyramid {
namespace {

[[noreturn]] void bad(const std::string& source, const std::string& problem) {
  throw Error(source + ": " + problem);
}

template <typename T>
void read(const YAML::Node& node, const char* key, T& value, const std::string& source) {
  const YAML::Node child = node[key];
  if (!child) return;
  try {
    value = child.as<T>();
  } catch (const YAML::Exception&) {
    bad(source, std::string("'") + key + "' has a value of the wrong type");
  }
}

void rejectUnknownKeys(const YAML::Node& node, const std::set<std::string>& known,
                       const std::string& where, const std::string& source) {
  for (const auto& entry : node) {
    const std::string key = entry.first.as<std::string>();
    if (known.count(key)) continue;
    const std::vector<std::string> names(known.begin(), known.end());
    std::string valid;
    for (const std::string& name : names) valid += (valid.empty() ? "" : ", ") + where + name;
    bad(source, "unknown setting '" + where + key + "'" + didYouMean(key, names) + "; the settings here are " + valid);
  }
}

// `key`: adjacent | all | from_first (or the command line's from-first).
void readFactorPairs(const YAML::Node& root, const char* key, FactorPairs& pairs, const std::string& source) {
  std::string name;
  read(root, key, name, source);
  if (name.empty()) return;
  const auto parsed = factorPairsFromString(name);
  if (!parsed) bad(source, std::string(key) + " must be adjacent, all or from_first");
  pairs = *parsed;
}

// Keys named like the flags of `hba optimize` (--iterations -> iterations),
// so a setting has one name on the command line and in the file. Giving a
// setting under both names is an error: which one wins would be a guess.
void readFlagNamedKeys(const YAML::Node& root, HbaSettings& s, const std::string& source) {
  const auto both = [&](const char* flag_name, const char* key) {
    if (root[flag_name] && root[key]) {
      bad(source, std::string("'") + flag_name + "' and '" + key + "' are the same setting; give one");
    }
  };
  both("iterations", "outer_iterations");
  both("voxel_scans", "scan_window_voxel");
  both("pairs", "factor_pairs");
  read(root, "iterations", s.outer_iterations, source);
  double voxel = 0.0;
  read(root, "voxel", voxel, source);
  if (root["voxel"]) s.scan_window_voxel = s.local.planes.voxel_size = s.global.planes.voxel_size = voxel;
  read(root, "voxel_scans", s.scan_window_voxel, source);
  read(root, "voxel_local", s.local.planes.voxel_size, source);
  read(root, "voxel_global", s.global.planes.voxel_size, source);
  if (root["final_voxel"]) {
    read(root, "final_voxel", s.local.final_voxel_size, source);
    s.global.final_voxel_size = s.local.final_voxel_size;
  }
  read(root, "theta_local", s.local.planes.eigen_ratio, source);
  read(root, "theta_global", s.global.planes.eigen_ratio, source);
  if (root["reject"]) {
    read(root, "reject", s.local.reject_ratio, source);
    s.global.reject_ratio = s.local.reject_ratio;
  }
  if (root["ba_iterations"]) {
    read(root, "ba_iterations", s.local.max_iterations, source);
    s.global.max_iterations = s.local.max_iterations;
  }
  readFactorPairs(root, "pairs", s.factor_pairs, source);
}

void readBa(const YAML::Node& node, const std::string& name, ba::BaSettings& ba,
            const std::string& source) {
  if (!node) return;
  if (!node.IsMap()) bad(source, "'" + name + "' must be a map of settings");
  rejectUnknownKeys(node,
                    {"voxel_size", "final_voxel_size", "eigen_ratio", "max_depth", "min_points",
                     "max_iterations", "association_rounds", "reject_ratio", "trust_check"},
                    name + ".", source);
  read(node, "voxel_size", ba.planes.voxel_size, source);
  read(node, "final_voxel_size", ba.final_voxel_size, source);
  read(node, "eigen_ratio", ba.planes.eigen_ratio, source);
  read(node, "max_depth", ba.planes.max_depth, source);
  read(node, "min_points", ba.planes.min_points, source);
  read(node, "max_iterations", ba.max_iterations, source);
  read(node, "association_rounds", ba.association_rounds, source);
  read(node, "reject_ratio", ba.reject_ratio, source);
  read(node, "trust_check", ba.check_fixed_map, source);
}

nlohmann::json baToJson(const ba::BaSettings& ba) {
  return {{"voxel_size", ba.planes.voxel_size},     {"final_voxel_size", ba.final_voxel_size},
          {"eigen_ratio", ba.planes.eigen_ratio},
          {"max_depth", ba.planes.max_depth},       {"min_points", ba.planes.min_points},
          {"max_iterations", ba.max_iterations},    {"association_rounds", ba.association_rounds},
          {"reject_ratio", ba.reject_ratio},        {"trust_check", ba.check_fixed_map}};
}

void checkBa(const ba::BaSettings& ba, const std::string& name) {
  auto fail = [&](const std::string& what) { throw Error("setting " + name + "." + what); };
  if (!(ba.planes.voxel_size >= 0.01 && ba.planes.voxel_size <= 1000)) {
    fail("voxel_size must be in [0.01, 1000] m");
  }
  if (!(ba.final_voxel_size == 0 || (ba.final_voxel_size >= 0.01 && ba.final_voxel_size <= 1000))) {
    fail("final_voxel_size must be 0 (off) or in [0.01, 1000] m");
  }
  if (!(ba.planes.eigen_ratio > 0 && ba.planes.eigen_ratio < 1)) fail("eigen_ratio must be in (0, 1)");
  if (ba.planes.max_depth < 0 || ba.planes.max_depth > 8) fail("max_depth must be in [0, 8]");
  if (ba.planes.min_points < 3) fail("min_points must be >= 3");
  if (ba.max_iterations < 1) fail("max_iterations must be >= 1");
  if (ba.association_rounds < 1) fail("association_rounds must be >= 1");
  if (!(ba.reject_ratio >= 0 && ba.reject_ratio < 1)) fail("reject_ratio must be in [0, 1)");
}

}  // namespace

std::string toString(TopDownMode mode) {
  return mode == TopDownMode::PoseGraph ? "pose_graph" : "direct_assign";
}

std::string toString(FactorPairs pairs) {
  switch (pairs) {
    case FactorPairs::Adjacent: return "adjacent";
    case FactorPairs::AllPairs: return "all";
    case FactorPairs::FromFirst: return "from_first";
  }
  return "adjacent";
}

std::optional<TopDownMode> topDownModeFromString(std::string name) {
  std::replace(name.begin(), name.end(), '-', '_');
  if (name == "pose_graph") return TopDownMode::PoseGraph;
  if (name == "direct_assign") return TopDownMode::DirectAssign;
  return std::nullopt;
}

std::optional<FactorPairs> factorPairsFromString(std::string name) {
  std::replace(name.begin(), name.end(), '-', '_');
  if (name == "adjacent") return FactorPairs::Adjacent;
  if (name == "all") return FactorPairs::AllPairs;
  if (name == "from_first") return FactorPairs::FromFirst;
  return std::nullopt;
}

void applySettingsYaml(const std::string& yaml_text, const std::string& source,
                       HbaSettings& settings) {
  YAML::Node root;
  try {
    root = YAML::Load(yaml_text);
  } catch (const YAML::Exception& e) {
    bad(source, "not valid YAML (" + std::string(e.what()) + ")");
  }
  if (!root || root.IsNull()) return;  // an empty file changes nothing
  if (!root.IsMap()) bad(source, "expected a map of settings at the top level");
  try {
    rejectUnknownKeys(root,
                      {"window", "stride", "layers", "outer_iterations", "scan_voxel",
                       "keyframe_voxel", "keyframe_voxel_growth", "scan_window_voxel", "top_down", "factor_pairs", "point_sigma", "local",
                       "global", "refine", "refine_voxel", "refine_scan_voxel", "refine_max_points",
                       "refine_iterations", "refine_rounds", "refine_round_gain",
                       "refine_groups", "group_min_frames", "group_max_count", "group_voxel",
                       "motion_prior",
                       // the command line's names, for the settings that have a flag
                       "iterations", "voxel", "voxel_scans", "voxel_local", "voxel_global",
                       "final_voxel", "theta_local", "theta_global", "reject", "ba_iterations",
                       "pairs"},
                      "", source);
    readFlagNamedKeys(root, settings, source);
    read(root, "window", settings.window, source);
    read(root, "stride", settings.stride, source);
    read(root, "layers", settings.layers, source);
    read(root, "outer_iterations", settings.outer_iterations, source);
    read(root, "scan_voxel", settings.scan_voxel, source);
    read(root, "keyframe_voxel", settings.keyframe_voxel, source);
    read(root, "keyframe_voxel_growth", settings.keyframe_voxel_growth, source);
    read(root, "scan_window_voxel", settings.scan_window_voxel, source);
    read(root, "point_sigma", settings.information.point_sigma, source);
    read(root, "refine", settings.refine, source);
    read(root, "refine_voxel", settings.refinement.planes.voxel_size, source);
    read(root, "refine_scan_voxel", settings.refine_scan_voxel, source);
    read(root, "refine_max_points", settings.refine_max_points, source);
    read(root, "refine_iterations", settings.refinement.lm.max_iterations, source);
    read(root, "refine_rounds", settings.refinement.association_rounds, source);
    read(root, "refine_round_gain", settings.refinement.round_gain, source);
    read(root, "refine_groups", settings.refine_groups, source);
    read(root, "group_min_frames", settings.group_min_frames, source);
    read(root, "group_max_count", settings.group_max_count, source);
    read(root, "group_voxel", settings.group_voxel, source);
    bool motion_prior = settings.motionPrior();
    read(root, "motion_prior", motion_prior, source);
    settings.setMotionPrior(motion_prior);
    std::string mode;
    read(root, "top_down", mode, source);
    if (!mode.empty()) {
      const auto parsed = topDownModeFromString(mode);
      if (!parsed) bad(source, "top_down must be pose_graph or direct_assign");
      settings.top_down = *parsed;
    }
    readFactorPairs(root, "factor_pairs", settings.factor_pairs, source);
    readBa(root["local"], "local", settings.local, source);
    readBa(root["global"], "global", settings.global, source);
  } catch (const YAML::Exception& e) {
    bad(source, "cannot read settings (" + std::string(e.what()) + ")");
  }
}

void applySettingsFile(const std::filesystem::path& path, HbaSettings& settings) {
  std::ifstream in(path);
  if (!in) failAt(path, "cannot open the settings file");
  std::ostringstream text;
  text << in.rdbuf();
  applySettingsYaml(text.str(), path.string(), settings);
}

void checkSettings(const HbaSettings& s) {
  if (s.window < 2) throw Error("setting window must be >= 2");
  if (s.stride < 1 || s.stride >= s.window) throw Error("setting stride must be in [1, window - 1]");
  if (s.layers < 0) throw Error("setting layers must be >= 0 (0 = automatic)");
  if (s.outer_iterations < 1) throw Error("setting outer_iterations must be >= 1");
  // Voxels below 1 mm only blow up hash keys; 0 switches downsampling off.
  auto downsampling = [](double v) { return v == 0.0 || (v >= 1e-3 && v <= 100.0); };
  if (!downsampling(s.scan_voxel)) throw Error("setting scan_voxel must be 0 (off) or in [0.001, 100] m");
  if (!downsampling(s.keyframe_voxel)) {
    throw Error("setting keyframe_voxel must be 0 (off) or in [0.001, 100] m");
  }
  if (!(s.keyframe_voxel_growth >= 1.0 && s.keyframe_voxel_growth <= 10.0)) {
    throw Error("setting keyframe_voxel_growth must be in [1, 10]");
  }
  if (!(s.scan_window_voxel == 0.0 || (s.scan_window_voxel >= 0.01 && s.scan_window_voxel <= 100.0))) {
    throw Error("setting scan_window_voxel must be 0 (= local voxel_size) or in [0.01, 100] m");
  }
  if (!(s.information.point_sigma > 0)) throw Error("setting point_sigma must be > 0");
  if (!(s.refinement.planes.voxel_size >= 0.05 && s.refinement.planes.voxel_size <= 100.0)) {
    throw Error("setting refine_voxel must be in [0.05, 100] m");
  }
  if (!(s.refine_scan_voxel == 0.0 || (s.refine_scan_voxel >= 1e-3 && s.refine_scan_voxel <= 100.0))) {
    throw Error("setting refine_scan_voxel must be 0 (= scan_voxel) or in [0.001, 100] m");
  }
  if (s.refine_max_points < 1000) throw Error("setting refine_max_points must be >= 1000");
  if (s.refinement.lm.max_iterations < 0) throw Error("setting refine_iterations must be >= 0");
  if (s.refinement.association_rounds < 1) throw Error("setting refine_rounds must be >= 1");
  if (!(s.refinement.round_gain >= 0.0 && s.refinement.round_gain <= 1.0)) {
    throw Error("setting refine_round_gain must be in [0, 1]");
  }
  if (s.group_min_frames < 2) throw Error("setting group_min_frames must be >= 2");
  // The groups' BA is solved densely: (6 x groups)^2 doubles.
  if (s.group_max_count < 3 || s.group_max_count > 2000) {
    throw Error("setting group_max_count must be in [3, 2000]");
  }
  if (!(s.group_voxel == 0.0 || (s.group_voxel >= 1e-3 && s.group_voxel <= 100.0))) {
    throw Error("setting group_voxel must be 0 (no downsampling) or in [0.001, 100] m");
  }
  checkBa(s.local, "local");
  checkBa(s.global, "global");
}

nlohmann::json settingsToJson(const HbaSettings& s) {
  return {{"window", s.window},
          {"stride", s.stride},
          {"layers", s.layers},
          {"outer_iterations", s.outer_iterations},
          {"scan_voxel", s.scan_voxel},
          {"keyframe_voxel", s.keyframe_voxel},
          {"keyframe_voxel_growth", s.keyframe_voxel_growth},
          {"scan_window_voxel", s.scan_window_voxel},
          {"top_down", toString(s.top_down)},
          {"factor_pairs", toString(s.factor_pairs)},
          {"point_sigma", s.information.point_sigma},
          {"refine", s.refine},
          {"refine_voxel", s.refinement.planes.voxel_size},
          {"refine_scan_voxel", s.refine_scan_voxel},
          {"refine_max_points", s.refine_max_points},
          {"refine_iterations", s.refinement.lm.max_iterations},
          {"refine_rounds", s.refinement.association_rounds},
          {"refine_round_gain", s.refinement.round_gain},
          {"refine_groups", s.refine_groups},
          {"group_min_frames", s.group_min_frames},
          {"group_max_count", s.group_max_count},
          {"group_voxel", s.group_voxel},
          {"motion_prior", s.motionPrior()},
          {"local", baToJson(s.local)},
          {"global", baToJson(s.global)}};
}

namespace {

// "key: value  # comment" with the value in YAML's plain form.
template <typename T>
std::string yamlLine(const std::string& indent, const std::string& key, const T& value, const std::string& comment) {
  std::string text = indent + key + ": ";
  if constexpr (std::is_same_v<T, bool>) {
    text += value ? "true" : "false";
  } else if constexpr (std::is_arithmetic_v<T>) {
    char digits[32];  // the shortest form that reads back the same
    text.append(digits, std::to_chars(digits, digits + sizeof(digits), value).ptr);
  } else {
    text += value;
  }
  if (text.size() < 34) text.resize(34, ' ');
  return text + "  # " + comment + "\n";
}

std::string baYaml(const ba::BaSettings& ba, const char* which) {
  std::string out;
  out += yamlLine("  ", "voxel_size", ba.planes.voxel_size, "root voxel of the adaptive plane map, m (--voxel-" + std::string(which) + ")");
  out += yamlLine("  ", "final_voxel_size", ba.final_voxel_size, "coarse to fine down to this voxel, m; 0 = off (--final-voxel)");
  out += yamlLine("  ", "eigen_ratio", ba.planes.eigen_ratio, "plane test lambda_min / lambda_max (--theta-" + std::string(which) + ")");
  out += yamlLine("  ", "max_depth", ba.planes.max_depth, "octree levels below the root voxel");
  out += yamlLine("  ", "min_points", ba.planes.min_points, "fewest points of a plane");
  out += yamlLine("  ", "max_iterations", ba.max_iterations, "LM iterations per association (--ba-iterations)");
  out += yamlLine("  ", "association_rounds", ba.association_rounds, "associations at the final voxel");
  out += yamlLine("  ", "reject_ratio", ba.reject_ratio, "share of the worst planes dropped (--reject)");
  out += yamlLine("  ", "trust_check", ba.check_fixed_map, "windows that blur the map keep their input poses");
  return out;
}

}  // namespace

std::string settingsToYaml(const HbaSettings& s) {
  std::string out =
      "# hba optimize settings: every one, at its value (hba optimize --print-config).\n"
      "# Read back with --config FILE; flags given on the command line override the file.\n"
      "# A key named like a flag (window for --window, iterations for --iterations, ...) is\n"
      "# the same setting under the same name. docs/pyramid.md explains them.\n";
  out += yamlLine("", "window", s.window, "frames per local window, w (--window)");
  out += yamlLine("", "stride", s.stride, "frames between window starts, s < w (--stride)");
  out += yamlLine("", "layers", s.layers, "pyramid layers incl. layer 1; 0 = automatic (--layers)");
  out += yamlLine("", "iterations", s.outer_iterations, "bottom-up + top-down rounds at most (--iterations)");
  out += yamlLine("", "scan_voxel", s.scan_voxel, "downsampling of the input scans, m (--scan-voxel)");
  out += yamlLine("", "keyframe_voxel", s.keyframe_voxel, "downsampling of keyframes, m (--keyframe-voxel)");
  out += yamlLine("", "keyframe_voxel_growth", s.keyframe_voxel_growth, "keyframe voxel factor per layer up");
  out += yamlLine("", "voxel_scans", s.scan_window_voxel, "root voxel of the layer-1 windows, m; 0 = local (--voxel-scans)");
  out += yamlLine("", "top_down", toString(s.top_down), "pose_graph or direct_assign (--top-down)");
  out += yamlLine("", "pairs", toString(s.factor_pairs), "window pairs that become factors: adjacent, all, from_first (--pairs)");
  out += yamlLine("", "point_sigma", s.information.point_sigma, "point-to-plane noise for the pose-graph weights, m (--point-sigma)");
  out += yamlLine("", "motion_prior", s.motionPrior(), "hold neighbours weakly at their input relative pose (--no-motion-prior)");
  out += yamlLine("", "refine", s.refine, "the final sparse BA over every scan (--no-refine)");
  out += yamlLine("", "refine_voxel", s.refinement.planes.voxel_size, "its root voxel, m (--refine-voxel)");
  out += yamlLine("", "refine_scan_voxel", s.refine_scan_voxel, "scans held at this density for it, m; 0 = scan_voxel");
  out += yamlLine("", "refine_max_points", s.refine_max_points, "beyond this many points it runs in blocks");
  out += yamlLine("", "refine_iterations", s.refinement.lm.max_iterations, "LM iterations per association");
  out += yamlLine("", "refine_rounds", s.refinement.association_rounds, "associations at most");
  out += yamlLine("", "refine_round_gain", s.refinement.round_gain, "associate again while a round cuts the cost by this share");
  out += yamlLine("", "refine_groups", s.refine_groups, "beyond one block, then place rigid groups of frames as a whole");
  out += yamlLine("", "group_min_frames", s.group_min_frames, "frames per group at least");
  out += yamlLine("", "group_max_count", s.group_max_count, "groups at most (larger groups on longer sequences)");
  out += yamlLine("", "group_voxel", s.group_voxel, "groups' merged clouds downsampled to this, m");
  out += "local:  # the windows of layers 1 and up\n" + baYaml(s.local, "local");
  out += "global:  # the one BA of the top layer\n" + baYaml(s.global, "global");
  return out;
}

}  // namespace hba::pyramid
