#pragma once
// Dataset discovery: finds the scans and the trajectory of a sequence.
//
// Layouts recognized in DIR:
//  - hba:      DIR/pcd/<i>.pcd (plain or zero-padded names) + DIR/pose.json
//  - scans:    DIR/Scans/NNNNNN.pcd + DIR/odom_poses.txt (KITTI), as written by
//              FAST-LIO2 / SC-SLAM pipelines; other scan-folder + trajectory pairs too
//  - kitti:    DIR/velodyne/NNNNNN.bin + a KITTI pose file; calib.txt's Tr is
//              applied when the poses are of the camera
//  - ros1-bag, ros2-bag: a recording given instead of DIR: the scans of its
//              point cloud topic, each with the pose of its trajectory topic
//              at its stamp (docs/recordings.md)
// Explicit overrides (scans folder, poses file, pose format) always win.
// A times.txt beside the trajectory (or --times) supplies timestamps when the
// trajectory has none; scans named by time are ordered by it and, with a
// stamped trajectory, paired with their poses by time. Conventions other
// than "sensor-to-world poses of the scans' sensor, scans in the sensor
// frame" are converted on request (inverted poses, another body frame,
// scans saved in the world frame). docs/io_datasets.md describes every rule.
//
// Opening reads only directory listings, the trajectory and the first scan
// (do the sweeps carry point times to deskew them by?), and when they do up
// to six more along the run (in which unit?): scans are loaded lazily by index.
#include <cstddef>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "hba/core/point_cloud.hpp"
#include "hba/core/pose.hpp"
#include "hba/io/deskew.hpp"
#include "hba/io/pose_file.hpp"
#include "hba/rec/recording.hpp"

namespace hba::io {

struct DatasetOverrides {
  std::optional<std::filesystem::path> scans_dir;
  std::optional<std::filesystem::path> poses_file;
  std::optional<PoseFormat> pose_format;
  std::optional<std::filesystem::path> times_file;   // one stamp (s) a line, one per scan
  bool invert_poses = false;                         // the file holds world-to-sensor poses
  std::optional<Pose> extrinsic;                     // T_body_sensor: the file holds poses of another body
  std::optional<std::filesystem::path> calibration;  // KITTI calib.txt: the file holds camera-0 poses
  bool scans_in_world = false;                       // the scans were saved already moved into the world
  rec::RecordingOptions recording;                   // topics and time offset of a recording (a bag)
  DeskewMode deskew = DeskewMode::Auto;              // raw sweeps with point times (io/deskew.hpp)
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

  std::size_t size() const { return recording_ ? recording_->size() : scan_paths_.size(); }
  // "hba", "scans", "kitti", "explicit", "ros1-bag", "ros2-bag"
  const std::string& layout() const { return layout_; }
  const std::filesystem::path& root() const { return root_; }
  const std::filesystem::path& scansDir() const { return scans_dir_; }
  const std::filesystem::path& posesFile() const { return poses_file_; }
  PoseFormat poseFormat() const { return pose_format_; }
  const Trajectory& trajectory() const { return trajectory_; }
  // Where the timestamps came from when not from the trajectory (else empty).
  const std::filesystem::path& timesFile() const { return times_file_; }
  // The KITTI calib.txt whose Tr turned camera poses into LiDAR poses (else empty).
  const std::filesystem::path& calibrationFile() const { return calibration_file_; }
  // Where the stamps came from: "trajectory", "times file", "scan names" or "" (none).
  const std::string& stampsSource() const { return stamps_source_; }
  // The frame the trajectory file described when it was not the sensor's:
  // "camera" (KITTI calibration), "body" (--extrinsic), else "".
  const std::string& inputFrame() const { return input_frame_; }
  // Sensor poses (like trajectory()) turned back into that frame's poses.
  std::vector<Pose> toInputFrame(const std::vector<Pose>& sensor_poses) const;
  bool scansInWorld() const { return scans_in_world_; }
  // How the sweeps' point times are read when loadScan deskews them; empty
  // when it does not (no point times, --deskew off, or motion too sparse).
  const std::optional<PointTimeReading>& pointTimes() const { return point_times_; }
  // The sensor's pose at time t (s, the stamps' clock), from the densest
  // trajectory the dataset holds (a recording's own, else the scans' poses).
  Pose sensorPoseAt(double t) const;
  // Every scan of a recording (keyframes or not) with its sensor pose, the
  // keyframes' `optimized` sensor poses spread to the scans between them
  // (spreadCorrections); a folder's scans as they are. Stamped.
  Trajectory everyScan(const std::vector<Pose>& optimized) const;
  // From now on, deskew by these sensor poses of the scans (a better
  // estimate of the motion than the input's: an optimized run's).
  void deskewBy(const std::vector<Pose>& sensor_poses);
  const std::vector<DatasetNote>& notes() const { return notes_; }
  // Scan i's file; a recording's scans have none (its own path).
  const std::filesystem::path& scanPath(std::size_t i) const {
    return recording_ ? root_ : scan_paths_.at(i);
  }
  // The recording the scans come from, or null for a folder.
  const rec::Recording* recording() const { return recording_.get(); }
  // Reads scan i from disk, in the sensor frame (scans saved in the world
  // frame are moved back by their pose; raw sweeps deskewed to their stamp
  // when pointTimes() is set). Throws hba::Error naming the file.
  PointCloud loadScan(std::size_t i) const;

 private:
  std::vector<double> scanStamps(std::vector<double> name_stamps, const DatasetOverrides& overrides,
                                 std::string& source);
  void pairScansWithPoses(std::vector<double> name_stamps, const DatasetOverrides& overrides);
  void checkStampsIncrease();
  void noteStampUnit(const std::filesystem::path& file, const std::string& unit);
  void convertPoses(const DatasetOverrides& overrides);
  void prepareDeskew(DeskewMode mode);
  static Dataset openRecording(const std::filesystem::path& path, const DatasetOverrides& overrides);

  std::string layout_;
  std::filesystem::path root_, scans_dir_, poses_file_, times_file_, calibration_file_;
  std::string stamps_source_, input_frame_;
  // trajectory() = frame_left_ * (pose in the file) * frame_right_
  Pose frame_left_, frame_right_;
  bool scans_in_world_ = false;
  PoseFormat pose_format_ = PoseFormat::Kitti;
  Trajectory trajectory_;
  std::vector<std::filesystem::path> scan_paths_;
  std::shared_ptr<const rec::Recording> recording_;
  std::optional<PointTimeReading> point_times_;
  std::optional<Trajectory> deskew_motion_;  // deskewBy's poses
  std::vector<DatasetNote> notes_;
};

}  // namespace hba::io
