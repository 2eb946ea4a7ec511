// The setting table is the one declaration of every setting: these tests
// check that each entry is wired to its own field, that its range is
// enforced, and that the docs' table is the one the code makes.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <set>
#include <sstream>

#include "hba/core/error.hpp"
#include "hba/settings/setting_table.hpp"
#include "hba/settings/settings_file.hpp"

namespace hba::settings {
namespace {

// Another valid value than the default.
SettingValue otherValue(const Setting& s) {
  const SettingValue d = s.default_value;
  switch (s.type) {
    case SettingType::Switch:
      return !std::get<bool>(d);
    case SettingType::Choice:
      for (const std::string& name : s.choices) {
        if (name != std::get<std::string>(d)) return name;
      }
      break;
    case SettingType::Integer:
    case SettingType::Count: {
      const long long v = std::get<long long>(d);
      // Above a meaningful 0 (automatic) lies the range's own minimum.
      const long long up = v == 0 && !s.range.zero.empty() ? static_cast<long long>(s.range.min) : v + 1;
      return up <= s.range.max ? up : v - 1;
    }
    case SettingType::Real: {
      const double v = std::get<double>(d);
      const double up = v == 0.0 ? std::max(s.range.min, 0.01) * 2 : v * 1.25;
      return up < s.range.max ? up : (v + std::max(s.range.min, 0.0)) / 2;
    }
  }
  ADD_FAILURE() << s.key << " has no second value";
  return d;
}

// The JSON leaves, "local.voxel_size" -> value.
std::map<std::string, nlohmann::json> leaves(const nlohmann::json& json, const std::string& prefix = "") {
  std::map<std::string, nlohmann::json> out;
  for (const auto& [key, value] : json.items()) {
    if (value.is_object()) {
      for (auto& [k, v] : leaves(value, prefix + key + ".")) out[k] = v;
    } else {
      out[prefix + key] = value;
    }
  }
  return out;
}

TEST(SettingTable, NamesAreUnique) {
  std::set<std::string> names, flags;
  for (const Setting& s : settingTable()) {
    EXPECT_TRUE(names.insert(s.key).second) << s.key;
    for (const std::string& alias : s.aliases) EXPECT_TRUE(names.insert(alias).second) << alias;
    if (!s.flag.empty()) {
      EXPECT_TRUE(flags.insert(s.flag).second) << s.flag;
    }
    for (const std::string& old : s.old_flags) EXPECT_TRUE(flags.insert(old).second) << old;
    EXPECT_FALSE(s.help.empty()) << s.key;
    // A switch's flag turns it from its default, and says so.
    if (s.type == SettingType::Switch && !s.flag.empty()) {
      EXPECT_EQ(s.flag.rfind("--no-", 0) == 0, std::get<bool>(s.default_value)) << s.flag;
    }
    for (const std::string& target : s.sets)
      EXPECT_NO_THROW(settingByKey(target)) << s.key << " sets " << target;
  }
}

TEST(SettingTable, DefaultsAreInRangeAndAreWhatASettingsObjectHolds) {
  const HbaSettings defaults;
  EXPECT_NO_THROW(checkSettings(defaults));
  for (const Setting& s : settingTable()) {
    if (s.shorthand()) continue;
    EXPECT_NO_THROW(checkSettingValue(s, s.default_value)) << s.key;
    EXPECT_EQ(s.get(defaults), s.default_value) << s.key;
  }
}

// One home per default: a setting whose field lives in a module's struct
// has that struct's default, so that a module used on its own (a test, the
// Python bindings, another program) runs as the tool does. The top layer's
// BA differs from the windows' in its one documented setting only.
TEST(SettingTable, ModuleStructsHoldTheTablesDefaults) {
  HbaSettings modules;  // every module struct as it comes
  modules.local = ba::BaSettings{};
  modules.global = ba::BaSettings{};
  modules.refinement = ba::RefinementSettings{};
  modules.information = graph::InformationSettings{};
  modules.graph = graph::PoseGraphSettings{};
  modules.revisit = closure::RevisitSettings{};
  const std::set<std::string> top_layer_own = {"global.eigen_ratio"};
  for (const Setting& s : settingTable()) {
    if (s.shorthand()) continue;
    if (top_layer_own.count(s.key) > 0) {
      EXPECT_NE(s.get(modules), s.default_value) << s.key << ": the top layer's own default";
    } else {
      EXPECT_EQ(s.get(modules), s.default_value) << s.key << ": the table says " << valueText(s.default_value)
                                                 << ", the module's struct " << valueText(s.get(modules));
    }
  }
  // Copies the tool makes from the table (HbaSettings::localBa()) start as it.
  EXPECT_EQ(ba::MotionPriorSettings{}.point_sigma, graph::InformationSettings{}.point_sigma);
  EXPECT_EQ(ba::RefinementSettings{}.motion_prior.enabled, ba::MotionPriorSettings{}.enabled);
}

// Each entry writes its own field and no other: a new value for one setting
// changes exactly that setting in report.json, and reads back from YAML.
TEST(SettingTable, EachSettingWritesItsOwnField) {
  const auto before = leaves(settingsToJson(HbaSettings()));
  EXPECT_EQ(before.size(),
            static_cast<std::size_t>(std::count_if(settingTable().begin(), settingTable().end(),
                                                   [](const Setting& s) { return !s.shorthand(); })));
  for (const Setting& s : settingTable()) {
    if (s.shorthand()) continue;
    const SettingValue value = otherValue(s);
    ASSERT_NO_THROW(checkSettingValue(s, value)) << s.key << " = " << valueText(value);
    HbaSettings changed;
    s.set(changed, value);
    EXPECT_EQ(s.get(changed), value) << s.key;
    const auto after = leaves(settingsToJson(changed));
    for (const auto& [key, json] : after) {
      if (key == s.key) {
        EXPECT_NE(json, before.at(key)) << key;
      } else {
        EXPECT_EQ(json, before.at(key)) << "setting " << s.key << " also changed " << key;
      }
    }
    // The same through the file, under the key.
    const std::string leaf = s.key.substr(s.key.find('.') + 1);
    const std::string yaml =
        s.key.find('.') == std::string::npos
            ? s.key + ": " + valueText(value) + "\n"
            : s.key.substr(0, s.key.find('.')) + ":\n  " + leaf + ": " + valueText(value) + "\n";
    HbaSettings read;
    applySettingsYaml(yaml, "one.yaml", read);
    EXPECT_EQ(s.get(read), value) << yaml;
  }
}

// Every finite bound is enforced, by the file reader and by checkSettings,
// with a message that names the setting.
TEST(SettingTable, EveryBoundIsEnforced) {
  int bounds = 0;
  for (const Setting& s : settingTable()) {
    if (s.shorthand() || s.type == SettingType::Switch || s.type == SettingType::Choice) continue;
    const bool integral = s.type != SettingType::Real;
    std::vector<double> outside;
    if (std::isfinite(s.range.min)) outside.push_back(integral ? s.range.min - 1 : s.range.min - 1e-6);
    if (std::isfinite(s.range.max)) outside.push_back(integral ? s.range.max + 1 : s.range.max + 1e-6);
    if (s.range.min_open) outside.push_back(s.range.min);
    if (s.range.max_open) outside.push_back(s.range.max);
    for (double v : outside) {
      if (v == 0.0 && !s.range.zero.empty()) continue;  // 0 means something
      const SettingValue value = integral ? SettingValue(static_cast<long long>(v)) : SettingValue(v);
      HbaSettings settings;
      s.set(settings, value);
      try {
        checkSettings(settings);
        ADD_FAILURE() << s.key << " = " << v << " passed the check";
      } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("setting " + s.key + " must be"), std::string::npos) << e.what();
      }
      ++bounds;
    }
  }
  EXPECT_GT(bounds, 30);
  HbaSettings s;
  s.window = 10;
  s.stride = s.window;
  try {
    checkSettings(s);
    ADD_FAILURE() << "stride = window passed";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("stride must be below window"), std::string::npos) << e.what();
  }
}

