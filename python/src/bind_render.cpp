// hba.write_report_page: the report page (the map in 3D in a browser, the
// input and optimized poses, the run's report) that `hba optimize` and
// `hba view` write, by the same library call.
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <filesystem>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "bindings.hpp"
#include "hba/core/error.hpp"
#include "hba/core/memory_budget.hpp"
#include "hba/render/report_page.hpp"
#include "numpy_convert.hpp"

namespace py = pybind11;
namespace fs = std::filesystem;

namespace hba::python {
namespace {

// A report dict (hba.Result.report, or report.json loaded) as JSON, through
// Python's own encoder: what it cannot encode raises there, naming the value.
nlohmann::json reportJson(const py::object& report) {
  if (report.is_none()) return nullptr;
  if (!py::isinstance<py::dict>(report)) throw Error("report: expected a dict (hba.Result.report) or None");
  const std::string text = py::module_::import("json").attr("dumps")(report).cast<std::string>();
  return nlohmann::json::parse(text);
}

py::dict writeReportPage(const fs::path& path, const py::object& scans, const py::object& before,
                         const py::object& after, const py::object& report, const std::string& title,
                         const py::object& ground_truth, const std::optional<fs::path>& picture,
                         std::size_t points, double voxel, bool force) {
  if (path.extension() != ".html") throw Error(path.string() + ": the page must be an .html file");
  // A page hba wrote is written again; any other file only with force=True.
  std::error_code ec;
  if (fs::exists(path, ec) && !force && !render::isReportPage(path)) {
    throw Error(path.string() + ": exists and is not a page hba wrote; pass force=True to replace it");
  }
  render::ReportPageInput input;
  input.title = title;
  input.before = posesFromArray(before, "before");
  input.after = posesFromArray(after, "after");
  if (!ground_truth.is_none()) input.ground_truth = posesFromArray(ground_truth, "ground_truth");
  input.report = reportJson(report);
  if (picture) input.picture = *picture;
  const std::unique_ptr<io::ScanSource> source = scanSourceFrom(scans);
  render::ReportPageSettings settings;
  settings.point_budget = points;
  settings.voxel = voxel;
  settings.memory = MemoryBudget::ofAvailableMemoryAsHeld();
  render::ReportPageFigures page;
  {
    const py::gil_scoped_release release;
    page = render::writeReportPage(*source, input, path, settings);
  }
  py::dict figures;
  figures["points"] = page.points;
  figures["voxel"] = page.voxel;
  figures["bytes"] = page.bytes;
  return figures;
}

}  // namespace

void bindRender(py::module_& m) {
  m.def("write_report_page", &writeReportPage, py::arg("path"), py::arg("scans"), py::arg("before"),
        py::arg("after"), py::kw_only(), py::arg("report") = py::none(), py::arg("title") = "",
        py::arg("ground_truth") = py::none(), py::arg("picture") = py::none(),
        py::arg("points") = render::ReportPageSettings{}.point_budget,
        py::arg("voxel") = render::ReportPageSettings{}.voxel, py::arg("force") = false,
        R"(Writes the report page `hba optimize` and `hba view` write (docs/report_page.md): the
map of `scans` (a list of arrays or an hba.Dataset) at the `after` poses in 3D in
a browser, with the `before` poses (and `ground_truth`, if given) beside them,
the run's `report` (hba.Result.report, or report.json loaded) as tables, and a
`picture` (a PNG) below them. points and voxel: as `hba view --points --voxel`.
An existing file is replaced only when hba wrote it, or with force=True.
Returns {'points', 'voxel', 'bytes'} of the page written (atomically).)");
}

}  // namespace hba::python
