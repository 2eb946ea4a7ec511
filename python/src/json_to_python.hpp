#pragma once
// JSON (the run report, the settings) as Python's dicts, lists and numbers.
#include <pybind11/pybind11.h>

#include <nlohmann/json.hpp>

namespace hba::python {

pybind11::object toPython(const nlohmann::json& value);

}  // namespace hba::python
