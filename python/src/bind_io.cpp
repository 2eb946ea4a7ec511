// Files and datasets: hba.read_scan, write_scan, read_poses, write_poses,
// open_dataset and hba.Dataset, with the readers `hba` itself uses.
#include <pybind11/numpy.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <filesystem>
#include <optional>
#include <string>

#include "bindings.hpp"
#include "hba/core/enum_names.hpp"
#include "hba/core/error.hpp"
#include "hba/io/dataset.hpp"
#include "hba/io/pose_file.hpp"
#include "hba/io/scan_file.hpp"
#include "hba/io/scan_formats.hpp"
#include "numpy_convert.hpp"

namespace py = pybind11;
namespace fs = std::filesystem;

namespace hba::python {
namespace {

py::object stampsArray(const std::vector<double>& stamps) {
  if (stamps.empty()) return py::none();
  return py::array_t<double>(static_cast<py::ssize_t>(stamps.size()), stamps.data());
}

py::array_t<double> readScan(const fs::path& path) {
  io::WideCloud cloud;
  {
    const py::gil_scoped_release release;
    cloud = io::readScanWide(path);
  }
  return arrayFromWideCloud(cloud);
}

void writeScan(const fs::path& path, const py::handle& points) {
  const io::WideCloud cloud = wideCloudFromArray(points, "points");
  const py::gil_scoped_release release;
  io::writeScanWide(path, cloud);
}

py::object readPoses(const fs::path& path, const std::optional<std::string>& format, bool return_stamps) {
  const Trajectory trajectory =
      format ? io::readPoses(path, parseEnum<io::PoseFormat>(*format)) : io::readPoses(path);
  py::array_t<double> poses = arrayFromPoses(trajectory.poses);
  if (!return_stamps) return poses;
  return py::make_tuple(poses, stampsArray(trajectory.stamps));
}

void writePoses(const fs::path& path, const py::handle& poses, const std::string& format,
                const py::object& stamps) {
  Trajectory trajectory;
  trajectory.poses = posesFromArray(poses, "poses");
  if (!stamps.is_none()) {
    const auto values = DenseArray<double>::ensure(stamps);
    if (!values || values.ndim() != 1 || static_cast<std::size_t>(values.shape(0)) != trajectory.size()) {
      throw Error("stamps: expected one time (s) per pose, a 1-D array of " +
                  std::to_string(trajectory.size()));
    }
    trajectory.stamps.assign(values.data(), values.data() + values.shape(0));
  }
  io::writePoses(path, trajectory, parseEnum<io::PoseFormat>(format));
}

io::Dataset openDataset(const fs::path& dir, const std::optional<fs::path>& scans,
                        const std::optional<fs::path>& poses, const std::optional<std::string>& pose_format,
                        const std::optional<fs::path>& times, bool invert_poses, const py::object& extrinsic,
                        const std::optional<fs::path>& calibration, bool scans_in_world,
                        const std::string& cloud_topic, const std::string& pose_topic,
                        const std::string& tf_frames, double time_offset, double keyframe_distance,
                        double keyframe_angle, const std::string& deskew) {
  io::DatasetOverrides overrides;
  overrides.scans_dir = scans;
  overrides.poses_file = poses;
  if (pose_format) overrides.pose_format = parseEnum<io::PoseFormat>(*pose_format);
  overrides.times_file = times;
  overrides.invert_poses = invert_poses;
  if (!extrinsic.is_none()) overrides.extrinsic = poseFromMatrix(extrinsic, "extrinsic");
  overrides.calibration = calibration;
  overrides.scans_in_world = scans_in_world;
  overrides.recording.cloud_topic = cloud_topic;
  overrides.recording.pose_topic = pose_topic;
  if (!tf_frames.empty()) {
    const std::size_t colon = tf_frames.find(':');
    if (colon == std::string::npos || colon == 0 || colon + 1 == tf_frames.size()) {
      throw Error("tf_frames: '" + tf_frames + "' must be PARENT:CHILD, e.g. odom:base_link");
    }
    overrides.recording.tf_parent = tf_frames.substr(0, colon);
    overrides.recording.tf_child = tf_frames.substr(colon + 1);
  }
  overrides.recording.time_offset = time_offset;
  overrides.recording.keyframe_distance = keyframe_distance;
  overrides.recording.keyframe_angle = keyframe_angle;
  overrides.deskew = parseEnum<io::DeskewMode>(deskew);
  return io::Dataset::open(dir, overrides);
}

std::size_t scanIndex(const io::Dataset& dataset, py::ssize_t index) {
  const auto size = static_cast<py::ssize_t>(dataset.size());
  const py::ssize_t from_start = index < 0 ? index + size : index;  // Python's negative indices
  if (from_start < 0 || from_start >= size) {
    throw py::index_error("scan index " + std::to_string(index) + " is out of range for " +
                          std::to_string(size) + " scans (" + std::to_string(-size) + " to " +
                          std::to_string(size - 1) + ")");
  }
  return static_cast<std::size_t>(from_start);
}

py::array_t<float> loadScan(const io::Dataset& dataset, py::ssize_t index) {
  const std::size_t i = scanIndex(dataset, index);
  PointCloud cloud;
  {
    const py::gil_scoped_release release;
    cloud = dataset.loadScan(i);
  }
  return arrayFromCloud(cloud);
}

void bindDataset(py::module_& m) {
  py::class_<io::Dataset>(m, "Dataset",
                          "A sequence on disk (scans + trajectory), opened by hba.open_dataset. "
                          "dataset[i] reads scan i in its sensor frame as hba optimizes it: (N, 4) "
                          "float32 (N, 3 without intensity); negative i counts from the end.")
      .def("__len__", &io::Dataset::size)
      .def("__getitem__", &loadScan, py::arg("index"))
      .def("scan_path", [](const io::Dataset& d, py::ssize_t i) { return d.scanPath(scanIndex(d, i)); })
      .def_property_readonly(
          "poses", [](const io::Dataset& d) { return arrayFromPoses(d.trajectory().poses); },
          "sensor-to-world poses, (K, 4, 4)")
      .def_property_readonly(
          "stamps", [](const io::Dataset& d) { return stampsArray(d.trajectory().stamps); },
          "times (s) of the poses, or None")
      .def(
          "every_scan",
          [](const io::Dataset& d, const py::object& poses) {
            const Trajectory every = d.everyScan(posesFromArray(poses, "poses"));
            return py::make_tuple(stampsArray(every.stamps), arrayFromPoses(every.poses));
          },
          py::arg("poses"),
          "Every scan of a keyframed recording, keyframe or not, with its pose corrected as the "
          "keyframes around it were (`hba optimize --every-scan`): (stamps (N,), poses (N, 4, 4)) "
          "for `poses`, one per keyframe (this dataset's scans)")
      .def_property_readonly("layout", &io::Dataset::layout)
      .def_property_readonly("root", &io::Dataset::root)
      .def_property_readonly("scans_dir", &io::Dataset::scansDir)
      .def_property_readonly("poses_file", &io::Dataset::posesFile)
      .def_property_readonly("pose_format",
                             [](const io::Dataset& d) { return hba::toString(d.poseFormat()); })
      .def_property_readonly("notes",
                             [](const io::Dataset& d) {
                               std::vector<std::string> notes;
                               for (const io::DatasetNote& note : d.notes()) notes.push_back(note.text);
                               return notes;
                             })
      .def("__repr__", [](const io::Dataset& d) {
        return "hba.Dataset('" + d.root().string() + "', " + d.layout() + " layout, " +
               std::to_string(d.size()) + " scans)";
      });
}

// The docstrings name the formats of the table (hba/io/scan_formats.hpp).
std::string readScanDoc() {
  return "Reads a scan or map: " + io::scanFormatList() + R"( (LAS 1.0-1.4).

Returns (N, 4) float64 (x y z intensity), (N, 3) when the file has no
intensity (a LAS file always has one). Coordinates are exactly as stored:
float64 fields to the last bit, LAS's scaled integers (UTM included) to the
file's scale, float32 fields widened. Points with a NaN or infinite
coordinate are dropped. Raises hba.Error naming the file.)";
}

std::string writeScanDoc() {
  return "Writes points in the format the extension names: " + io::scanFormatList() + R"(.

points: (N, 3) or (N, 4) (x y z [intensity]) of any real, integer or bool
dtype, in any memory layout; every coordinate must be exactly a float64.
Coordinates are kept: .pcd and .ply store float32 x y z when every
coordinate is exactly a float32 and float64 otherwise; .las stores
millimetres (scale 0.001) from an offset at the cloud's centre; .bin holds
float32 only and refuses coordinates a float32 would round. Intensities are
stored as float32 (.las: uint16, rounded). Raises hba.Error.)";
}

}  // namespace

