// What a declared setting takes, as text and as a check: one wording for the
// command line, the YAML file, the docs and the errors.
#include <cmath>

#include "hba/core/enum_names.hpp"
#include "hba/core/error.hpp"
#include "hba/settings/setting_table.hpp"

namespace hba::settings {
namespace {

std::string joined(const std::vector<std::string>& names) {
  std::string out;
  for (const std::string& name : names) out += (out.empty() ? "" : ", ") + name;
  return out;
}

NumberKind kindOf(const Setting& s) {
  switch (s.type) {
    case SettingType::Integer:
      return NumberKind::Integer;
    case SettingType::Count:
      return NumberKind::Count;
    default:
      return NumberKind::Real;
  }
}

}  // namespace

std::string rangeText(const Setting& s) {
  switch (s.type) {
    case SettingType::Switch:
      return "true or false";
    case SettingType::Choice:
      return "one of " + joined(s.choices);
    default:
      break;
  }
  std::string text = rangeText(s.range);
  if (!s.below.empty()) text += ", below " + s.below;
  return text;
}

std::string valueText(const SettingValue& value) {
  if (const bool* b = std::get_if<bool>(&value)) return *b ? "true" : "false";
  if (const long long* i = std::get_if<long long>(&value)) return std::to_string(*i);
  if (const double* d = std::get_if<double>(&value)) return numberText(*d);
  return std::get<std::string>(value);
}

std::string settingProblem(const Setting& s, const SettingValue& value) {
  const std::string must = "must be " + rangeText(s);
  switch (s.type) {
    case SettingType::Switch:
      return std::holds_alternative<bool>(value) ? "" : must;
    case SettingType::Choice: {
      const std::string* name = std::get_if<std::string>(&value);
      if (name == nullptr) return must;
      for (const std::string& choice : s.choices) {
        if (normalizedEnumName(*name) == choice) return "";
      }
      return must;
    }
    case SettingType::Integer:
    case SettingType::Count:
    case SettingType::Real:
      break;
  }
  double number = 0.0;
  if (const long long* i = std::get_if<long long>(&value)) {
    number = static_cast<double>(*i);
    if (s.type == SettingType::Integer &&
        (*i < std::numeric_limits<int>::min() || *i > std::numeric_limits<int>::max()))
      return must;
    if (s.type == SettingType::Count && *i < 0) return must;
  } else if (const double* d = std::get_if<double>(&value); d != nullptr && s.type == SettingType::Real) {
    number = *d;
  } else {
    return must;
  }
  return inRange(s.range, number) ? "" : must;
}

void checkSettingValue(const Setting& setting, const SettingValue& value) {
  const std::string problem = settingProblem(setting, value);
  if (!problem.empty()) throw ValueError("setting " + setting.key + " " + problem);
}

ParsedSetting parseSettingNumber(const Setting& setting, const std::string& text) {
  ParsedSetting parsed;
  const NumberKind kind = kindOf(setting);
  parsed.problem = numberProblem(text, setting.range, kind, rangeText(setting));
  if (!parsed.problem.empty()) return parsed;
  const ParsedNumber number = parseNumber(text, setting.range, kind);
  if (kind == NumberKind::Real) {
    parsed.value = number.value;
  } else {
    parsed.value = number.whole;
  }
  return parsed;
}

void applySetting(const Setting& setting, const SettingValue& value, HbaSettings& settings) {
  if (!setting.shorthand()) {
    setting.set(settings, value);
    return;
  }
  for (const std::string& key : setting.sets) settingByKey(key).set(settings, value);
}

}  // namespace hba::settings
