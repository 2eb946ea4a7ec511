// Dataset::open: finds the scans and the trajectory, checks they agree, and
// records every choice it made. Reads no scan.
#include "hba/io/dataset.hpp"

#include <fmt/format.h>

#include <exception>

#include "core/input_file.hpp"
#include "dataset_parts.hpp"
#include "hba/core/error.hpp"
#include "hba/io/scan_file.hpp"
#include "hba/io/scan_formats.hpp"
#include "io/file_warnings.hpp"

namespace hba::io {
namespace fs = std::filesystem;

namespace {

std::string layoutOf(const DatasetOverrides& overrides, const fs::path& scans_dir, const fs::path& poses_file,
                     const fs::path& first_scan) {
  if (overrides.scans_dir && overrides.poses_file) return "explicit";
  if (scans_dir.filename() == "pcd" && poses_file.filename() == "pose.json") return "hba";
  if (std::string(scanFormatOf(first_scan).extension) == ".bin") return "kitti";
  return "scans";
}

std::string countsDiffer(std::size_t scans, const fs::path& scans_dir, std::size_t poses,
                         const fs::path& poses_file) {
  return "scans and poses differ in number: " + std::to_string(scans) + " scans in " + scans_dir.string() +
         " but " + std::to_string(poses) + " poses in " + poses_file.string();
}

template <typename T>
std::vector<T> pick(const std::vector<T>& values, const std::vector<std::size_t>& indices) {
  std::vector<T> out;
  out.reserve(indices.size());
  for (std::size_t i : indices) out.push_back(values[i]);
  return out;
}

}  // namespace

void Dataset::noteStampUnit(const fs::path& file, const std::string& unit) {
  if (unit.empty()) return;
  notes_.push_back(
      {DatasetNote::Level::Info, file.string() + ": the stamps are in " + unit + "; read as seconds"});
}

// The scans' own stamps: --times FILE (must fit), else the names, else a
// times.txt in DIR that fits (one that does not is ignored, with a warning
// when nothing else gives stamps).
std::vector<double> Dataset::scanStamps(std::vector<double> name_stamps, const DatasetOverrides& overrides,
                                        std::string& source) {
  const fs::path times = root_ / "times.txt";
  fs::path path;
  if (overrides.times_file) {
    path = detail::resolveOverride(root_, *overrides.times_file, "times file");
  } else if (name_stamps.empty() && regularFileIsPresent(times)) {
    path = times;
  }
  if (path.empty()) {
    source = name_stamps.empty() ? "" : "scan names";
    return name_stamps;
  }
  std::vector<double> stamps = readTimes(path);
  noteStampUnit(path, stampsToSeconds(stamps));
  if (stamps.size() != size()) {
    const std::string problem =
        std::to_string(stamps.size()) + " timestamps for " + std::to_string(size()) + " scans";
    if (overrides.times_file) failAt(path, problem);
    if (!trajectory_.hasStamps()) {
      notes_.push_back({DatasetNote::Level::Warning, "ignoring " + path.string() + ": " + problem});
    }
    source.clear();
    return {};
  }
  times_file_ = path;
  source = "times file";
  return stamps;
}

// Scans and poses paired by time when both have stamps and the scans' are
// meant to be matched (named by time, --times, or counts that differ: a
// trajectory at another rate); else by position, and the counts must agree.
void Dataset::pairScansWithPoses(std::vector<double> name_stamps, const DatasetOverrides& overrides) {
  std::string scan_source;
  const std::vector<double> scan_stamps = scanStamps(std::move(name_stamps), overrides, scan_source);
  const bool by_time = trajectory_.hasStamps() && !scan_stamps.empty() &&
                       (scan_source != "times file" || overrides.times_file || trajectory_.size() != size());
  if (by_time) {
    for (std::size_t i = 1; i < scan_stamps.size(); ++i) {
      if (scan_stamps[i] > scan_stamps[i - 1]) continue;
      failAt(times_file_, "the timestamps do not increase at line " + std::to_string(i + 1) +
                              "; scans cannot be paired with poses by time");
    }
    const detail::TimeMatch match =
        detail::matchByTime(scan_stamps, trajectory_.stamps, scans_dir_, poses_file_, notes_);
    scan_paths_ = pick(scan_paths_, match.kept_scans);
    trajectory_.poses = pick(trajectory_.poses, match.pose_of_scan);
    trajectory_.stamps = pick(trajectory_.stamps, match.pose_of_scan);
    stamps_source_ = "trajectory";
    return;
  }
  if (trajectory_.size() != size()) {
    throw Error(countsDiffer(size(), scans_dir_, trajectory_.size(), poses_file_));
  }
  if (trajectory_.hasStamps()) {
    times_file_.clear();  // the trajectory's own stamps are used
    stamps_source_ = "trajectory";
  } else if (!scan_stamps.empty()) {
    trajectory_.stamps = scan_stamps;
    stamps_source_ = scan_source;
  }
}

// Stamps that go backwards or repeat usually mean a wrong or merged file;
// pairing by time would then be wrong, so say where.
void Dataset::checkStampsIncrease() {
  const std::vector<double>& stamps = trajectory_.stamps;
  for (std::size_t i = 1; i < stamps.size(); ++i) {
    if (stamps[i] > stamps[i - 1]) continue;
    const fs::path& source = stamps_source_ == "times file" ? times_file_ : poses_file_;
    notes_.push_back({DatasetNote::Level::Warning,
                      source.string() + ": the timestamps do not increase at scan " + std::to_string(i) +
                          " (" + std::to_string(stamps[i - 1]) + " then " + std::to_string(stamps[i]) +
                          "); outputs keep them as given"});
    return;
  }
}

// The poses as the file holds them -> sensor-to-world poses of the scans' sensor.
void Dataset::convertPoses(const DatasetOverrides& overrides) {
  if (overrides.invert_poses) {
    for (Pose& pose : trajectory_.poses) pose = pose.inverse();
    notes_.push_back(
        {DatasetNote::Level::Info, "poses inverted (--invert-poses): the file holds world-to-sensor poses"});
  }
  // KITTI ground-truth poses are of camera 0: T_world_cam. The LiDAR's pose
  // is T_world_cam * Tr, and left-multiplying by Tr^-1 makes the world the
  // first LiDAR frame (z up) instead of the first camera frame (y down).
  // An explicit --poses file is taken as LiDAR poses unless --calib is given.
  fs::path calib;
  if (overrides.calibration) {
    calib = detail::resolveOverride(root_, *overrides.calibration, "calibration file");
  } else if (layout_ == "kitti" && !overrides.poses_file && !overrides.extrinsic &&
             regularFileIsPresent(root_ / "calib.txt")) {
    calib = root_ / "calib.txt";
  }
  if (!calib.empty()) {
    if (overrides.extrinsic) throw Error("give either --extrinsic or --calib, not both");
    const std::optional<Pose> lidar_to_camera = detail::readKittiLidarToCamera(calib);
    if (!lidar_to_camera) {
      if (overrides.calibration) failAt(calib, "has no Tr: line (the LiDAR-to-camera transform)");
      return;
    }
    frame_left_ = lidar_to_camera->inverse();
    frame_right_ = *lidar_to_camera;
    calibration_file_ = calib;
    input_frame_ = "camera";
    notes_.push_back({DatasetNote::Level::Info,
                      "KITTI camera poses turned into LiDAR poses with Tr of " + calib.string()});
  } else if (overrides.extrinsic) {
    frame_right_ = *overrides.extrinsic;
    input_frame_ = "body";
    notes_.push_back(
        {DatasetNote::Level::Info, "poses of the body frame turned into sensor poses with --extrinsic"});
  }
  for (Pose& pose : trajectory_.poses) pose = frame_left_ * pose * frame_right_;
}

Trajectory Dataset::everyScan(const std::vector<Pose>& optimized) const {
  if (optimized.size() != size()) {
    throw Error("every scan's pose: " + std::to_string(optimized.size()) + " poses for " +
                std::to_string(size()) + " scans");
  }
  if (!recording_) return Trajectory{optimized, trajectory_.stamps};
  Trajectory dense = recording_->coveredScans();
  for (Pose& pose : dense.poses) pose = frame_left_ * pose * frame_right_;
  return spreadCorrections(trajectory_, optimized, dense);
}

std::vector<Pose> Dataset::toInputFrame(const std::vector<Pose>& sensor_poses) const {
  const Pose left = frame_left_.inverse(), right = frame_right_.inverse();
  std::vector<Pose> out;
  out.reserve(sensor_poses.size());
  for (const Pose& pose : sensor_poses) out.push_back(left * pose * right);
  return out;
}

// A recording: its scans and interpolated poses; the pose conventions
// (--invert-poses, --extrinsic, --scans-in-world) apply as to a folder.
Dataset Dataset::openRecording(const fs::path& path, const DatasetOverrides& overrides) {
  if (overrides.scans_dir || overrides.times_file || overrides.calibration) {
    failAt(path,
           "a recording brings its own scans and stamps: --scans, --times and --calib are for folders "
           "(choose topics with --cloud-topic and --pose-topic)");
  }
  Dataset dataset;
  rec::RecordingOptions options = overrides.recording;
  Trajectory given;
  if (overrides.poses_file) {
    dataset.poses_file_ = *overrides.poses_file;
    dataset.pose_format_ =
        overrides.pose_format ? *overrides.pose_format : detectPoseFormat(dataset.poses_file_);
    given = readPoses(dataset.poses_file_, dataset.pose_format_);
    if (given.hasStamps()) {
      // A stamped trajectory (an odometry's poses): the scans' poses are interpolated from it.
      if (!options.pose_topic.empty()) {
        failAt(dataset.poses_file_,
               "--poses with stamps is the trajectory: --pose-topic cannot be given too");
      }
      dataset.noteStampUnit(dataset.poses_file_, stampsToSeconds(given.stamps));
      options.poses = given;
      options.poses_name = dataset.poses_file_.string();
    }
  }
  dataset.recording_ = std::make_shared<const rec::Recording>(rec::Recording::open(path, options));
  const rec::Recording& recording = *dataset.recording_;
  dataset.root_ = dataset.scans_dir_ = path;
  if (!overrides.poses_file) dataset.poses_file_ = path;
  dataset.layout_ = recording.format() == "ROS 1 bag" ? "ros1-bag" : "ros2-bag";
  dataset.trajectory_ = recording.trajectory();
  dataset.stamps_source_ = "recording";
  if (overrides.poses_file && !given.hasStamps()) {
    // Poses without stamps, one for each of the recording's scans (an earlier run's output).
    if (given.size() != recording.size()) {
      failAt(dataset.poses_file_, countsDiffer(recording.size(), path, given.size(), dataset.poses_file_));
    }
    dataset.trajectory_.poses = given.poses;
  }
  for (const std::string& note : recording.notes())
    dataset.notes_.push_back({DatasetNote::Level::Info, note});
  for (const std::string& warning : recording.warnings()) {
    dataset.notes_.push_back({DatasetNote::Level::Warning, warning});
  }
  dataset.checkStampsIncrease();
  const std::string& frames = recording.staticFrameProblem();
  if (!frames.empty() && !overrides.extrinsic) {
    failAt(path, frames + ". Give the clouds' pose in the body with --extrinsic 'tx ty tz qx qy qz qw'");
  }
  if (!frames.empty()) dataset.notes_.push_back({DatasetNote::Level::Warning, frames + ": --extrinsic used"});
  // The recording's own extrinsic (/tf_static) unless --extrinsic is given.
  DatasetOverrides conventions = overrides;
  if (!conventions.extrinsic && recording.staticExtrinsic())
    conventions.extrinsic = recording.staticExtrinsic();
  dataset.convertPoses(conventions);
  dataset.scans_in_world_ = overrides.scans_in_world;
  dataset.prepareDeskew(overrides.deskew);
  return dataset;
}

Dataset Dataset::open(const fs::path& dir, const DatasetOverrides& overrides) {
  if (rec::isRecording(dir)) return openRecording(dir, overrides);
  if (!overrides.recording.isDefault()) {
    failAt(dir,
           "--cloud-topic, --pose-topic, --time-offset and --keyframe-distance/-angle are for recordings "
           "(a bag, an MCAP file, a rosbag2 folder), not for a folder of scans");
  }
  requireFolder(dir, "dataset folder");
  Dataset dataset;
  dataset.root_ = dir;
  dataset.scans_dir_ = overrides.scans_dir
                           ? detail::resolveOverride(dir, *overrides.scans_dir, "scans folder")
                           : detail::findScansDir(dir, dataset.notes_);
  detail::ScanFiles scans = detail::listScans(dataset.scans_dir_);
  dataset.scan_paths_ = std::move(scans.paths);
  dataset.poses_file_ = overrides.poses_file
                            ? detail::resolveOverride(dir, *overrides.poses_file, "poses file")
                            : detail::findTrajectoryFile(dir, dataset.scans_dir_, dataset.notes_);
  dataset.pose_format_ =
      overrides.pose_format ? *overrides.pose_format : detectPoseFormat(dataset.poses_file_);
  dataset.trajectory_ = readPoses(dataset.poses_file_, dataset.pose_format_);
  dataset.noteStampUnit(dataset.poses_file_, stampsToSeconds(dataset.trajectory_.stamps));
  dataset.layout_ = layoutOf(overrides, dataset.scans_dir_, dataset.poses_file_, dataset.scan_paths_.front());
  dataset.pairScansWithPoses(std::move(scans.stamps), overrides);
  dataset.checkStampsIncrease();
  dataset.convertPoses(overrides);
  dataset.scans_in_world_ = overrides.scans_in_world;
  dataset.prepareDeskew(overrides.deskew);
  return dataset;
}

PointCloud Dataset::loadScan(std::size_t i) const {
  const fs::path& path = scanPath(i);
  try {
    PointCloud scan = recording_ ? recording_->loadScan(i) : readScan(path);
    if (point_times_ && scan.hasTime()) {
      const std::string what = recording_ ? path.string() + ": scan " + std::to_string(i) : path.string();
      const StrayTimes stray = deskew(
          scan, *point_times_, trajectory_.stamps.at(i), [this](double t) { return sensorPoseAt(t); }, what);
      if (stray.count > 0) {
        // Named once a file: a recording's later scans with strays go unnamed.
        warnAboutFile(
            path, "point times far from the scan's stamp",
            fmt::format("{}{} of {} points have times more than {:g} s from the scan's stamp (the "
                        "farthest {:.3g} s, read as {}): left out, their instant unknown{}",
                        recording_ ? "scan " + std::to_string(i) + ": " : "", stray.count,
                        scan.size() + stray.count, kFarthestTime, stray.farthest, point_times_->describe(),
                        recording_ ? " (later scans with such points are not named)" : ""));
      }
    }
    scan.time.clear();
    scan.time.shrink_to_fit();
    if (scan.empty()) {
      warnAboutFile(
          path, "scans with no points",
          "the scan has no points (none stored, or none with finite coordinates): it adds nothing to "
          "the map or to the optimization of its pose");
    }
    // In double: world-frame scans may be far from the origin (scan.origin).
    const Pose to_sensor = scans_in_world_ ? trajectory_.poses[i].inverse() : Pose::identity();
    if (scans_in_world_ || !scan.origin.isZero()) {
      for (Vec3f& p : scan.points) p = (to_sensor * (scan.origin + p.cast<double>())).cast<float>();
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
