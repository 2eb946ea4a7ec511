#pragma once
// Dataset discovery: finds the scans and the trajectory of a sequence.
//
// Layouts recognized in DIR:
//  - hba:      DIR/pcd/<i>.pcd (plain or zero-padded names) + DIR/pose.json
//  - scans:    DIR/Scans/NNNNNN.pcd + DIR/odom_poses.txt (KITTI), as written by
//              FAST-LIO2 / SC-SLAM pipelines; other scan-folder + trajectory pairs too
//  - kitti:    DIR/velodyne/NNNNNN.bin + a KITTI pose file; calib.txt's Tr is
//              applied when the poses are of the camera
// Explicit overrides (scans folder, poses file, pose format) always win.
//
// Opening reads no scan: scans are loaded lazily by index.
#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "hba/core/point_cloud.hpp"
#include "hba/core/pose.hpp"
#include "hba/io/pose_file.hpp"

namespace hba::io {

struct DatasetOverrides {
  std::optional<std::filesystem::path> scans_dir;
  std::optional<std::filesystem::path> poses_file;
  std::optional<PoseFormat> pose_format;
};

class Dataset {
 public:
  // Throws hba::Error naming the file or folder and the problem (missing,
  // unreadable, scan and pose counts that differ, ...).
  static Dataset open(const std::filesystem::path& dir, const DatasetOverrides& overrides = {});

  std::size_t size() const { return scan_paths_.size(); }
  const std::string& layout() const { return layout_; }  // "hba", "scans", "kitti", "explicit"
  const std::filesystem::path& root() const { return root_; }
  const std::filesystem::path& scansDir() const { return scans_dir_; }
  const std::filesystem::path& posesFile() const { return poses_file_; }
  PoseFormat poseFormat() const { return pose_format_; }
  const Trajectory& trajectory() const { return trajectory_; }
  const std::filesystem::path& scanPath(std::size_t i) const { return scan_paths_.at(i); }
  // Reads scan i from disk (sensor frame). Throws hba::Error naming the file.
  PointCloud loadScan(std::size_t i) const;

 private:
  std::string layout_;
  std::filesystem::path root_, scans_dir_, poses_file_;
  PoseFormat pose_format_ = PoseFormat::Kitti;
  Trajectory trajectory_;
  std::vector<std::filesystem::path> scan_paths_;
};

}  // namespace hba::io
