#include "settings_kwargs.hpp"

#include <nlohmann/json.hpp>

#include <cmath>
#include <limits>
#include <optional>
#include <string>

#include "hba/core/error.hpp"
#include "hba/settings/setting_table.hpp"
#include "hba/settings/settings_file.hpp"

namespace py = pybind11;

namespace hba::python {
namespace {

const char* const kSource = "hba.optimize";

// The setting a keyword names ("window", an alias such as "scan_voxel", or
// "local.voxel_size" inside a section's dict); null for an unknown name,
// which the settings reader refuses with a "did you mean".
const settings::Setting* settingNamed(const std::string& name) {
  for (const settings::Setting& s : settings::settingTable()) {
    if (s.key == name) return &s;
    for (const std::string& alias : s.aliases) {
      if (alias == name) return &s;
    }
  }
  return nullptr;
}

[[noreturn]] void refuse(const std::string& name, const std::string& problem) {
  const settings::Setting* setting = settingNamed(name);
  throw Error(std::string(kSource) + ": setting '" + name + "' " + problem +
              (setting ? "; it takes " + settings::rangeText(*setting) : std::string()));
}

std::string reprOf(const py::handle& value) { return py::repr(value); }

// A Python integer of any size (numpy's too) as a long long; none when it
// does not fit (2**70), which pybind's cast reports as a bare RuntimeError.
std::optional<long long> asLongLong(const py::handle& value) {
  const auto integer = py::reinterpret_steal<py::object>(PyNumber_Index(value.ptr()));
  if (!integer) throw py::error_already_set();
  int overflow = 0;
  const long long number = PyLong_AsLongLongAndOverflow(integer.ptr(), &overflow);
  if (overflow != 0) return std::nullopt;
  return number;
}

long long integerValue(const py::handle& value, const std::string& name) {
  const std::optional<long long> number = asLongLong(value);
  if (!number) refuse(name, "is " + reprOf(value) + ", out of range");
  return *number;
}

int threadCount(const py::handle& value) {
  std::optional<long long> number;
  if (!py::isinstance<py::bool_>(value) && PyIndex_Check(value.ptr())) number = asLongLong(value);
  // hba -j's limit.
  if (!number || *number < 0 || *number > kMostThreads) {
    throw Error(std::string(kSource) +
                ": threads must be an integer >= 0 (0 = as many as allowed) and at most " +
                std::to_string(kMostThreads) + " (as hba -j), got " + reprOf(value));
  }
  return static_cast<int>(*number);
}

// One keyword's value as JSON, which is YAML too: the settings reader takes it.
nlohmann::json settingValue(const py::handle& value, const std::string& name) {
  // bool before int: Python's bool is an int.
  if (py::isinstance<py::bool_>(value)) return value.cast<bool>();
  if (py::isinstance<py::dict>(value)) {
    nlohmann::json section = nlohmann::json::object();
    for (const auto& [key, entry] : py::reinterpret_borrow<py::dict>(value)) {
      const std::string leaf = py::str(key);
      section[leaf] = settingValue(entry, name + "." + leaf);
    }
    return section;
  }
  if (py::isinstance<py::str>(value)) {
    // YAML would read the text "10" as a number: a string is a name, for the
    // settings that take one.
    const settings::Setting* setting = settingNamed(name);
    if (setting && setting->type != settings::SettingType::Choice) {
      refuse(name, "is the string " + reprOf(value) + ", not a " +
                       (setting->type == settings::SettingType::Switch ? "bool" : "number"));
    }
    return value.cast<std::string>();
  }
  // Integers of any kind (numpy's too) stay integers, so window=10.0 is refused like in YAML.
  if (PyIndex_Check(value.ptr()) && !PyFloat_Check(value.ptr())) return integerValue(value, name);
  if (py::hasattr(value, "__float__")) {
    const double number = value.cast<double>();
    // JSON has no NaN or infinity: they would arrive as null.
    if (!std::isfinite(number)) refuse(name, "is " + reprOf(value) + ", not a finite number");
    return number;
  }
  throw Error(std::string(kSource) + ": setting '" + name + "' has a value of type " +
              std::string(py::str(value.get_type().attr("__name__"))) +
              "; settings take numbers, True/False, names or a dict of a section's settings");
}

}  // namespace

HbaSettings settingsFromKwargs(const py::kwargs& kwargs) {
  HbaSettings settings;
  nlohmann::json given = nlohmann::json::object();
  for (const auto& [key, value] : kwargs) {
    const std::string name = py::str(key);
    if (name == "threads") {
      settings.threads = threadCount(value);
      continue;
    }
    given[name] = settingValue(value, name);
  }
  settings::applySettingsYaml(given.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace), kSource,
                              settings);
  try {
    settings::checkSettings(settings);
  } catch (const Error& e) {
    throw Error(std::string(kSource) + ": " + e.what());
  }
  return settings;
}

}  // namespace hba::python
