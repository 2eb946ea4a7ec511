#pragma once
// A recording (a ROS 1 bag, an MCAP file, a ROS 2 sqlite3 bag or a rosbag2
// folder) as a sequence hba can optimize: the scans
// of one point cloud topic, each with the pose of one trajectory topic
// interpolated at the scan's stamp. Topics are chosen automatically when
// only one of each kind is there; otherwise the caller names them.
// Opening reads every cloud message's header once (their stamps) and the
// whole trajectory; scans are then read one at a time, on demand.
#include <cstddef>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "hba/core/point_cloud.hpp"
#include "hba/core/pose.hpp"

namespace hba::rec {

class MessageStore;  // message_store.hpp (internal)
struct StampedPose;  // ros_messages.hpp

struct RecordingOptions {
  std::string cloud_topic;  // empty: the only PointCloud2 topic
  std::string pose_topic;   // empty: the only trajectory topic
  // With pose_topic a tf2_msgs/TFMessage topic (/tf): the transforms that
  // place `tf_child` in `tf_parent` are the trajectory (empty: the only
  // pair the topic holds).
  std::string tf_parent, tf_child;
  double time_offset = 0.0;  // s, added to every scan's stamp before its pose is looked up
  // Keyframes: a scan is kept when it is this far (m) or turned this much
  // (deg) from the last kept one; 0 and 0 keep every scan.
  double keyframe_distance = 0.0;
  double keyframe_angle = 0.0;
  // A trajectory with stamps from elsewhere (an odometry's pose file: the
  // body's or the clouds' frame, stamps on the recording's clock) instead
  // of a topic: each scan's pose is interpolated from it alike.
  std::optional<Trajectory> poses;
  std::string poses_name;  // what it is called in messages (its file)

  bool keepsEveryScan() const { return !(keyframe_distance > 0.0) && !(keyframe_angle > 0.0); }
  bool isDefault() const {
    return cloud_topic.empty() && pose_topic.empty() && tf_parent.empty() && tf_child.empty() &&
           time_offset == 0.0 && keepsEveryScan();
  }
};

struct RecordingTopic {
  std::string topic;
  std::string type;
  std::size_t messages = 0;
};

class Ros1Bag;

class Recording {
 public:
  // Throws hba::Error naming the file: not a recording hba reads, no cloud
  // or trajectory topic (or several, listed), a trajectory that covers no scan.
  static Recording open(const std::filesystem::path& path, const RecordingOptions& options = {});
  ~Recording();
  Recording(Recording&&) noexcept;
  Recording& operator=(Recording&&) noexcept;

  const std::filesystem::path& path() const { return path_; }
  const std::string& format() const { return format_; }  // "ROS 1 bag", "MCAP", ...
  const std::vector<RecordingTopic>& topics() const { return topics_; }
  const std::string& cloudTopic() const { return cloud_topic_; }
  // "sensor_msgs/PointCloud2" or "livox_ros_driver/CustomMsg" (or driver 2's).
  const std::string& cloudType() const { return cloud_type_; }
  // The trajectory topic, or the name of the trajectory given instead.
  const std::string& poseTopic() const { return pose_topic_; }
  const std::string& cloudFrame() const { return cloud_frame_; }
  // T_body_cloud from /tf_static, when the poses place another frame (the
  // body, an IMU) than the clouds' and the recording says how they sit.
  const std::optional<Pose>& staticExtrinsic() const { return extrinsic_; }
  // Why /tf_static cannot join the clouds' frame to the poses' (its
  // transforms form a cycle), or "": the caller refuses the recording
  // unless it is given the extrinsic itself.
  const std::string& staticFrameProblem() const { return static_problem_; }
  const std::string& poseFrame() const { return pose_frame_; }
  // The first cloud's field names, as recorded ("x y z intensity ...").
  const std::vector<std::string>& cloudFields() const { return cloud_fields_; }

  // The trajectory's own poses and stamps (the body's, on the trajectory's
  // clock, which the scans' stamps meet after --time-offset): the scans'
  // poses and the motion within a sweep are read from it.
  const Trajectory& recordedTrajectory() const { return recorded_; }
  double timeOffset() const { return time_offset_; }

  // The scans kept (those the trajectory covers), their stamps and poses.
  std::size_t size() const { return trajectory_.size(); }
  const Trajectory& trajectory() const { return trajectory_; }
  std::size_t cloudMessages() const { return cloud_messages_; }
  // Every scan the trajectory covers, kept as a keyframe or not: stamps and
  // poses (the same as trajectory() when every scan is kept).
  const Trajectory& coveredScans() const { return covered_; }
  // Sentences for the log: what was chosen, what was dropped and why.
  const std::vector<std::string>& notes() const { return notes_; }
  const std::vector<std::string>& warnings() const { return warnings_; }

  // Scan i in its sensor frame. Thread-safe. Throws hba::Error.
  PointCloud loadScan(std::size_t i) const;

 private:
  Recording();
  struct Clouds;
  // The steps of open().
  void placeClouds(const MessageStore& bag, const RecordingOptions& options,
                   const std::vector<StampedPose>& trajectory);
  void keepKeyframes(const RecordingOptions& options, const std::vector<StampedPose>& trajectory);
  void joinFrames(const MessageStore& bag, const std::string& pose_frame);
  std::filesystem::path path_;
  std::string format_, cloud_topic_, cloud_type_, pose_topic_, cloud_frame_;
  std::vector<RecordingTopic> topics_;
  std::vector<std::string> cloud_fields_;
  std::string pose_frame_;
  std::optional<Pose> extrinsic_;
  std::string static_problem_;
  Trajectory trajectory_, recorded_, covered_;
  double time_offset_ = 0.0;
  std::size_t cloud_messages_ = 0;
  std::vector<std::string> notes_, warnings_;
  std::unique_ptr<Clouds> clouds_;
};

// The topics as a table for messages: one line per topic, its type and count.
std::string describeTopics(const std::vector<RecordingTopic>& topics);

// True when `path` is a file hba reads as a recording (a bag file or a rosbag2 folder).
bool isRecording(const std::filesystem::path& path);

}  // namespace hba::rec
