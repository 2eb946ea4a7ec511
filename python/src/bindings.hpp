#pragma once
// The parts of the `hba` Python module, each registered by one function.
#include <pybind11/pybind11.h>

namespace hba::python {

void bindOptimize(pybind11::module_& m);  // optimize, Result
void bindIo(pybind11::module_& m);        // read_scan, read_poses, open_dataset, ...
void bindEval(pybind11::module_& m);      // ate, mme
void bindRender(pybind11::module_& m);    // write_report_page

}  // namespace hba::python