TEST(SettingTable, ShorthandsSetEachOfTheirSettingsAndTheSpecificKeyWins) {
  HbaSettings s;
  applySettingsYaml("final_voxel: 0.5\nlocal:\n  final_voxel_size: 2\n", "both.yaml", s);
  EXPECT_EQ(s.local.final_voxel_size, 2.0);
  EXPECT_EQ(s.global.final_voxel_size, 0.5);
  applySettingsYaml("ba_iterations: 7\n", "one.yaml", s);
  EXPECT_EQ(s.local.max_iterations, 7);
  EXPECT_EQ(s.global.max_iterations, 7);
}

TEST(SettingTable, AChoiceTakesDashesAndNamesItsChoicesWhenWrong) {
  HbaSettings s;
  applySettingsYaml("top_down: direct-assign\nfactor_pairs: from-first\n", "dashes.yaml", s);
  EXPECT_EQ(s.top_down, TopDownMode::DirectAssign);
  EXPECT_EQ(s.factor_pairs, FactorPairs::FromFirst);
  try {
    applySettingsYaml("pairs: every\n", "bad.yaml", s);
    ADD_FAILURE() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("bad.yaml: setting pairs must be one of adjacent, all, from_first"),
              std::string::npos)
        << e.what();
  }
}

// docs/settings.md holds the table the code makes. HBA_UPDATE_DOCS=1
// rewrites it.
TEST(SettingTable, DocsTableIsTheCodes) {
  const std::string path = std::string(HBA_SOURCE_DIR) + "/docs/settings.md";
  std::ifstream in(path);
  ASSERT_TRUE(in) << path;
  std::stringstream text;
  text << in.rdbuf();
  const std::string doc = text.str();
  const std::string begin =
      "<!-- settings table: made by the code, HBA_UPDATE_DOCS=1 ctest -R SettingTable -->\n";
  const std::string end = "<!-- end of the settings table -->";
  const auto from = doc.find(begin);
  const auto to = doc.find(end);
  ASSERT_TRUE(from != std::string::npos && to != std::string::npos && from < to)
      << "markers missing in " << path;
  const std::string table = doc.substr(from + begin.size(), to - from - begin.size());
  const std::string expected = settingsMarkdown();
  if (table == expected) return;
  const char* update = std::getenv("HBA_UPDATE_DOCS");
  if (update != nullptr && std::string(update) == "1") {
    std::ofstream out(path);
    out << doc.substr(0, from + begin.size()) << expected << doc.substr(to);
    return;
  }
  ADD_FAILURE() << path << " is out of date; run HBA_UPDATE_DOCS=1 ctest -R SettingTable. It should hold:\n"
                << expected;
}

}  // namespace
}  // namespace hba::settings
