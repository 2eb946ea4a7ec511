#include "setting_flags.hpp"

#include <string>

#include "hba/core/enum_names.hpp"

namespace hba::cli {

using pyramid::Setting;
using pyramid::SettingType;
using pyramid::SettingValue;

namespace {

std::string describe(const Setting& setting) {
  const Setting& typed = pyramid::valueSetting(setting);
  std::string text = setting.help;
  // Which BA a sectioned setting belongs to (local.eigen_ratio: the windows').
  const auto dot = setting.key.find('.');
  if (dot != std::string::npos) text = setting.key.substr(0, dot) + " BA: " + text;
  if (typed.type == SettingType::Switch) {
    text = (std::get<bool>(typed.default_value) ? "Off: " : "On: ") + text;
  }
  if (!typed.range.zero.empty()) text += "; 0 = " + typed.range.zero;
  return text;
}

}  // namespace

void SettingFlags::addTo(CLI::App* command) {
  const std::vector<Setting>& table = pyramid::settingTable();
  given_.assign(table.size(), std::nullopt);
  CLI::App* group = command->add_option_group(
      "Settings", "Settings (also in a --config YAML file; docs/settings.md lists them all)");
  for (std::size_t i = 0; i < table.size(); ++i) {
    const Setting& setting = table[i];
    if (setting.flag.empty()) continue;
    std::optional<SettingValue>& slot = given_[i];
    const Setting& typed = pyramid::valueSetting(setting);
    const std::string help = describe(setting);
    std::string names = setting.flag;
    for (const std::string& old : setting.old_flags) names += "," + old;
    CLI::Option* option = nullptr;
    switch (typed.type) {
      case SettingType::Switch:
        // A switch's flag turns it from its default (--no-refine, --no-revisits: off).
        group->add_flag_callback(
            names, [&slot, on = !std::get<bool>(typed.default_value)] { slot = on; }, help);
        continue;
      case SettingType::Integer:
      case SettingType::Count:
        option = group->add_option_function<long long>(
            names, [&slot](const long long& v) { slot = v; }, help);
        break;
      case SettingType::Real:
        option = group->add_option_function<double>(
            names, [&slot](const double& v) { slot = v; }, help);
        break;
      case SettingType::Choice:
        option = group->add_option_function<std::string>(
            names, [&slot](const std::string& v) { slot = normalizedEnumName(v); }, help);
        option->check(CLI::IsMember(typed.choices, normalizedEnumName));
        break;
    }
    if (!setting.shorthand()) option->default_str(pyramid::valueText(setting.default_value));
  }
}

void SettingFlags::applyTo(pyramid::HbaSettings& settings) const {
  const std::vector<Setting>& table = pyramid::settingTable();
  for (const bool shorthands : {true, false}) {
    for (std::size_t i = 0; i < table.size(); ++i) {
      const Setting& setting = table[i];
      if (setting.shorthand() != shorthands || !given_[i]) continue;
      // The range is checked with the whole settings (checkSettings), which
      // names the setting.
      pyramid::applySetting(setting, *given_[i], settings);
    }
  }
}

}  // namespace hba::cli
