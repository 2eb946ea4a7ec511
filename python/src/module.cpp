// The `hba` Python module: hierarchical LiDAR bundle adjustment on numpy
// arrays (docs/python.md).
#include <pybind11/pybind11.h>
#include <spdlog/spdlog.h>

#include <string>

#include "bindings.hpp"
#include "hba/core/error.hpp"

namespace py = pybind11;

namespace {

void setLogLevel(const std::string& name) {
  const spdlog::level::level_enum level = spdlog::level::from_str(name);
  // from_str answers "off" for a name it does not know.
  if (level == spdlog::level::off && name != "off") {
    throw hba::Error("log level '" + name + "': expected trace, debug, info, warn, error, critical or off");
  }
  spdlog::set_level(level);
}

}  // namespace

PYBIND11_MODULE(hba, m) {
  m.doc() = "Hierarchical LiDAR bundle adjustment (hba) on numpy arrays; see docs/python.md";
  m.attr("__version__") = HBA_MODULE_VERSION;
  // A subclass of ValueError: bad input (a setting, an array, a file) is what hba reports.
  py::register_exception<hba::Error>(m, "Error", PyExc_ValueError);
  m.def("set_log_level", &setLogLevel, py::arg("level"),
        "How much hba logs: trace, debug, info, warn (the module's default), error, critical, off.");
  // A library should not talk on every call: only warnings, unless asked.
  setLogLevel("warn");
  hba::python::bindOptimize(m);
  hba::python::bindIo(m);
  hba::python::bindEval(m);
  hba::python::bindRender(m);
}
