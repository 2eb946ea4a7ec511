#include "setting_flags.hpp"

#include <string>

#include "hba/core/enum_names.hpp"

namespace hba::cli {

using settings::Setting;
using settings::SettingType;
using settings::SettingValue;

namespace {

std::string describe(const Setting& setting) {
  std::string text = setting.help;
  // Which BA a sectioned setting belongs to (local.eigen_ratio: the windows').
  const auto dot = setting.key.find('.');
  if (dot != std::string::npos) text = setting.key.substr(0, dot) + " BA: " + text;
  if (setting.type == SettingType::Switch) {
    text = (std::get<bool>(setting.default_value) ? "Off: " : "On: ") + text;
  }
  if (!setting.range.zero.empty()) text += "; 0 = " + setting.range.zero;
  return text;
}

// A number flag's value checked against the setting's own range, by the
// flag's name ("--window: must be >= 2, got -3"), and written back as the
// digits CLI11 converts ("1e3" -> "1000").
CLI::Validator numberOf(const Setting& setting) {
  return CLI::Validator(
      [&setting](std::string& text) -> std::string {
        const settings::ParsedSetting parsed = settings::parseSettingNumber(setting, text);
        if (parsed.problem.empty()) text = settings::valueText(parsed.value);
        return parsed.problem;
      },
      settings::rangeText(setting));
}

// One option under `name` writing into `slot`.
CLI::Option* addOption(CLI::App* group, const Setting& setting, const std::string& name,
                       std::optional<SettingValue>& slot, const std::string& help) {
  switch (setting.type) {
    case SettingType::Switch:
      // A switch's flag turns it from its default (--no-refine, --no-revisits: off).
      return group->add_flag_callback(
          name, [&slot, on = !std::get<bool>(setting.default_value)] { slot = on; }, help);
    case SettingType::Integer:
    case SettingType::Count: {
      const auto store = [&slot](const long long& v) { slot = v; };
      return group->add_option_function<long long>(name, store, help)->check(numberOf(setting));
    }
    case SettingType::Real: {
      const auto store = [&slot](const double& v) { slot = v; };
      return group->add_option_function<double>(name, store, help)->check(numberOf(setting));
    }
    case SettingType::Choice:
      return group
          ->add_option_function<std::string>(
              name, [&slot](const std::string& v) { slot = normalizedEnumName(v); }, help)
          ->check(CLI::IsMember(setting.choices, normalizedEnumName));
  }
  return nullptr;
}

}  // namespace

void SettingFlags::addTo(CLI::App* command) {
  const std::vector<Setting>& table = settings::settingTable();
  given_.assign(table.size(), std::nullopt);
  CLI::App* group = command->add_option_group(
      "Settings", "Settings (also in a --config YAML file; docs/settings.md lists them all)");
  for (std::size_t i = 0; i < table.size(); ++i) {
    const Setting& setting = table[i];
    if (setting.flag.empty()) continue;
    std::optional<SettingValue>& slot = given_[i];
    const std::string help = describe(setting);
    CLI::Option* option = addOption(group, setting, setting.flag, slot, help);
    if (setting.type != SettingType::Switch && !setting.shorthand())
      option->default_str(settings::valueText(setting.default_value));
    // Earlier names still read, listed apart, and an error names the one
    // typed (CLI11 names a hidden option "").
    for (const std::string& old : setting.old_flags)
      addOption(group, setting, old, slot, "old name of " + setting.flag)->group("Old names (still read)");
  }
}

void SettingFlags::applyTo(HbaSettings& settings) const {
  const std::vector<Setting>& table = settings::settingTable();
  for (const bool shorthands : {true, false}) {
    for (std::size_t i = 0; i < table.size(); ++i) {
      const Setting& setting = table[i];
      if (setting.shorthand() != shorthands || !given_[i]) continue;
      // Each value's range was checked by its flag; what settings hold
      // together (stride below window), by checkSettings.
      settings::applySetting(setting, *given_[i], settings);
    }
  }
}

}  // namespace hba::cli
