// What a declared setting takes, as text and as a check: one wording for the
// command line, the YAML file, the docs and the errors.
#include <charconv>
#include <cmath>

#include "hba/core/error.hpp"
#include "hba/pyramid/setting_table.hpp"

namespace hba::pyramid {
namespace {

std::string numberText(double value) {
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  char digits[32];  // the shortest form that reads back the same
  return std::string(digits, std::to_chars(digits, digits + sizeof(digits), value).ptr);
}

std::string joined(const std::vector<std::string>& names) {
  std::string out;
  for (const std::string& name : names) out += (out.empty() ? "" : ", ") + name;
  return out;
}

std::string intervalText(const SettingRange& r) {
  const bool no_min = std::isinf(r.min);
  const bool no_max = std::isinf(r.max);
  if (no_min && no_max) return "any number";
  if (no_max) return (r.min_open ? "> " : ">= ") + numberText(r.min);
  if (no_min) return (r.max_open ? "< " : "<= ") + numberText(r.max);
  return std::string(r.min_open ? "(" : "[") + numberText(r.min) + ", " + numberText(r.max) +
         (r.max_open ? ")" : "]");
}

bool inInterval(const SettingRange& r, double v) {
  const bool above = r.min_open ? v > r.min : v >= r.min;
  const bool below = r.max_open ? v < r.max : v <= r.max;
  return above && below;
}

}  // namespace

const Setting& valueSetting(const Setting& setting) {
  return setting.shorthand() ? settingByKey(setting.sets.front()) : setting;
}

std::string rangeText(const Setting& setting) {
  const Setting& s = valueSetting(setting);
  switch (s.type) {
    case SettingType::Switch:
      return "true or false";
    case SettingType::Choice:
      return "one of " + joined(s.choices);
    default:
      break;
  }
  std::string text = intervalText(s.range);
  if (!s.range.zero.empty()) text = "0 (" + s.range.zero + ") or " + text;
  if (!s.below.empty()) text += ", below " + s.below;
  return text;
}

std::string valueText(const SettingValue& value) {
  if (const bool* b = std::get_if<bool>(&value)) return *b ? "true" : "false";
  if (const long long* i = std::get_if<long long>(&value)) return std::to_string(*i);
  if (const double* d = std::get_if<double>(&value)) return numberText(*d);
  return std::get<std::string>(value);
}

void checkSettingValue(const Setting& setting, const SettingValue& value) {
  const Setting& s = valueSetting(setting);
  const auto fail = [&] { throw Error("setting " + setting.key + " must be " + rangeText(setting)); };
  switch (s.type) {
    case SettingType::Switch:
      if (!std::holds_alternative<bool>(value)) fail();
      return;
    case SettingType::Choice: {
      const std::string* name = std::get_if<std::string>(&value);
      if (name == nullptr) fail();
      for (const std::string& choice : s.choices) {
        if (normalizedEnumName(*name) == choice) return;
      }
      fail();
      return;
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
      fail();
    if (s.type == SettingType::Count && *i < 0) fail();
  } else if (const double* d = std::get_if<double>(&value); d != nullptr && s.type == SettingType::Real) {
    number = *d;
  } else {
    fail();
  }
  if (!std::isfinite(number)) fail();
  if (number == 0.0 && !s.range.zero.empty()) return;
  if (!inInterval(s.range, number)) fail();
}

void applySetting(const Setting& setting, const SettingValue& value, HbaSettings& settings) {
  if (!setting.shorthand()) {
    setting.set(settings, value);
    return;
  }
  for (const std::string& key : setting.sets) settingByKey(key).set(settings, value);
}

}  // namespace hba::pyramid
