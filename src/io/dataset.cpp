// Dataset::open: finds the scans and the trajectory, checks they agree, and
// records every choice it made. Reads no scan.
#include "hba/io/dataset.hpp"

#include <exception>
#include <system_error>

#include "dataset_parts.hpp"
#include "hba/core/error.hpp"
#include "hba/io/scan_file.hpp"

namespace hba::io {
namespace fs = std::filesystem;

namespace {

void checkDatasetFolder(const fs::path& dir) {
  std::error_code ec;
  if (!fs::exists(dir, ec)) failAt(dir, "dataset folder not found");
  if (!fs::is_directory(dir, ec)) failAt(dir, "is not a folder (expected a dataset folder)");
}

std::string layoutOf(const DatasetOverrides& overrides, const fs::path& scans_dir,
                     const fs::path& poses_file, const fs::path& first_scan) {
  if (overrides.scans_dir && overrides.poses_file) return "explicit";
  if (scans_dir.filename() == "pcd" && poses_file.filename() == "pose.json") return "hba";
  if (scanFormatFromExtension(first_scan) == ScanFormat::KittiBin) return "kitti";
  return "scans";
}

// KITTI ground-truth poses are of camera 0: T_world_cam. The LiDAR's pose is
// T_world_cam * Tr, and left-multiplying by Tr^-1 makes the world the first
// LiDAR frame (z up) instead of the first camera frame (y down).
void cameraToLidarPoses(Trajectory& trajectory, const Pose& lidar_to_camera) {
  const Pose camera_to_lidar = lidar_to_camera.inverse();
  for (Pose& pose : trajectory.poses) pose = camera_to_lidar * pose * lidar_to_camera;
}

}  // namespace

Dataset Dataset::open(const fs::path& dir, const DatasetOverrides& overrides) {
  checkDatasetFolder(dir);
  Dataset dataset;
  dataset.root_ = dir;
  dataset.scans_dir_ = overrides.scans_dir
                           ? detail::resolveOverride(dir, *overrides.scans_dir, "scans folder")
                           : detail::findScansDir(dir, dataset.notes_);
  dataset.scan_paths_ = detail::listNumberedScans(dataset.scans_dir_);
  dataset.poses_file_ =
      overrides.poses_file ? detail::resolveOverride(dir, *overrides.poses_file, "poses file")
                           : detail::findTrajectoryFile(dir, dataset.scans_dir_, dataset.notes_);
  dataset.pose_format_ =
      overrides.pose_format ? *overrides.pose_format : detectPoseFormat(dataset.poses_file_);
  dataset.trajectory_ = readPoses(dataset.poses_file_, dataset.pose_format_);
  dataset.layout_ = layoutOf(overrides, dataset.scans_dir_, dataset.poses_file_,
                             dataset.scan_paths_.front());

  if (dataset.trajectory_.size() != dataset.size()) {
    throw Error("scans and poses differ in number: " + std::to_string(dataset.size()) +
                " scans in " + dataset.scans_dir_.string() + " but " +
                std::to_string(dataset.trajectory_.size()) + " poses in " +
                dataset.poses_file_.string());
  }

  // An explicit --poses file is taken as LiDAR poses (e.g. hba's own output).
  const fs::path calib = dir / "calib.txt";
  std::error_code ec;
  if (dataset.layout_ == "kitti" && !overrides.poses_file && fs::is_regular_file(calib, ec)) {
    if (const std::optional<Pose> lidar_to_camera = detail::readKittiLidarToCamera(calib)) {
      cameraToLidarPoses(dataset.trajectory_, *lidar_to_camera);
      dataset.calibration_file_ = calib;
      dataset.notes_.push_back({DatasetNote::Level::Info,
                                "KITTI camera poses turned into LiDAR poses with Tr of " +
                                    calib.string()});
    }
  }

  const fs::path times = dir / "times.txt";
  if (!dataset.trajectory_.hasStamps() && fs::is_regular_file(times, ec)) {
    std::vector<double> stamps = detail::readTimesFile(times);
    if (stamps.size() == dataset.size()) {
      dataset.trajectory_.stamps = std::move(stamps);
      dataset.times_file_ = times;
    } else {
      dataset.notes_.push_back({DatasetNote::Level::Warning,
                                "ignoring " + times.string() + ": " +
                                    std::to_string(stamps.size()) + " timestamps for " +
                                    std::to_string(dataset.size()) + " scans"});
    }
  }
  return dataset;
}

PointCloud Dataset::loadScan(std::size_t i) const {
  const fs::path& path = scanPath(i);
  try {
    PointCloud scan = readScan(path);
    if (!scan.origin.isZero()) {  // a float64 file far from its origin: sensor-frame points
      for (Vec3f& p : scan.points) p = (scan.origin + p.cast<double>()).cast<float>();
      scan.origin.setZero();
    }
    return scan;
  } catch (const Error&) {
    throw;
  } catch (const std::exception& e) {
    failAt(path, std::string("cannot read the scan: ") + e.what());
  }
}

}  // namespace hba::io