void bindIo(py::module_& m) {
  m.def("read_scan", &readScan, py::arg("path"), readScanDoc().c_str());
  m.def("write_scan", &writeScan, py::arg("path"), py::arg("points"), writeScanDoc().c_str());
  m.def("read_poses", &readPoses, py::arg("path"), py::arg("format") = py::none(),
        py::arg("return_stamps") = false,
        "Reads a trajectory (hba pose.json, kitti, tum; detected unless `format`): (K, 4, 4) "
        "sensor-to-world poses, or (poses, stamps or None) with return_stamps=True.");
  m.def("write_poses", &writePoses, py::arg("path"), py::arg("poses"), py::arg("format") = "kitti",
        py::arg("stamps") = py::none(), "Writes (K, 4, 4) poses as an hba, kitti or tum trajectory.");
  bindDataset(m);
  m.def("open_dataset", &openDataset, py::arg("path"), py::kw_only(), py::arg("scans") = py::none(),
        py::arg("poses") = py::none(), py::arg("pose_format") = py::none(), py::arg("times") = py::none(),
        py::arg("invert_poses") = false, py::arg("extrinsic") = py::none(),
        py::arg("calibration") = py::none(), py::arg("scans_in_world") = false, py::arg("cloud_topic") = "",
        py::arg("pose_topic") = "", py::arg("tf_frames") = "", py::arg("time_offset") = 0.0,
        py::arg("keyframe_distance") = 0.0, py::arg("keyframe_angle") = 0.0, py::arg("deskew") = "auto",
        "Opens a dataset folder or a recording (ROS 1 bag, MCAP, .db3, rosbag2 folder) as `hba "
        "optimize DIR` does (docs/io_datasets.md, docs/recordings.md); the keywords are its --scans, "
        "--poses, --format, --times, --invert-poses, --extrinsic (4x4), --calib, --scans-in-world, "
        "--cloud-topic, --pose-topic, --tf-frames ('PARENT:CHILD'), --time-offset (s), "
        "--keyframe-distance (m), --keyframe-angle (deg) and --deskew ('auto', 'on', 'off'). Reads no "
        "scan until asked.");
}

}  // namespace hba::python
