#pragma once
// hba.optimize's keyword arguments as HbaSettings. The names are the YAML
// keys of `hba optimize --config` (docs/settings.md), a section's settings a
// dict (local={"voxel_size": 2.0}); they are read by the same code as a YAML
// file, so names, ranges and "did you mean" messages are the CLI's.
#include <pybind11/pybind11.h>

#include "hba/settings/settings.hpp"

namespace hba::python {

// HbaSettings() with the keywords applied and checked; `threads` sets
// HbaSettings::threads (the CLI's -j). Throws hba::Error.
HbaSettings settingsFromKwargs(const pybind11::kwargs& kwargs);

}  // namespace hba::python
