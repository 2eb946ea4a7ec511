#pragma once
// Every setting of `hba optimize`, declared once (src/settings/setting_table.cpp):
// its key, flag, default, range and help. The command line's options, the
// YAML reader, --print-config, report.json, the range checks and the table
// in docs/settings.md are all made from that list, so a new setting is one
// entry there plus the code that uses it.
#include <functional>
#include <string>
#include <variant>
#include <vector>

#include "hba/core/number_range.hpp"
#include "hba/settings/settings.hpp"

namespace hba::settings {

using SettingValue = std::variant<bool, long long, double, std::string>;

enum class SettingType {
  Switch,   // true or false; a flag "--no-x" turns it off
  Integer,  // int
  Count,    // std::size_t
  Real,     // double
  Choice,   // one of `choices`
};

// Numbers a setting takes: between min and max (either end open), and 0
// too when `zero` names what 0 means ("off", "automatic").
using SettingRange = NumberRange;

struct Setting {
  // YAML key, also the name in report.json. "local.voxel_size" is the key
  // voxel_size in the YAML map `local`.
  std::string key;
  // Other YAML keys for the same setting (the flag's name: iterations for
  // outer_iterations). Giving two names of one setting is an error.
  std::vector<std::string> aliases;
  // "--window"; a Switch's flag is "--no-x" and turns it off; "" = YAML only.
  std::string flag;
  // Earlier names of the flag, still accepted.
  std::vector<std::string> old_flags;
  std::string help;  // one line, with the unit
  SettingType type = SettingType::Real;
  SettingRange range;
  std::vector<std::string> choices;  // a Choice's names
  SettingValue default_value;
  std::function<SettingValue(const HbaSettings&)> get;
  std::function<void(HbaSettings&, const SettingValue&)> set;
  // Another setting's value that this one must stay below, if any
  // (stride < window).
  std::string below;
  // A shorthand sets these settings (keys) at once and has no value of its
  // own: it is read and applied before them, so the specific key wins. Its
  // type and default are the first one's, its range what all of them take.
  std::vector<std::string> sets;

  bool shorthand() const { return !sets.empty(); }
};

// In a stable order: the order of --print-config, report.json and the docs.
const std::vector<Setting>& settingTable();

// The setting with this key (not an alias); throws hba::Error if none.
const Setting& settingByKey(const std::string& key);

// The YAML maps that group settings ("local", "global"), with a line each.
struct SettingSection {
  std::string name;
  std::string help;
};
const std::vector<SettingSection>& settingSections();

// "[0.001, 100] m"-like text of what a setting takes: "0 (off) or [0.001, 100]",
// "one of pose_graph, direct_assign", "true or false".
std::string rangeText(const Setting& setting);
// The value as YAML's plain form: 0.1, 20000000, true, pose_graph.
std::string valueText(const SettingValue& value);
// "" if `value` is one `setting` takes, else "must be RANGE".
std::string settingProblem(const Setting& setting, const SettingValue& value);
// Throws hba::ValueError "setting KEY must be ..." when `value` is out of
// range or of the wrong kind.
void checkSettingValue(const Setting& setting, const SettingValue& value);
// A number setting's value written as text (a flag's value, a YAML scalar),
// checked against its range; or "must be RANGE, got TEXT (why)" in
// `problem` ("too large", "not a whole number", "not finite", ...).
struct ParsedSetting {
  SettingValue value;
  std::string problem;  // "" when `value` holds the value
};
ParsedSetting parseSettingNumber(const Setting& setting, const std::string& text);
// Sets `setting` (every setting a shorthand stands for) to `value`.
void applySetting(const Setting& setting, const SettingValue& value, HbaSettings& settings);

}  // namespace hba::settings
