// hba.optimize: the whole method (runHierarchicalBa) on scans and poses from
// Python, with loop pairs and position priors read as the tool reads them.
#include <pybind11/numpy.h>

#include "bindings.hpp"
#include "hba/core/error.hpp"
#include "hba/io/dataset.hpp"
#include "hba/pyramid/closure_files.hpp"
#include "hba/pyramid/hierarchical_ba.hpp"
#include "hba/pyramid/sessions.hpp"
#include "hba/pyramid/settings_file.hpp"
#include "json_to_python.hpp"
#include "numpy_convert.hpp"
#include "pyramid/report_json.hpp"
#include "settings_kwargs.hpp"

namespace py = pybind11;

namespace hba::python {
namespace {

struct OptimizeResult {
  py::array_t<double> poses;  // (K, 4, 4)
  py::dict report;            // report.json's library part, settings included
};

// A file name from Python (str or os.PathLike), "" for None.
std::string fileName(const py::object& name, const char* what) {
  if (name.is_none()) return "";
  if (!py::isinstance<py::str>(name) && !py::hasattr(name, "__fspath__")) {
    throw Error(std::string(what) + ": expected a file name (str or os.PathLike)");
  }
  return py::str(py::module_::import("os").attr("fspath")(name)).cast<std::string>();
}

// --loops and --priors as the tool reads them; priors go to frames by their
// stamps, which only a dataset has.
pyramid::ClosureInputs closureInputs(const py::object& scans, const std::vector<Pose>& initial,
                                     const pyramid::ClosureFiles& files) {
  if (files.loops.empty() && files.priors.empty()) return {};
  Trajectory stamped;
  stamped.poses = initial;
  if (!files.priors.empty()) {
    if (!py::isinstance<io::Dataset>(scans)) {
      throw Error(
          "priors: they go to frames by time, and arrays of scans have no stamps; pass "
          "hba.open_dataset(folder) as scans");
    }
    stamped.stamps = scans.cast<const io::Dataset&>().trajectory().stamps;
  }
  return pyramid::readClosureFiles(files, {&stamped}, {0}, initial.size());
}

OptimizeResult optimize(const py::object& scans, const py::object& poses, const py::object& loops,
                        const py::object& priors, double prior_max_gap, const py::kwargs& kwargs) {
  const pyramid::HbaSettings settings = settingsFromKwargs(kwargs);
  const std::unique_ptr<io::ScanSource> source = scanSourceFrom(scans);
  const std::vector<Pose> initial = posesFromArray(poses, "poses");
  // Poses and scans that differ in number: the run below refuses them.
  const pyramid::ClosureInputs closures =
      initial.size() == source->size()
          ? closureInputs(scans, initial,
                          {fileName(loops, "loops"), fileName(priors, "priors"), prior_max_gap})
          : pyramid::ClosureInputs{};
  pyramid::HbaResult result;
  {
    // Python threads run on while hba works; nothing below touches Python.
    const py::gil_scoped_release release;
    result = pyramid::runHierarchicalBa(*source, initial, settings, closures);
  }
  nlohmann::json report = pyramid::reportToJson(result.report);
  report["settings"] = pyramid::settingsToJson(settings);
  return {arrayFromPoses(result.poses), py::dict(toPython(report))};
}

// align="register" | "identity" | the later sessions' world_from_session.
pyramid::SessionPlacement placementFrom(const py::object& align, std::size_t sessions) {
  pyramid::SessionPlacement how;
  if (py::isinstance<py::str>(align)) {
    const std::string name = align.cast<std::string>();
    if (name == "identity") {
      how.method = pyramid::SessionPlacement::Method::Identity;
    } else if (name != "register") {
      throw Error("align: '" + name + "' is none of 'register', 'identity' or a list of 4x4 transforms");
    }
    return how;
  }
  how.method = pyramid::SessionPlacement::Method::Given;
  how.given = posesFromArray(align, "align");
  if (how.given.size() + 1 != sessions) {
    throw Error("align: " + std::to_string(how.given.size()) + " transforms for " +
                std::to_string(sessions - 1) + " later sessions (one world_from_session each)");
  }
  return how;
}

OptimizeResult optimizeSessions(const py::sequence& datasets, const py::object& align,
                                const py::object& loops, const py::object& priors, double prior_max_gap,
                                const py::kwargs& kwargs) {
  const pyramid::HbaSettings settings = settingsFromKwargs(kwargs);
  std::vector<const io::Dataset*> sessions;
  for (std::size_t k = 0; k < datasets.size(); ++k) {
    if (!py::isinstance<io::Dataset>(datasets[k])) {
      throw Error("datasets[" + std::to_string(k) + "]: expected an hba.Dataset (hba.open_dataset(folder))");
    }
    sessions.push_back(&datasets[k].cast<const io::Dataset&>());
  }
  if (sessions.size() < 2) throw Error("datasets: give two sessions or more (one: hba.optimize)");
  std::vector<std::string> names;
  for (std::size_t k = 0; k < sessions.size(); ++k) names.push_back("datasets[" + std::to_string(k) + "]");
  const pyramid::SessionScans session_scans(sessions, names);
  const io::ConcatenatedScanSource& scans = session_scans.all();
  pyramid::ClosureInputs closures =
      pyramid::readClosureFiles({fileName(loops, "loops"), fileName(priors, "priors"), prior_max_gap},
                                session_scans.trajectories(), scans.starts(), scans.size());
  const pyramid::SessionPlacement how = placementFrom(align, sessions.size());
  pyramid::HbaResult result;
  pyramid::PlacedSessions placed;
  {
    const py::gil_scoped_release release;
    placed = pyramid::placeSessions(session_scans.inputs(), how, settings.scan_voxel);
    const std::vector<Pose> initial = pyramid::sessionsInOneFrame(session_scans.inputs(), placed, closures);
    result = pyramid::runHierarchicalBa(scans, initial, settings, closures);
  }
  nlohmann::json report = pyramid::reportToJson(result.report);
  report["settings"] = pyramid::settingsToJson(settings);
  report["sessions"] = nlohmann::json::array();
  for (std::size_t k = 0; k < sessions.size(); ++k) {
    report["sessions"].push_back(
        {{"first_frame", scans.starts()[k]}, {"frames", scans.starts()[k + 1] - scans.starts()[k]}});
  }
  report["alignment"] = {{"method", pyramid::placementName(how.method)}, {"registered", placed.registered}};
  return {arrayFromPoses(result.poses), py::dict(toPython(report))};
}

py::dict settingsDict(const py::kwargs& kwargs) {
  const pyramid::HbaSettings settings = settingsFromKwargs(kwargs);
  nlohmann::json out = pyramid::settingsToJson(settings);
  out["threads"] = settings.threads;
  return py::dict(toPython(out));
}

const char* const kOptimizeDoc = R"(Optimizes the poses of a sequence, as `hba optimize` does.

scans: a list of (N, 3) or (N, 4) arrays (x y z [intensity], sensor frame),
       or an hba.Dataset (read from disk as needed).
poses: (K, 4, 4) sensor-to-world poses, one per scan.
loops: a file of loop-closure pairs, as `hba optimize --loops` (docs/closure.md).
priors: a file of position priors, as `--priors`; scans must then be an
       hba.Dataset (priors go to frames by the scans' stamps).
prior_max_gap: a prior further than this (s) from every scan is not used.
**settings: the YAML keys of `hba optimize --config` (docs/settings.md):
       window=10, refine=False, local={"voxel_size": 2.0}; threads=N as -j N.
Returns an hba.Result: .poses (K, 4, 4) and .report (report.json's dict).
Raises hba.Error for a bad setting, array or pose count.)";

const char* const kOptimizeSessionsDoc = R"(Optimizes several sessions of one place as one map, as
`hba optimize A B ...` does.

datasets: two or more hba.Dataset, each in its own frame; the result is in
       the first one's.
align: how the later sessions are placed first: "register" (found from
       their scans), "identity" (they share a frame), or one 4x4
       world_from_session per later session.
loops, priors, prior_max_gap, **settings: as hba.optimize; loop indices
       count all sessions' frames one after the other.
Returns an hba.Result: .poses (every session's, one after the other) and
.report (with 'sessions': each one's first_frame and frames, and
'alignment').)";

}  // namespace

void bindOptimize(py::module_& m) {
  py::class_<OptimizeResult>(m, "Result", "What hba.optimize returns")
      .def_readonly("poses", &OptimizeResult::poses, "optimized sensor-to-world poses, (K, 4, 4)")
      .def_readonly("report", &OptimizeResult::report,
                    "the run report (report.json's library part, with 'settings')")
      .def("__repr__", [](const OptimizeResult& r) {
        return "hba.Result(" + std::to_string(r.poses.shape(0)) +
               " poses, report keys: " + std::string(py::str(py::list(r.report.attr("keys")()))) + ")";
      });
  m.def("optimize", &optimize, py::arg("scans"), py::arg("poses"), py::kw_only(),
        py::arg("loops") = py::none(), py::arg("priors") = py::none(),
        py::arg("prior_max_gap") = pyramid::ClosureFiles{}.prior_max_gap_s, kOptimizeDoc);
  m.def("optimize_sessions", &optimizeSessions, py::arg("datasets"), py::kw_only(),
        py::arg("align") = "register", py::arg("loops") = py::none(), py::arg("priors") = py::none(),
        py::arg("prior_max_gap") = pyramid::ClosureFiles{}.prior_max_gap_s, kOptimizeSessionsDoc);
  m.def("settings", &settingsDict,
        "Every setting hba.optimize would run with for these keywords (defaults for the rest), as "
        "the dict report['settings'] holds, plus 'threads'; raises hba.Error as hba.optimize does.");
}

}  // namespace hba::python
