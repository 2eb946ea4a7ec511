// Evaluation: hba.ate (as `hba eval`) and hba.mme (as `hba mme`).
#include <pybind11/numpy.h>

#include <string>

#include "bindings.hpp"
#include "hba/core/error.hpp"
#include "hba/eval/map_entropy.hpp"
#include "hba/eval/merged_map.hpp"
#include "hba/eval/trajectory_error.hpp"
#include "numpy_convert.hpp"

namespace py = pybind11;

namespace hba::python {
namespace {

std::string numberText(double value) { return py::repr(py::float_(value)); }

py::dict statsDict(const eval::ErrorStats& s) {
  py::dict d;
  d["count"] = s.count;
  d["rmse"] = s.rmse;
  d["mean"] = s.mean;
  d["median"] = s.median;
  d["std"] = s.std;
  d["min"] = s.min;
  d["max"] = s.max;
  return d;
}

py::dict ate(const py::handle& reference, const py::handle& estimate, const std::string& align) {
  eval::EvalOptions options;
  options.alignment = parseEnum<eval::Alignment>(align);
  Trajectory ref, est;
  ref.poses = posesFromArray(reference, "reference");
  est.poses = posesFromArray(estimate, "estimate");
  const eval::TrajectoryEvaluation r = eval::evaluateTrajectory(ref, est, options);
  py::dict alignment;
  alignment["rotation"] =
      py::array_t<double>({3, 3}, {sizeof(double), 3 * sizeof(double)}, r.alignment.R.data());
  alignment["translation"] = py::array_t<double>(3, r.alignment.t.data());
  alignment["scale"] = r.alignment.scale;
  py::dict out;
  out["translation_m"] = statsDict(r.ate.translation_m);
  out["rotation_deg"] = statsDict(r.ate.rotation_deg);
  out["matched"] = r.matched;
  out["alignment"] = alignment;
  return out;
}

double mme(const py::object& scans, const py::handle& poses, double voxel, double radius, int min_neighbors) {
  // The rules of `hba mme`'s --voxel, --radius and --min-neighbors (NaN fails each).
  if (!(voxel >= 0))
    throw Error("mme: voxel must be >= 0 (m; 0 = keep every point), got " + numberText(voxel));
  if (!(radius > 0)) throw Error("mme: radius must be > 0 (m), got " + numberText(radius));
  if (min_neighbors < 0) throw Error("mme: min_neighbors must be >= 0, got " + std::to_string(min_neighbors));
  // World points far out (UTM) keep their precision, as `hba mme --map` keeps a float64 file's.
  const std::unique_ptr<io::ScanSource> source = scanSourceFrom(scans, FarPoints::KeepOrigin);
  const std::vector<Pose> world_poses = posesFromArray(poses, "poses");
  eval::MapSettings map_settings;
  map_settings.voxel = voxel;
  eval::MmeSettings entropy;
  entropy.radius = radius;
  entropy.min_neighbors = min_neighbors;
  eval::MmeResult result;
  {
    const py::gil_scoped_release release;
    const PointCloud map = eval::buildMergedMap(*source, world_poses, map_settings);
    result = eval::meanMapEntropy(map, entropy);
  }
  if (result.used == 0) throw Error("mme: no map point has enough neighbours: MME is undefined");
  return result.mme;
}

}  // namespace

void bindEval(py::module_& m) {
  m.def("ate", &ate, py::arg("reference"), py::arg("estimate"), py::arg("align") = "se3",
        "Absolute trajectory error of `estimate` against `reference` ((K, 4, 4) each, matched by "
        "index) after alignment (none, se3, sim3), as `hba eval`: a dict with 'translation_m' and "
        "'rotation_deg' statistics (rmse, mean, median, std, min, max, count), 'matched' and "
        "'alignment' (rotation, translation, scale mapping the estimate onto the reference).");
  m.def("mme", &mme, py::arg("scans"), py::arg("poses"), py::arg("voxel") = eval::MapSettings{}.voxel,
        py::arg("radius") = eval::MmeSettings{}.radius,
        py::arg("min_neighbors") = eval::MmeSettings{}.min_neighbors,
        "Mean map entropy of the scans merged with `poses` and downsampled to `voxel` (m), as "
        "`hba mme`: lower is crisper. scans: a list of (N, 3)/(N, 4) arrays or an hba.Dataset.");
}

}  // namespace hba::python
