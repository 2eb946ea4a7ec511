// hba.optimize: the whole method (runHierarchicalBa) on scans and poses from
// Python, with loop pairs and position priors read as the tool reads them.
#include <pybind11/numpy.h>

#include <filesystem>
#include <optional>

#include "bindings.hpp"
#include "hba/core/error.hpp"
#include "hba/io/dataset.hpp"
#include "hba/pipeline/closure_files.hpp"
#include "hba/pipeline/deskew_passes.hpp"
#include "hba/pipeline/hierarchical_ba.hpp"
#include "hba/pipeline/prior_map.hpp"
#include "hba/pipeline/sessions.hpp"
#include "hba/settings/settings_file.hpp"
#include "json_to_python.hpp"
#include "numpy_convert.hpp"
#include "pipeline/report_json.hpp"
#include "settings_kwargs.hpp"

namespace py = pybind11;

namespace hba::python {
namespace {

struct OptimizeResult {
  py::array_t<double> poses;            // (K, 4, 4)
  py::dict report;                      // report.json's library part, settings included
  py::array_t<double> hierarchy_poses;  // (K, 4, 4): the paper's method alone, before the refinement
};

// A file name from Python (str or os.PathLike), "" for None.
std::string fileName(const py::object& name, const char* what) {
  if (name.is_none()) return "";
  if (!py::isinstance<py::str>(name) && !py::hasattr(name, "__fspath__")) {
    throw Error(std::string(what) + ": expected a file name (str or os.PathLike)");
  }
  return py::str(py::module_::import("os").attr("fspath")(name)).cast<std::string>();
}

// report.json's library part: the run's report and the settings it ran with.
nlohmann::json libraryReport(const pipeline::HbaReport& report, const HbaSettings& settings) {
  nlohmann::json json = pipeline::reportToJson(report);
  json["settings"] = settings::settingsToJson(settings);
  return json;
}

// --loops and --priors as the tool reads them; priors go to frames by their
// stamps, which only a dataset has.
pipeline::ClosureInputs closureInputs(const py::object& scans, const std::vector<Pose>& initial,
                                      const pipeline::ClosureFiles& files) {
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
  return pipeline::readClosureFiles(files, {&stamped}, {0}, initial.size());
}

// hba.plan: what hba.optimize would do with these scans and keywords, as
// `hba optimize --print-plan` prints it.
py::dict plan(const py::object& scans, const py::kwargs& kwargs) {
  const HbaSettings settings = settingsFromKwargs(kwargs);
  std::optional<io::Dataset> dataset;
  if (py::isinstance<io::Dataset>(scans)) dataset.emplace(scans.cast<const io::Dataset&>());
  const std::unique_ptr<io::ScanSource> source =
      dataset ? std::make_unique<io::DatasetScanSource>(*dataset) : scanSourceFrom(scans);
  nlohmann::json json;
  {
    const py::gil_scoped_release release;
    json = pipeline::planToJson(pipeline::planRun(*source, settings));
  }
  return py::dict(toPython(json));
}

OptimizeResult optimize(const py::object& scans, const py::object& poses, const py::object& loops,
                        const py::object& priors, double prior_max_gap, int deskew_passes,
                        const py::kwargs& kwargs) {
  const HbaSettings settings = settingsFromKwargs(kwargs);
  const bool is_dataset = py::isinstance<io::Dataset>(scans);
  if (poses.is_none() && !is_dataset)
    throw Error("poses: required with arrays of scans (only a dataset has its own)");
  // A dataset's own poses as read, not through a 4x4 matrix and back (which
  // rounds them): the tool's poses, bit for bit.
  const std::vector<Pose> initial =
      poses.is_none() ? scans.cast<const io::Dataset&>().trajectory().poses : posesFromArray(poses, "poses");
  if (deskew_passes < 1) throw Error("deskew_passes: " + std::to_string(deskew_passes) + " (at least 1)");
  // A dataset's raw sweeps are deskewed again between passes: in a copy, so
  // that the caller's dataset still reads them as it did.
  std::optional<io::Dataset> dataset;
  if (is_dataset) dataset.emplace(scans.cast<const io::Dataset&>());
  const std::unique_ptr<io::ScanSource> source =
      dataset ? std::make_unique<io::DatasetScanSource>(*dataset) : scanSourceFrom(scans);
  // Poses and scans that differ in number: the run below refuses them.
  const pipeline::ClosureInputs closures =
      initial.size() == source->size()
          ? closureInputs(scans, initial,
                          {fileName(loops, "loops"), fileName(priors, "priors"), prior_max_gap})
          : pipeline::ClosureInputs{};
  pipeline::DatasetRun run;
  {
    // Python threads run on while hba works; nothing below touches Python.
    const py::gil_scoped_release release;
    if (dataset) {
      run = pipeline::runWithDeskewPasses(*dataset, *source, initial, pipeline::planRun(*source, settings),
                                          closures, deskew_passes);
    } else {
      run.result = pipeline::runHierarchicalBa(*source, initial, settings, closures);
    }
  }
  nlohmann::json report = libraryReport(run.result.report, settings);
  if (dataset && dataset->pointTimes()) report["deskew"] = pipeline::deskewReport(*dataset, run);
  return {arrayFromPoses(run.result.poses), py::dict(toPython(report)),
          arrayFromPoses(run.result.hierarchy_poses)};
}

bool sameFolder(const std::filesystem::path& a, const std::filesystem::path& b) {
  std::error_code ec;
  return a == b || std::filesystem::equivalent(a, b, ec);
}

// map: a cloud file, or an hba.Dataset at its poses (or at map_poses).
pipeline::PriorMap priorMapFrom(const py::object& map, const py::object& map_poses) {
  if (py::isinstance<io::Dataset>(map)) {
    const io::Dataset& dataset = map.cast<const io::Dataset&>();
    std::vector<Pose> poses =
        map_poses.is_none() ? dataset.trajectory().poses : posesFromArray(map_poses, "map_poses");
    const std::string name = "map (" + dataset.root().string() + ")";
    return pipeline::priorMapFromDataset(dataset, std::move(poses), name);
  }
  if (!map_poses.is_none()) throw Error("map_poses: only for a map given as an hba.Dataset");
  return pipeline::priorMapFromCloud(fileName(map, "map"));
}

OptimizeResult optimizeInMap(const io::Dataset& dataset, const py::object& map, const py::object& map_poses,
                             const py::object& poses, const py::object& loops, const py::kwargs& kwargs) {
  const HbaSettings settings = settingsFromKwargs(kwargs);
  const std::vector<Pose> initial =
      poses.is_none() ? dataset.trajectory().poses : posesFromArray(poses, "poses");
  // Refused before the map is merged from its scans.
  if (py::isinstance<io::Dataset>(map) && sameFolder(map.cast<const io::Dataset&>().root(), dataset.root())) {
    throw Error("map: " + dataset.root().string() +
                " is the session being optimized: a session placed in a map of itself finds only itself");
  }
  const io::DatasetScanSource scans(dataset);
  pipeline::ClosureFiles files;
  files.loops = fileName(loops, "loops");
  const pipeline::ClosureInputs closures =
      initial.size() == scans.size()
          ? pipeline::readClosureFiles(files, {&dataset.trajectory()}, {0}, scans.size())
          : pipeline::ClosureInputs{};
  const pipeline::PriorMap prior_map = priorMapFrom(map, map_poses);
  pipeline::MapRun run;
  {
    const py::gil_scoped_release release;
    run = pipeline::runInMap(prior_map, scans, initial, settings, closures, dataset.root().string());
  }
  nlohmann::json report = libraryReport(run.result.report, settings);
  report["map"] = pipeline::mapReport(prior_map, run);
  return {arrayFromPoses(pipeline::inMapFrame(prior_map, run.result.poses)), py::dict(toPython(report)),
          arrayFromPoses(pipeline::inMapFrame(prior_map, run.result.hierarchy_poses))};
}

// align="register" | "identity" | the later sessions' world_from_session.
pipeline::SessionPlacement placementFrom(const py::object& align, std::size_t sessions) {
  pipeline::SessionPlacement how;
  if (py::isinstance<py::str>(align)) {
    const std::string name = align.cast<std::string>();
    if (name == "identity") {
      how.method = pipeline::SessionPlacement::Method::Identity;
    } else if (name != "register") {
      throw Error("align: '" + name + "' is none of 'register', 'identity' or a list of 4x4 transforms");
    }
    return how;
  }
  how.method = pipeline::SessionPlacement::Method::Given;
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
  const HbaSettings settings = settingsFromKwargs(kwargs);
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
  const pipeline::SessionScans session_scans(sessions, names);
  const io::ConcatenatedScanSource& scans = session_scans.all();
  pipeline::ClosureInputs closures =
      pipeline::readClosureFiles({fileName(loops, "loops"), fileName(priors, "priors"), prior_max_gap},
                                 session_scans.trajectories(), scans.starts(), scans.size());
  const pipeline::SessionPlacement how = placementFrom(align, sessions.size());
  pipeline::SessionsRun run;
  {
    const py::gil_scoped_release release;
    run = pipeline::runSessions(session_scans, how, pipeline::planRun(scans, settings), closures);
  }
  const pipeline::HbaResult& result = run.result;
  const pipeline::PlacedSessions& placed = run.placed;
  nlohmann::json report = libraryReport(result.report, settings);
  report["sessions"] = nlohmann::json::array();
  for (std::size_t k = 0; k < sessions.size(); ++k) {
    report["sessions"].push_back(
        {{"first_frame", scans.starts()[k]}, {"frames", scans.starts()[k + 1] - scans.starts()[k]}});
  }
  report["alignment"] = {{"method", pipeline::placementName(how.method)}, {"registered", placed.registered}};
  return {arrayFromPoses(result.poses), py::dict(toPython(report)), arrayFromPoses(result.hierarchy_poses)};
}

const char* const kOptimizeInMapDoc = R"(Places a new session in a map that stays put, optimizes it
and refines it against the map, as `hba optimize NEW --map MAP` (a cloud
file) or `--fixed SESSION` (a dataset at its poses) does.

dataset: the new session, an hba.Dataset.
map: a map cloud file (.pcd, .ply, .las, .xyz, ...), or an hba.Dataset
       whose scans at its poses (or at map_poses) are the map.
poses: the session's start poses (default: the dataset's).
loops, **settings: as hba.optimize.
Returns an hba.Result: .poses in the map's frame, .report with 'map' (the
placement and the refinement against the map).)";

