// The settings of `hba optimize`, each declared once. To add one: an entry
// here and the code that uses it; the flag, YAML key, report.json, range
// check and docs/settings.md follow (regenerate the docs with
// HBA_UPDATE_DOCS=1 ctest -R SettingTable).
//
// One home per default: a setting whose field lives in a module's struct
// (ba::BaSettings, ba::RefinementSettings, the pose graph's, the
// revisits') takes its default from that struct, so a module used on its
// own runs as the tool does; the others' defaults are written here.
#include "hba/settings/setting_table.hpp"

#include "hba/core/enum_names.hpp"
#include "hba/core/error.hpp"

namespace hba::settings {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

template <typename T>
using FieldOf = std::function<T&(HbaSettings&)>;

// A setting stored in one field of HbaSettings. One accessor serves both
// directions: `get` casts constness away only to call it, and only reads.
template <typename T>
Setting field(std::string key, std::string flag, SettingType type, T default_value, SettingRange range,
              FieldOf<T> ref, std::string help) {
  Setting s;
  s.key = std::move(key);
  s.flag = std::move(flag);
  s.type = type;
  s.range = std::move(range);
  s.help = std::move(help);
  if constexpr (std::is_same_v<T, bool> || std::is_same_v<T, double>) {
    s.default_value = default_value;
    s.get = [ref](const HbaSettings& h) { return SettingValue(ref(const_cast<HbaSettings&>(h))); };
    s.set = [ref](HbaSettings& h, const SettingValue& v) { ref(h) = std::get<T>(v); };
  } else {
    // Integers travel as long long; the range check keeps them in T's range.
    s.default_value = static_cast<long long>(default_value);
    s.get = [ref](const HbaSettings& h) {
      return SettingValue(static_cast<long long>(ref(const_cast<HbaSettings&>(h))));
    };
    s.set = [ref](HbaSettings& h, const SettingValue& v) { ref(h) = static_cast<T>(std::get<long long>(v)); };
  }
  return s;
}

Setting integer(std::string key, std::string flag, int default_value, SettingRange range, FieldOf<int> ref,
                std::string help) {
  return field<int>(std::move(key), std::move(flag), SettingType::Integer, default_value, std::move(range),
                    std::move(ref), std::move(help));
}

Setting count(std::string key, std::string flag, std::size_t default_value, SettingRange range,
              FieldOf<std::size_t> ref, std::string help) {
  return field<std::size_t>(std::move(key), std::move(flag), SettingType::Count, default_value,
                            std::move(range), std::move(ref), std::move(help));
}

Setting real(std::string key, std::string flag, double default_value, SettingRange range, FieldOf<double> ref,
             std::string help) {
  return field<double>(std::move(key), std::move(flag), SettingType::Real, default_value, std::move(range),
                       std::move(ref), std::move(help));
}

Setting onOff(std::string key, std::string flag, bool default_value, FieldOf<bool> ref, std::string help) {
  return field<bool>(std::move(key), std::move(flag), SettingType::Switch, default_value, {}, std::move(ref),
                     std::move(help));
}

template <typename E>
Setting choice(std::string key, std::string flag, E default_value, FieldOf<E> ref, std::string help) {
  Setting s;
  s.key = std::move(key);
  s.flag = std::move(flag);
  s.type = SettingType::Choice;
  s.choices = enumNames<E>();
  s.default_value = toString(default_value);
  s.help = std::move(help);
  s.get = [ref](const HbaSettings& h) { return SettingValue(toString(ref(const_cast<HbaSettings&>(h)))); };
  s.set = [ref](HbaSettings& h, const SettingValue& v) { ref(h) = parseEnum<E>(std::get<std::string>(v)); };
  return s;
}

Setting withAliases(Setting s, std::vector<std::string> aliases, std::vector<std::string> old_flags = {}) {
  s.aliases = std::move(aliases);
  s.old_flags = std::move(old_flags);
  return s;
}

// A name that sets several settings at once.
Setting shorthand(std::string key, std::string flag, std::vector<std::string> sets, std::string help) {
  Setting s;
  s.key = std::move(key);
  s.flag = std::move(flag);
  s.sets = std::move(sets);
  s.help = std::move(help);
  return s;  // type, range and default: completeShorthands
}

SettingRange atLeast(double min) { return {min, kInf, false, false, ""}; }
SettingRange between(double min, double max) { return {min, max, false, false, ""}; }
SettingRange zeroOr(const std::string& zero, double min, double max) {
  return {min, max, false, false, zero};
}

// One of the plane BAs' settings in HbaSettings.
using BaSettingsOf = ba::BaSettings HbaSettings::*;

// The settings of one plane BA (the windows' or the top layer's), in the
// YAML map `section`, with the defaults in `d`; `which` names its flags
// (--voxel-local).
void addBaSettings(std::vector<Setting>& table, const std::string& section, const std::string& which,
                   const ba::BaSettings& d, BaSettingsOf member) {
  const auto ba = [member](HbaSettings& h) -> ba::BaSettings& { return h.*member; };
  const std::string k = section + ".";
  table.push_back(
      withAliases(real(
                      k + "voxel_size", "--voxel-" + which, d.planes.voxel_size, between(0.01, 1000),
                      [ba](HbaSettings& h) -> double& { return ba(h).planes.voxel_size; },
                      "root voxel of the adaptive plane map, m"),
                  {"voxel_" + which}));
  table.push_back(real(
      k + "final_voxel_size", "", d.final_voxel_size, zeroOr("off", 0.01, 1000),
      [ba](HbaSettings& h) -> double& { return ba(h).final_voxel_size; },
      "coarse to fine down to this voxel, m"));
  table.push_back(
      withAliases(real(
                      k + "eigen_ratio", "--theta-" + which, d.planes.eigen_ratio, {0.0, 1.0, true, true, ""},
                      [ba](HbaSettings& h) -> double& { return ba(h).planes.eigen_ratio; },
                      "plane test lambda_min / lambda_max"),
                  {"theta_" + which}));
  table.push_back(integer(
      k + "max_depth", "", d.planes.max_depth, between(0, 8),
      [ba](HbaSettings& h) -> int& { return ba(h).planes.max_depth; }, "octree levels below the root voxel"));
  table.push_back(integer(
      k + "min_points", "", d.planes.min_points, atLeast(3),
      [ba](HbaSettings& h) -> int& { return ba(h).planes.min_points; }, "fewest points of a plane"));
  table.push_back(integer(
      k + "max_iterations", "", d.max_iterations, atLeast(0),
      [ba](HbaSettings& h) -> int& { return ba(h).max_iterations; }, "LM iterations per association"));
  table.push_back(integer(
      k + "association_rounds", "", d.association_rounds, atLeast(1),
      [ba](HbaSettings& h) -> int& { return ba(h).association_rounds; }, "associations at the final voxel"));
  table.push_back(real(
      k + "reject_ratio", "", d.reject_ratio, {0.0, 1.0, false, true, ""},
      [ba](HbaSettings& h) -> double& { return ba(h).reject_ratio; }, "share of the worst planes dropped"));
  table.push_back(onOff(
      k + "trust_check", "", d.check_fixed_map,
      [ba](HbaSettings& h) -> bool& { return ba(h).check_fixed_map; },
      "windows that blur the map keep their input poses"));
  table.push_back(real(
      k + "significant_gain", "", d.significant_gain, zeroOr("off", 0.1, 1e6),
      [ba](HbaSettings& h) -> double& { return ba(h).significant_gain; },
      "windows gaining at most this many times fitting noise keep their start poses"));
}

// The top layer's BA: the windows' but for two settings.
ba::BaSettings topLayerDefaults() {
  ba::BaSettings top;
  // A looser plane test: it finds the large divergences of a whole sequence.
  top.planes.eigen_ratio = 0.1;
  // The top settles as the windows do (above layer 1 only: one global BA
  // of the scans, --layers 1, never settles; see windowSettings).
  return top;
}

const Setting& inTable(const std::vector<Setting>& table, const std::string& key) {
  for (const Setting& s : table) {
    if (s.key == key) return s;
  }
  throw Error("no setting '" + key + "'");
}

// The numbers both ranges take (0 only if both take it).
SettingRange common(const SettingRange& a, const SettingRange& b) {
  SettingRange r = a;
  if (b.min > r.min || (b.min == r.min && b.min_open)) {
    r.min = b.min;
    r.min_open = b.min_open;
  }
  if (b.max < r.max || (b.max == r.max && b.max_open)) {
    r.max = b.max;
    r.max_open = b.max_open;
  }
  if (b.zero.empty()) r.zero.clear();
  return r;
}

// A shorthand takes the first setting's type and default, and only what
// every setting it sets takes: --voxel is refused above voxel_scans' 100 m
// by its own name, not by another setting's later.
void completeShorthands(std::vector<Setting>& table) {
  for (Setting& s : table) {
    if (!s.shorthand()) continue;
    const Setting& first = inTable(table, s.sets.front());
    s.type = first.type;
    s.choices = first.choices;
    s.default_value = first.default_value;
    s.range = first.range;
    for (const std::string& key : s.sets) s.range = common(s.range, inTable(table, key).range);
  }
}

// Shorthands first: they are applied before the settings they set.
void addShorthands(std::vector<Setting>& t) {
  t.push_back(shorthand("voxel", "--voxel", {"local.voxel_size", "global.voxel_size", "voxel_scans"},
                        "root voxel V of every BA, m"));
  t.push_back(shorthand("final_voxel", "--final-voxel", {"local.final_voxel_size", "global.final_voxel_size"},
                        "coarse to fine: voxel of the last associations of every BA, m"));
  t.push_back(shorthand("reject", "--reject", {"local.reject_ratio", "global.reject_ratio"},
                        "share of the worst planes every BA drops"));
  t.push_back(shorthand("ba_iterations", "--ba-iterations", {"local.max_iterations", "global.max_iterations"},
                        "LM iterations per association of every BA"));
}

// The pyramid's shape and its outer rounds.
void addPyramidShape(std::vector<Setting>& t) {
  // Automatic windows (0) hold enough points to place their frames better
  // than the odometry (window_size.hpp): ten dense scans, more sparse ones.
  Setting window = integer(
      "window", "--window", 0, zeroOr("automatic", 2, kInf), [](HbaSettings& h) -> int& { return h.window; },
      "frames per local window, w; automatic: the scans of 150 000 points, at least 10");
  t.push_back(window);
  Setting stride = integer(
      "stride", "--stride", 0, zeroOr("half the window", 1, kInf),
      [](HbaSettings& h) -> int& { return h.stride; }, "frames between window starts, s < w");
  stride.below = "window";
  t.push_back(stride);
  t.push_back(integer(
      "layers", "--layers", 0, zeroOr("automatic", 1, kInf), [](HbaSettings& h) -> int& { return h.layers; },
      "pyramid layers incl. layer 1"));
  // Rounds stop before the limit when the poses settle (outer_rounds.hpp):
  // a round that moves no pose beyond both tolerances, or no less than the
  // round before. A round costs what the first did: past 100 the limit is
  // no limit.
  t.push_back(withAliases(integer(
                              "iterations", "--iterations", 1, between(1, 100),
                              [](HbaSettings& h) -> int& { return h.outer_iterations; },
                              "bottom-up + top-down rounds at most; fewer when the poses settle"),
                          {"outer_iterations"}));
  // Half the default point_sigma; 0.01 deg turns a point 50 m away by 9 mm.
  t.push_back(real(
      "settle_translation", "--settle-translation", 0.01, between(1e-6, 1),
      [](HbaSettings& h) -> double& { return h.settle_translation_m; },
      "a round that moves no pose further (and no more than settle_rotation) settles the poses, m"));
  t.push_back(real(
      "settle_rotation", "--settle-rotation", 0.01, between(1e-6, 10),
      [](HbaSettings& h) -> double& { return h.settle_rotation_deg; },
      "a round that turns no pose further (and no more than settle_translation) settles the poses, deg"));
}

// How dense the scans and keyframes are, and where the windows' plane maps start.
void addDensity(std::vector<Setting>& t) {
  // Downsampling, named apart from the plane maps' root voxels (--voxel-*).
  t.push_back(withAliases(real(
                              "downsample_scans", "--downsample-scans", 0.1, zeroOr("off", 1e-3, 100),
                              [](HbaSettings& h) -> double& { return h.scan_voxel; },
                              "voxel the input scans are downsampled to, m"),
                          {"scan_voxel"}, {"--scan-voxel"}));
  t.push_back(withAliases(real(
                              "downsample_keyframes", "--downsample-keyframes", 0.2, zeroOr("off", 1e-3, 100),
                              [](HbaSettings& h) -> double& { return h.keyframe_voxel; },
                              "voxel keyframes are downsampled to, m"),
                          {"keyframe_voxel"}, {"--keyframe-voxel"}));
  t.push_back(real(
      "keyframe_voxel_growth", "", 1.0, between(1, 10),
      [](HbaSettings& h) -> double& { return h.keyframe_voxel_growth; },
      "keyframe voxel factor per layer up"));
  t.push_back(withAliases(real(
                              "voxel_scans", "--voxel-scans", 2.0, zeroOr("as local.voxel_size", 0.01, 100),
                              [](HbaSettings& h) -> double& { return h.scan_window_voxel; },
                              "root voxel of the layer-1 (scan) windows, m"),
                          {"scan_window_voxel"}));
  t.push_back(onOff(
      "adapt_final_voxel", "--no-adapt-final-voxel", true,
      [](HbaSettings& h) -> bool& { return h.adapt_final_voxel; },
      "end the windows' association at a coarser voxel where a scan puts fewer than half a plane's "
      "points in one (ten-scan windows; 10 / w of that in windows of w)"));
}

// The top-down pose graph and the weights of its factors.
void addTopDown(std::vector<Setting>& t) {
  t.push_back(choice<TopDownMode>(
      "top_down", "--top-down", TopDownMode::PoseGraph,
      [](HbaSettings& h) -> TopDownMode& { return h.top_down; },
      "how the corrections come down: pose_graph (the paper) or direct_assign"));
  t.push_back(withAliases(choice<FactorPairs>(
                              "pairs", "--pairs", FactorPairs::Joint,
                              [](HbaSettings& h) -> FactorPairs& { return h.factor_pairs; },
                              "how a window becomes pose-graph factors: joint (one factor of its whole "
                              "shape), or pairs of its frames: adjacent (the paper), all, from_first"),
                          {"factor_pairs"}));
  t.push_back(real(
      "point_sigma", "--point-sigma", graph::InformationSettings{}.point_sigma, {0.0, kInf, true, false, ""},
      [](HbaSettings& h) -> double& { return h.information.point_sigma; },
      "point-to-plane noise for the pose-graph weights, m"));
  Setting prior = onOff(
      "motion_prior", "--no-motion-prior", ba::MotionPriorSettings{}.enabled,
      [](HbaSettings& h) -> bool& { return h.local.motion_prior.enabled; },
      "hold neighbours weakly at their input relative pose");
  // One switch for the prior of every BA.
  prior.set = [](HbaSettings& h, const SettingValue& v) { h.setMotionPrior(std::get<bool>(v)); };
  t.push_back(prior);
  t.push_back(integer(
      "graph_max_iterations", "", graph::PoseGraphSettings{}.max_iterations, atLeast(1),
      [](HbaSettings& h) -> int& { return h.graph.max_iterations; },
      "Levenberg-Marquardt iterations of the pose graph at most"));
  t.push_back(choice<graph::RobustLoss>(
      "graph_robust_loss", "--graph-robust-loss", graph::PoseGraphSettings{}.robust_loss,
      [](HbaSettings& h) -> graph::RobustLoss& { return h.graph.robust_loss; },
      "robust loss on the pose graph's window factors (a window that went wrong "
      "pulls less)"));
}

// The closure stage's revisits.
void addClosures(std::vector<Setting>& t) {
  t.push_back(onOff(
      "revisits", "--no-revisits", true, [](HbaSettings& h) -> bool& { return h.revisits; },
      "find places the poses come back to, verify them with the plane BA and close them"));
  t.push_back(real(
      "revisit_drift", "--revisit-drift", closure::RevisitSettings{}.drift, between(0, 1),
      [](HbaSettings& h) -> double& { return h.revisit.drift; },
      "how far the input may have drifted between two visits, share of the path driven"));
  t.push_back(real(
      "revisit_reach", "", closure::RevisitSettings{}.reach_m, between(0.5, 1000),
      [](HbaSettings& h) -> double& { return h.revisit.reach_m; },
      "frames this close (beyond drift) may see the same place, m"));
  t.push_back(real(
      "revisit_min_path", "", closure::RevisitSettings{}.min_separation_m, between(1, 1e6),
      [](HbaSettings& h) -> double& { return h.revisit.min_separation_m; },
      "less path than this between two frames is one pass, not a revisit, m"));
}

// The last stage: refinement, blocks, groups.
void addRefinement(std::vector<Setting>& t) {
  t.push_back(onOff(
      "refine", "--no-refine", true, [](HbaSettings& h) -> bool& { return h.refine; },
      "the final sparse BA over every scan"));
  t.push_back(real(
      "refine_voxel", "--refine-voxel", ba::RefinementSettings{}.planes.voxel_size, between(0.05, 100),
      [](HbaSettings& h) -> double& { return h.refinement.planes.voxel_size; },
      "the final sparse BA's root voxel, m"));
  t.push_back(real(
      "refine_scan_voxel", "", 0.2, zeroOr("as downsample_scans", 1e-3, 100),
      [](HbaSettings& h) -> double& { return h.refine_scan_voxel; }, "scans held at this density for it, m"));
  t.push_back(count(
      "refine_max_points", "", 20'000'000, atLeast(1000),
      [](HbaSettings& h) -> std::size_t& { return h.refine_max_points; },
      "beyond this many points it runs in blocks"));
  t.push_back(integer(
      "refine_iterations", "", ba::RefinementSettings{}.lm.max_iterations, atLeast(0),
      [](HbaSettings& h) -> int& { return h.refinement.lm.max_iterations; },
      "its LM iterations per association"));
  t.push_back(integer(
      "refine_rounds", "", ba::RefinementSettings{}.association_rounds, atLeast(1),
      [](HbaSettings& h) -> int& { return h.refinement.association_rounds; }, "its associations at most"));
  t.push_back(real(
      "refine_round_gain", "", ba::RefinementSettings{}.round_gain, between(0, 1),
      [](HbaSettings& h) -> double& { return h.refinement.round_gain; },
      "associate again while a round cuts the cost by this share"));
  t.push_back(real(
      "refine_step_gain", "", ba::RefinementSettings{}.step_gain, zeroOr("off", 0.01, 1e6),
      [](HbaSettings& h) -> double& { return h.refinement.step_gain; },
      "end a round's LM at a step gaining less than this many times fitting the noise (the blocks'; the "
      "groups' BA takes every step)"));
  t.push_back(onOff(
      "refine_groups", "", true, [](HbaSettings& h) -> bool& { return h.refine_groups; },
      "beyond one block, then place rigid groups of frames as a whole"));
  t.push_back(count(
      "group_min_frames", "", 10, atLeast(2),
      [](HbaSettings& h) -> std::size_t& { return h.group_min_frames; }, "frames per group at least"));
  // The groups' BA is solved densely: (6 x groups)^2 doubles.
  t.push_back(count(
      "group_max_count", "", 500, between(3, 2000),
      [](HbaSettings& h) -> std::size_t& { return h.group_max_count; },
      "groups at most (larger groups on longer sequences)"));
  t.push_back(real(
      "group_voxel", "", 0.4, zeroOr("no downsampling", 1e-3, 100),
      [](HbaSettings& h) -> double& { return h.group_voxel; },
      "groups' merged clouds downsampled to this, m"));
}

std::vector<Setting> makeTable() {
  std::vector<Setting> t;
  addShorthands(t);
  addPyramidShape(t);
  addDensity(t);
  addTopDown(t);
  addClosures(t);
  addRefinement(t);
  addBaSettings(t, "local", "local", ba::BaSettings{}, &HbaSettings::local);
  addBaSettings(t, "global", "global", topLayerDefaults(), &HbaSettings::global);
  completeShorthands(t);
  return t;
}

}  // namespace

const std::vector<Setting>& settingTable() {
  static const std::vector<Setting> table = makeTable();
  return table;
}

const std::vector<SettingSection>& settingSections() {
  static const std::vector<SettingSection> sections = {
      {"local", "the windows of layers 1 and up"},
      {"global", "the one BA of the top layer"},
  };
  return sections;
}

const Setting& settingByKey(const std::string& key) {
  for (const Setting& s : settingTable()) {
    if (s.key == key) return s;
  }
  throw Error("no setting '" + key + "'");
}

}  // namespace hba::settings
