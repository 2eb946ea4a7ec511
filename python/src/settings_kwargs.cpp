#include "settings_kwargs.hpp"

#include <nlohmann/json.hpp>

#include <string>

#include "hba/core/error.hpp"
#include "hba/pyramid/settings_file.hpp"

namespace py = pybind11;

namespace hba::python {
namespace {

const char* const kSource = "hba.optimize";

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
  if (py::isinstance<py::str>(value)) return value.cast<std::string>();
  // Integers of any kind (numpy's too) stay integers, so window=10.0 is refused like in YAML.
  if (PyIndex_Check(value.ptr()) && !PyFloat_Check(value.ptr())) return value.cast<long long>();
  if (py::hasattr(value, "__float__")) return value.cast<double>();
  throw Error(std::string(kSource) + ": setting '" + name + "' has a value of type " +
              std::string(py::str(value.get_type().attr("__name__"))) +
              "; settings take numbers, True/False, names or a dict of a section's settings");
}

}  // namespace

pyramid::HbaSettings settingsFromKwargs(const py::kwargs& kwargs) {
  pyramid::HbaSettings settings;
  nlohmann::json given = nlohmann::json::object();
  for (const auto& [key, value] : kwargs) {
    const std::string name = py::str(key);
    if (name == "threads") {
      if (!PyIndex_Check(value.ptr()) || value.cast<long long>() < 0) {
        throw Error(std::string(kSource) + ": threads must be an integer >= 0 (0 = as many as allowed)");
      }
      settings.threads = value.cast<int>();
      continue;
    }
    given[name] = settingValue(value, name);
  }
  pyramid::applySettingsYaml(given.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace), kSource,
                             settings);
  try {
    pyramid::checkSettings(settings);
  } catch (const Error& e) {
    throw Error(std::string(kSource) + ": " + e.what());
  }
  return settings;
}

}  // namespace hba::python