py::dict settingsDict(const py::kwargs& kwargs) {
  const HbaSettings settings = settingsFromKwargs(kwargs);
  nlohmann::json out = settings::settingsToJson(settings);
  out["threads"] = settings.threads;
  return py::dict(toPython(out));
}

const char* const kOptimizeDoc = R"(Optimizes the poses of a sequence, as `hba optimize` does.

scans: a list of (N, 3) or (N, 4) arrays (x y z [intensity], sensor frame),
       or an hba.Dataset (read from disk as needed).
poses: (K, 4, 4) sensor-to-world poses, one per scan; for an hba.Dataset,
       None (the default) takes its own poses as the tool reads them.
loops: a file of loop-closure pairs, as `hba optimize --loops` (docs/closure.md).
priors: a file of position priors, as `--priors`; scans must then be an
       hba.Dataset (priors go to frames by the scans' stamps).
prior_max_gap: a prior further than this (s) from every scan is not used.
deskew_passes: raw sweeps (an hba.Dataset with point times, deskewed): runs
       in all, each after deskewing the sweeps by the poses the last found,
       as `--deskew-passes` (the dataset passed in is not changed).
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
      .def_readonly("hierarchy_poses", &OptimizeResult::hierarchy_poses,
                    "the poses the paper's method alone reached (the top-down pose graph), before the "
                    "refinement and the self-check, (K, 4, 4): for diagnosis")
      .def("__repr__", [](const OptimizeResult& r) {
        return "hba.Result(" + std::to_string(r.poses.shape(0)) +
               " poses, report keys: " + std::string(py::str(py::list(r.report.attr("keys")()))) + ")";
      });
  m.def("optimize", &optimize, py::arg("scans"), py::arg("poses") = py::none(), py::kw_only(),
        py::arg("loops") = py::none(), py::arg("priors") = py::none(),
        py::arg("prior_max_gap") = pipeline::ClosureFiles{}.prior_max_gap_s, py::arg("deskew_passes") = 2,
        kOptimizeDoc);
  m.def("optimize_in_map", &optimizeInMap, py::arg("dataset"), py::kw_only(), py::arg("map"),
        py::arg("map_poses") = py::none(), py::arg("poses") = py::none(), py::arg("loops") = py::none(),
        kOptimizeInMapDoc);
  m.def("optimize_sessions", &optimizeSessions, py::arg("datasets"), py::kw_only(),
        py::arg("align") = "register", py::arg("loops") = py::none(), py::arg("priors") = py::none(),
        py::arg("prior_max_gap") = pipeline::ClosureFiles{}.prior_max_gap_s, kOptimizeSessionsDoc);
  m.def("plan", &plan, py::arg("scans"),
        "What hba.optimize(scans, **settings) would do, worked out from the settings and a few scans "
        "read, as a dict: frames, windows (automatic: from the scans' density), final_voxel, layers, "
        "threads and memory_estimate, as `hba optimize DIR --print-plan` prints them; raises hba.Error "
        "as hba.optimize does.");
  m.def("settings", &settingsDict,
        "Every setting hba.optimize would run with for these keywords (defaults for the rest), as "
        "the dict report['settings'] holds, plus 'threads'; raises hba.Error as hba.optimize does.");
}

}  // namespace hba::python
