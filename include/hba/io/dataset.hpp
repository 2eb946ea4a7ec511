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
// A times.txt beside the trajectory supplies timestamps when the trajectory
// has none. docs/io_datasets.md describes every rule.
//
// Opening reads no scan (only directory listings and the trajectory): scans
// are loaded lazily by index.
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

// One thing discovery decided or noticed (which file it picked, what it
// ignored), for the caller to log.
struct DatasetNote {
  enum class Level { Info, Warning };
  Level level = Level::Info;
  std::string text;
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
  // Where the timestamps came from when not from the trajectory (else empty).
  const std::filesystem::path& timesFile() const { return times_file_; }
  // The KITTI calib.txt whose Tr turned camera poses into LiDAR poses (else empty).
  const std::filesystem::path& calibrationFile() const { return calibration_file_; }
  const std::vector<DatasetNote>& notes() const { return notes_; }
  const std::filesystem::path& scanPath(std::size_t i) const { return scan_paths_.at(i); }
  // Reads scan i from disk (sensor frame). Throws hba::Error naming the file.
  PointCloud loadScan(std::size_t i) const;

 private:
  std::string layout_;
  std::filesystem::path root_, scans_dir_, poses_file_, times_file_, calibration_file_;
  PoseFormat pose_format_ = PoseFormat::Kitti;
  Trajectory trajectory_;
  std::vector<std::filesystem::path> scan_paths_;
  std::vector<DatasetNote> notes_;
};

}  // namespace hba::io
