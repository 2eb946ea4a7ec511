#include "dataset_args.hpp"

#include <spdlog/spdlog.h>

#include <charconv>
#include <cmath>
#include <vector>

#include "enum_choice.hpp"
#include "hba/core/error.hpp"
#include "hba/io/pose_file.hpp"
#include "number_checks.hpp"

namespace hba::cli {

namespace {

// "" with the pose in `pose`, or what is wrong with `text`.
std::string readPose(const std::string& text, Pose& pose) {
  std::vector<double> values;
  std::size_t pos = 0;
  const auto separator = [](char c) { return c == ' ' || c == ',' || c == '\t'; };
  while (pos < text.size()) {
    while (pos < text.size() && separator(text[pos])) ++pos;
    std::size_t end = pos;
    while (end < text.size() && !separator(text[end])) ++end;
    if (end == pos) break;
    double value = 0.0;
    const auto [ptr, ec] = std::from_chars(text.data() + pos, text.data() + end, value);
    if (ec != std::errc() || ptr != text.data() + end || !std::isfinite(value)) {
      return "'" + text.substr(pos, end - pos) + "' is not a number";
    }
    values.push_back(value);
    pos = end;
  }
  if (values.size() == 7) {
    const Quat q(values[6], values[3], values[4], values[5]);  // given as qx qy qz qw
    if (q.norm() < 1e-3) return "the quaternion has zero length";
    pose = Pose(q, Vec3(values[0], values[1], values[2]));
    return "";
  }
  if (values.size() == 12) {
    Mat3 R;
    R << values[0], values[1], values[2], values[4], values[5], values[6], values[8], values[9], values[10];
    if ((R.transpose() * R - Mat3::Identity()).norm() > 1e-3 || R.determinant() < 0.0) {
      return "the 3x3 block is not a rotation";
    }
    pose = Pose(R, Vec3(values[3], values[7], values[11]));
    return "";
  }
  return "expected 7 numbers (tx ty tz qx qy qz qw) or 12 (row-major 3x4 [R|t]), found " +
         std::to_string(values.size());
}

}  // namespace

std::vector<Pose> readPosesFor(const io::Dataset& dataset, const std::filesystem::path& path) {
  std::vector<Pose> poses = io::readPoses(path).poses;
  if (poses.size() != dataset.size()) {
    failAt(path, std::to_string(poses.size()) + " poses for " + std::to_string(dataset.size()) + " scans");
  }
  return poses;
}

std::string folderName(const std::filesystem::path& folder) {
  const std::filesystem::path path = std::filesystem::absolute(folder).lexically_normal();
  return (path.has_filename() ? path.filename() : path.parent_path().filename()).string();
}

Pose parsePoseArgument(const std::string& text, const std::string& flag) {
  Pose pose;
  const std::string problem = readPose(text, pose);
  if (!problem.empty()) throw Error(flag + ": " + problem);
  return pose;
}

void DatasetArgs::addTo(CLI::App* command) {
  command
      ->add_option("DIR", dir,
                   "Dataset folder (HBA, scans+trajectory, or KITTI layout) or a recording (ROS 1 bag, MCAP, "
                   ".db3, rosbag2 folder)")
      ->required();
  command->add_option("--scans", scans, "Folder of scans (overrides detection)");
  command->add_option("--poses", poses, "Trajectory file (overrides detection)");
  command->add_option("--format", format, "Format of the --poses file")->check(oneOf<io::PoseFormat>());
  command->add_option("--times", times, "Timestamps, one per scan and line (seconds)");
  auto* conventions = command->add_option_group(
      "Conventions",
      "When the input is not sensor-to-world poses of sensor-frame scans (docs/io_datasets.md)");
  conventions->add_flag("--invert-poses", invert_poses, "The poses map world to sensor: invert them");
  conventions
      ->add_option("--extrinsic", extrinsic,
                   "The poses are of another body (IMU, base): T_body_sensor as "
                   "'tx ty tz qx qy qz qw' or 12 numbers row-major [R|t]")
      ->check(CLI::Validator(
          [](const std::string& text) {
            Pose pose;
            return readPose(text, pose);
          },
          "POSE"));
  conventions->add_option("--calib", calibration,
                          "KITTI calib.txt: the poses are of camera 0, turned into LiDAR poses with Tr");
  conventions->add_flag("--scans-in-world", scans_in_world,
                        "The scans were saved in the world frame (moved by their pose)");
  conventions
      ->add_option("--deskew", deskew,
                   "Raw sweeps whose points carry times (t, time, timestamp, offset_time): auto deskews "
                   "them when the trajectory follows the motion within a sweep; on, off")
      ->check(oneOf<io::DeskewMode>())
      ->capture_default_str();
  auto* topics = command->add_option_group("Recordings", "When DIR is a recording (docs/recordings.md)");
  topics->add_option(
      "--cloud-topic", recording.cloud_topic,
      "The point cloud topic: sensor_msgs/PointCloud2 or livox_ros_driver/CustomMsg (default: the only one)");
  topics->add_option("--pose-topic", recording.pose_topic,
                     "The trajectory topic: nav_msgs/Odometry, geometry_msgs/PoseStamped, "
                     "PoseWithCovarianceStamped or nav_msgs/Path (default: the only one)");
  topics
      ->add_option("--tf-frames", tf_frames,
                   "With --pose-topic /tf: PARENT:CHILD, the frames whose transforms are the trajectory "
                   "(default: the only pair)")
      ->check(CLI::Validator(
          [](const std::string& text) {
            const std::size_t colon = text.find(':');
            return colon == std::string::npos || colon == 0 || colon + 1 == text.size()
                       ? std::string("must be PARENT:CHILD, e.g. odom:base_link")
                       : std::string();
          },
          "PARENT:CHILD"));
  topics
      ->add_option("--time-offset", recording.time_offset,
                   "Seconds added to each scan's stamp before its pose is looked up")
      ->check(realIn(-1e6, 1e6, "s"))
      ->capture_default_str();
  topics
      ->add_option(
          "--keyframe-distance", recording.keyframe_distance,
          "Keep a scan only this far (m) from the last kept one, or turned --keyframe-angle (0: all)")
      ->check(realIn(0, 1000, "m"))
      ->capture_default_str();
  topics
      ->add_option(
          "--keyframe-angle", recording.keyframe_angle,
          "Keep a scan turned this much (deg) from the last kept one, or --keyframe-distance away (0: all)")
      ->check(realIn(0, 180, "deg"))
      ->capture_default_str();
}

io::Dataset DatasetArgs::open() const {
  io::DatasetOverrides overrides;
  if (!scans.empty()) overrides.scans_dir = scans;
  if (!poses.empty()) overrides.poses_file = poses;
  if (!format.empty()) overrides.pose_format = parseEnum<io::PoseFormat>(format);
  if (!times.empty()) overrides.times_file = times;
  overrides.invert_poses = invert_poses;
  if (!extrinsic.empty()) overrides.extrinsic = parsePoseArgument(extrinsic, "--extrinsic");
  if (!calibration.empty()) overrides.calibration = calibration;
  overrides.scans_in_world = scans_in_world;
  overrides.recording = recording;
  if (!tf_frames.empty()) {
    overrides.recording.tf_parent = tf_frames.substr(0, tf_frames.find(':'));
    overrides.recording.tf_child = tf_frames.substr(tf_frames.find(':') + 1);
  }
  overrides.deskew = parseEnum<io::DeskewMode>(deskew);
  io::Dataset dataset = io::Dataset::open(dir, overrides);
  // Say what discovery chose and noticed, so a wrong guess is visible before a long run.
  spdlog::debug("dataset {}: layout {}, {} scans in {}, poses {} ({})", dataset.root().string(),
                dataset.layout(), dataset.size(), dataset.scansDir().string(), dataset.posesFile().string(),
                hba::toString(dataset.poseFormat()));
  for (const io::DatasetNote& note : dataset.notes()) {
    if (note.level == io::DatasetNote::Level::Warning) {
      spdlog::warn("{}", note.text);
    } else {
      spdlog::info("{}", note.text);
    }
  }
  return dataset;
}

}  // namespace hba::cli
