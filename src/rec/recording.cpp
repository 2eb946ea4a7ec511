#include "hba/rec/recording.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>

#include "hba/core/error.hpp"
#include "hba/rec/ros_messages.hpp"
#include "message_store.hpp"

namespace hba::rec {
namespace fs = std::filesystem;

struct Recording::Clouds {
  std::unique_ptr<MessageStore> store;
  std::vector<StoredMessage> kept;  // scan i's message
};

namespace {

// The topics of one kind; `wanted` names one, else the only one.
std::string chooseTopic(const fs::path& path, const std::vector<RecordingTopic>& topics,
                        bool (*of_kind)(const std::string&), const std::string& wanted,
                        const std::string& kind, const std::string& flag) {
  std::vector<RecordingTopic> candidates;
  for (const RecordingTopic& topic : topics) {
    if (of_kind(topic.type)) candidates.push_back(topic);
  }
  if (!wanted.empty()) {
    for (const RecordingTopic& topic : topics) {
      if (topic.topic != wanted) continue;
      if (!of_kind(topic.type)) {
        failAt(path, flag + " " + wanted + " is a " + topic.type + ", not a " + kind + ". Its topics:\n" +
                         describeTopics(topics));
      }
      return wanted;
    }
    failAt(path, "no topic " + wanted + " (" + flag + "). Its topics:\n" + describeTopics(topics));
  }
  if (candidates.empty()) failAt(path, "no " + kind + " topic. Its topics:\n" + describeTopics(topics));
  if (candidates.size() > 1) {
    failAt(path, std::to_string(candidates.size()) + " " + kind + " topics: choose one with " + flag +
                     ". They are:\n" + describeTopics(candidates));
  }
  return candidates.front().topic;
}

bool isTfType(const std::string& type) { return type == kTfMessage; }

std::string typeOf(const MessageStore& store, const std::string& topic) {
  for (const StoredChannel& c : store.channels()) {
    if (c.topic == topic) return c.type;
  }
  return "";
}

// A pose of a trajectory and where it was read, for messages ("message 12").
struct SourcedPose {
  StampedPose pose;
  std::string origin;
};

// The trajectory's poses in the order recorded, which must be the order of
// their stamps: scans are paired with poses by stamp, so stamps that run
// backwards (a merged or re-stamped recording) are refused, as are two
// different poses at one stamp. A pose republished with its stamp is read
// once, with a note.
std::vector<StampedPose> inStampOrder(const fs::path& path, const std::string& name,
                                      std::vector<SourcedPose> poses, std::vector<std::string>& notes) {
  const std::string named = name.empty() ? "" : name + ": ";
  constexpr double kSamePose = 1e-6;  // m and rad: a republished pose, not another one
  std::vector<StampedPose> out;
  std::size_t repeats = 0;
  for (std::size_t i = 0; i < poses.size(); ++i) {
    if (i > 0) {
      const SourcedPose& before = poses[i - 1];
      const SourcedPose& now = poses[i];
      if (now.pose.stamp < before.pose.stamp) {
        failAt(path, fmt::format("{}the stamps run backwards at {}: {:.9f} s after {:.9f} s ({}); scans "
                                 "are paired with poses by stamp, so the trajectory cannot be read",
                                 named, now.origin, now.pose.stamp, before.pose.stamp, before.origin));
      }
      if (now.pose.stamp == before.pose.stamp) {
        const Pose step = relative(before.pose.pose, now.pose.pose);
        const double angle = Eigen::AngleAxisd(step.q).angle();
        if (step.t.norm() > kSamePose || angle > kSamePose) {
          failAt(path, fmt::format("{}{} and {} share the stamp {:.9f} s but place the body {:.6g} m and "
                                   "{:.6g} deg apart; a trajectory has one pose at a time",
                                   named, before.origin, now.origin, now.pose.stamp, step.t.norm(),
                                   angle * 180.0 / M_PI));
        }
        ++repeats;
        continue;
      }
    }
    out.push_back(poses[i].pose);
  }
  if (repeats > 0) {
    notes.push_back(fmt::format("{}: {} {} the stamp and pose of the one before (republished): read once",
                                name.empty() ? path.string() : name, repeats,
                                repeats == 1 ? "pose repeats" : "poses repeat"));
  }
  return out;
}

// The trajectory's poses by stamp: a Path's last message, or every message.
std::vector<StampedPose> readTrajectory(const MessageStore& store, const std::string& topic,
                                        std::vector<std::string>& notes) {
  const std::string type = typeOf(store, topic);
  std::vector<StoredMessage> messages = store.messages(topic);
  const bool path = type == "nav_msgs/Path" && !messages.empty();
  const std::size_t first = path ? messages.size() - 1 : 0;
  std::vector<SourcedPose> poses;
  for (std::size_t i = first; i < messages.size(); ++i) {
    const std::string what =
        fmt::format("{}: {} message {} at {:.3f} s", store.path().string(), topic, i, messages[i].time);
    std::vector<StampedPose> decoded =
        decodePoses(type, store.read(messages[i]), store.serialization(), what);
    for (std::size_t k = 0; k < decoded.size(); ++k) {
      poses.push_back({std::move(decoded[k]),
                       path ? fmt::format("poses[{}] of message {}", k, i) : fmt::format("message {}", i)});
    }
  }
  return inStampOrder(store.path(), topic, std::move(poses), notes);
}

// A tf frame's name without ROS 1's optional leading slash ("/base" is "base").
std::string frameName(const std::string& frame) {
  return !frame.empty() && frame.front() == '/' ? frame.substr(1) : frame;
}

// Every transform a tf2_msgs/TFMessage topic holds, frames named as tf names
// them, with the message each came from.
std::vector<SourcedPose> readTransforms(const MessageStore& store, const std::string& topic) {
  std::vector<SourcedPose> transforms;
  const std::vector<StoredMessage> messages = store.messages(topic);
  for (std::size_t i = 0; i < messages.size(); ++i) {
    const std::string what =
        fmt::format("{}: {} message {} at {:.3f} s", store.path().string(), topic, i, messages[i].time);
    std::vector<StampedPose> decoded = decodeTransforms(store.read(messages[i]), store.serialization(), what);
    for (std::size_t k = 0; k < decoded.size(); ++k) {
      StampedPose& t = decoded[k];
      t.frame_id = frameName(t.frame_id);
      t.child_frame_id = frameName(t.child_frame_id);
      transforms.push_back({std::move(t), fmt::format("transforms[{}] of message {}", k, i)});
    }
  }
  return transforms;
}

// The transforms of a /tf topic that place `child` in `parent` (both empty:
// the only pair there is), in order of stamp.
std::vector<StampedPose> readTfTrajectory(const MessageStore& store, const std::string& topic,
                                          const RecordingOptions& options, std::vector<std::string>& notes) {
  std::map<std::pair<std::string, std::string>, std::vector<SourcedPose>> by_pair;
  for (SourcedPose& t : readTransforms(store, topic))
    by_pair[{t.pose.frame_id, t.pose.child_frame_id}].push_back(std::move(t));
  std::string pairs;
  for (const auto& [pair, poses] : by_pair) {
    pairs += fmt::format("\n  {} -> {}  {} transforms", pair.first, pair.second, poses.size());
  }
  const bool named = !options.tf_parent.empty() || !options.tf_child.empty();
  const auto checked = [&](const std::pair<std::string, std::string>& pair, std::vector<SourcedPose> poses) {
    return inStampOrder(store.path(), fmt::format("{} ({} in {})", topic, pair.second, pair.first),
                        std::move(poses), notes);
  };
  if (!named && by_pair.size() == 1) return checked(by_pair.begin()->first, by_pair.begin()->second);
  if (!named) {
    failAt(store.path(), fmt::format("{} holds {} pairs of frames: choose one with --tf-frames PARENT:CHILD. "
                                     "They are:{}",
                                     topic, by_pair.size(), pairs.empty() ? "\n  (none)" : pairs));
  }
  const auto found = by_pair.find({frameName(options.tf_parent), frameName(options.tf_child)});
  if (found == by_pair.end()) {
    failAt(store.path(),
           fmt::format("{} places no {} in {} (--tf-frames). Its pairs:{}", topic, options.tf_child,
                       options.tf_parent, pairs.empty() ? "\n  (none)" : pairs));
  }
  return checked(found->first, found->second);
}

// The scans a keyframe apart: the first, then each as far or as turned
// from the last kept one as the options say.
std::vector<std::size_t> keyframesOf(const std::vector<Pose>& poses, const RecordingOptions& options) {
  std::vector<std::size_t> kept;
  for (std::size_t i = 0; i < poses.size(); ++i) {
    if (!kept.empty()) {
      const Pose step = relative(poses[kept.back()], poses[i]);
      const double turn = Eigen::AngleAxisd(step.q).angle() * 180.0 / M_PI;
      const bool far = options.keyframe_distance > 0.0 && step.t.norm() >= options.keyframe_distance;
      const bool turned = options.keyframe_angle > 0.0 && turn >= options.keyframe_angle;
      if (!far && !turned) continue;
    }
    kept.push_back(i);
  }
  return kept;
}

// The scans stamped (within 1 us) where the trajectory has a pose.
std::vector<std::size_t> scansAt(const std::vector<double>& scan_stamps,
                                 const std::vector<StampedPose>& poses) {
  std::vector<std::size_t> scans;
  for (const StampedPose& pose : poses) {
    const auto at = std::lower_bound(scan_stamps.begin(), scan_stamps.end(), pose.stamp - 1e-6);
    if (at != scan_stamps.end() && *at <= pose.stamp + 1e-6)
      scans.push_back(static_cast<std::size_t>(at - scan_stamps.begin()));
  }
  return scans;
}

// T_from_to from the recording's /tf_static (frames as tf names them):
// `to` reached from `from` through the static transforms, either way up
// the tree; empty when they are not joined, or when the transforms form a
// cycle (`problem` then says which frames, and whether they disagree).
std::optional<Pose> staticTransform(const MessageStore& store, const std::string& from, const std::string& to,
                                    std::string& problem) {
  std::map<std::string, std::pair<std::string, Pose>> parent_of;  // child -> (parent, T_parent_child)
  for (const StoredChannel& channel : store.channels()) {
    if (channel.topic != "/tf_static" || channel.type != kTfMessage) continue;
    for (const SourcedPose& t : readTransforms(store, channel.topic))
      parent_of[t.pose.child_frame_id] = {t.pose.frame_id, t.pose.pose};
  }
  // Each frame's pose in its root's frame, along its chain of parents; a
  // chain that comes back to a frame has no root (tf2 refuses such a tree).
  const auto inRoot = [&parent_of, &problem](std::string frame, std::string& root) {
    Pose pose;
    std::vector<std::string> chain{frame};
    while (parent_of.count(frame)) {
      pose = parent_of.at(frame).second * pose;
      frame = parent_of.at(frame).first;
      const std::size_t seen =
          static_cast<std::size_t>(std::find(chain.begin(), chain.end(), frame) - chain.begin());
      chain.push_back(frame);
      if (seen + 1 == chain.size()) continue;
      // Round the cycle once: the identity when its transforms agree.
      Pose round;
      std::string names;
      for (std::size_t at = seen; at + 1 < chain.size(); ++at) {
        round = parent_of.at(chain[at]).second * round;
        names += (names.empty() ? "" : ", ") + chain[at] + " in " + chain[at + 1];
      }
      const double angle = Eigen::AngleAxisd(round.q).angle() * 180.0 / M_PI;
      const bool agree = round.t.norm() < 1e-6 && angle < 1e-6;
      root.clear();
      if (!problem.empty()) return pose;  // found from the other frame already
      problem = fmt::format(
          "/tf_static's transforms form a cycle ({}){}: a tf tree has no cycles, so they cannot "
          "join frames",
          names,
          agree ? ""
                : fmt::format(" and contradict each other (going round moves {:.6g} m and turns {:.6g} deg)",
                              round.t.norm(), angle));
      return pose;
    }
    root = frame;
    return pose;
  };
  std::string root_from, root_to;
  const Pose from_in_root = inRoot(frameName(from), root_from);
  const Pose to_in_root = inRoot(frameName(to), root_to);
  if (!problem.empty() || root_from != root_to) return std::nullopt;
  return relative(from_in_root, to_in_root);
}

// The pose at `t` between the trajectory's poses, or false outside it.
bool poseAt(const Trajectory& trajectory, double t, Pose& pose) {
  constexpr double kEdge = 1e-3;  // s: a scan stamped this close to an end takes the end's pose
  if (trajectory.empty() || t < trajectory.stamps.front() - kEdge || t > trajectory.stamps.back() + kEdge)
    return false;
  pose = poseAtTime(trajectory, std::clamp(t, trajectory.stamps.front(), trajectory.stamps.back()));
  return true;
}

}  // namespace

std::string describeTopics(const std::vector<RecordingTopic>& topics) {
  std::size_t width = 0, type_width = 0;
  for (const RecordingTopic& topic : topics) {
    width = std::max(width, topic.topic.size());
    type_width = std::max(type_width, topic.type.size());
  }
  std::string text;
  for (const RecordingTopic& topic : topics) {
    text += fmt::format("  {:<{}}  {:<{}}  {} messages\n", topic.topic, width, topic.type, type_width,
                        topic.messages);
  }
  if (!text.empty()) text.pop_back();
  return text.empty() ? "  (none)" : text;
}

bool isRecording(const fs::path& path) {
  return looksLikeRecordingFile(path) || looksLikeRosbag2Folder(path);
}

Recording::Recording() = default;
Recording::~Recording() = default;
Recording::Recording(Recording&&) noexcept = default;
Recording& Recording::operator=(Recording&&) noexcept = default;

namespace {

// The trajectory the options name (a topic, /tf or a given trajectory):
// its poses in order of stamp, what it is called, and where they came from.
struct PoseSource {
  std::vector<StampedPose> poses;
  std::string name;
  std::vector<std::string> notes;
};

PoseSource readPoseSource(const MessageStore& bag, const std::vector<RecordingTopic>& topics,
                          const std::string& cloud_topic, const RecordingOptions& options) {
  PoseSource source;
  if (options.poses) {
    source.name = options.poses_name;
    std::vector<SourcedPose> poses;
    for (std::size_t i = 0; i < options.poses->size() && i < options.poses->stamps.size(); ++i) {
      poses.push_back(
          {{options.poses->stamps[i], options.poses->poses[i], "", ""}, fmt::format("pose {}", i)});
    }
    source.notes.push_back("scans from " + cloud_topic + ", poses from " + source.name);
    source.poses = inStampOrder(source.name, "", std::move(poses), source.notes);
    return source;
  }
  // A /tf topic is a trajectory only when named: most recordings hold one.
  const bool tf = typeOf(bag, options.pose_topic) == kTfMessage;
  source.name = chooseTopic(
      bag.path(), topics, tf ? &isTfType : &isTrajectoryType, options.pose_topic,
      "trajectory (nav_msgs/Odometry, geometry_msgs/PoseStamped, PoseWithCovarianceStamped, nav_msgs/Path)",
      "--pose-topic");
  if (tf) {
    std::vector<std::string> notes;
    source.poses = readTfTrajectory(bag, source.name, options, notes);
    if (!source.poses.empty()) {
      source.notes.push_back(fmt::format("scans from {}, poses from {}: {} in {}", cloud_topic, source.name,
                                         source.poses.front().child_frame_id, source.poses.front().frame_id));
    }
    source.notes.insert(source.notes.end(), notes.begin(), notes.end());
    return source;
  }
  if (!options.tf_parent.empty() || !options.tf_child.empty()) {
    failAt(bag.path(), "--tf-frames is for a tf2_msgs/TFMessage trajectory: give --pose-topic /tf");
  }
  source.notes.push_back("scans from " + cloud_topic + ", poses from " + source.name + " (" +
                         typeOf(bag, source.name) + ")");
  source.poses = readTrajectory(bag, source.name, source.notes);
  return source;
}

}  // namespace

Recording Recording::open(const fs::path& path, const RecordingOptions& options) {
  Recording recording;
  recording.path_ = path;
  recording.clouds_ = std::make_unique<Clouds>(Clouds{openMessageStore(path), {}});
  const MessageStore& bag = *recording.clouds_->store;
  recording.format_ = bag.format();
  recording.warnings_ = bag.warnings();

  std::map<std::string, RecordingTopic> by_topic;
  for (const StoredChannel& c : bag.channels()) {
    RecordingTopic& topic = by_topic[c.topic];
    topic.topic = c.topic;
    topic.type = c.type;
    topic.messages += c.messages;
  }
  for (auto& entry : by_topic) recording.topics_.push_back(entry.second);

  recording.cloud_topic_ =
      chooseTopic(path, recording.topics_, &isCloudType, options.cloud_topic,
                  "point cloud (sensor_msgs/PointCloud2, livox_ros_driver/CustomMsg)", "--cloud-topic");
  recording.cloud_type_ = typeOf(bag, recording.cloud_topic_);
  PoseSource source = readPoseSource(bag, recording.topics_, recording.cloud_topic_, options);
  recording.pose_topic_ = source.name;
  recording.notes_.insert(recording.notes_.end(), source.notes.begin(), source.notes.end());
  const std::vector<StampedPose> trajectory = std::move(source.poses);
  if (trajectory.empty()) failAt(path, recording.pose_topic_ + " holds no pose");
  recording.time_offset_ = options.time_offset;
  for (const StampedPose& pose : trajectory) {
    recording.recorded_.poses.push_back(pose.pose);
    recording.recorded_.stamps.push_back(pose.stamp);
  }

  recording.placeClouds(bag, options, trajectory);
  if (!options.keepsEveryScan()) recording.keepKeyframes(options, trajectory);
  recording.joinFrames(bag, trajectory.front().child_frame_id);
  return recording;
}

// Every cloud's own stamp, and its pose there: those the trajectory covers
// are kept.
void Recording::placeClouds(const MessageStore& bag, const RecordingOptions& options,
                            const std::vector<StampedPose>& trajectory) {
  const std::vector<StoredMessage> clouds = bag.messages(cloud_topic_);
  cloud_messages_ = clouds.size();
  std::vector<double> dropped;
  std::vector<std::pair<double, StoredMessage>> stamped;
  double previous = 0.0;
  for (std::size_t i = 0; i < clouds.size(); ++i) {
    const StoredMessage& message = clouds[i];
    const std::string what =
        fmt::format("{}: {} message {} at {:.3f} s", path_.string(), cloud_topic_, i, message.time);
    const CloudHeader header = decodeCloudHeader(cloud_type_, bag.read(message), bag.serialization(), what);
    if (stamped.empty()) {
      cloud_frame_ = header.frame_id;
      cloud_fields_ = header.fields;
    } else if (header.stamp < previous) {
      // Each scan is paired with the pose at its stamp: stamps out of order
      // mean a merged or re-stamped recording, whose pairing cannot be trusted.
      failAt(path_,
             fmt::format("{}: the stamps run backwards at message {}: {:.9f} s after {:.9f} s (message "
                         "{}); scans are paired with poses by stamp, so the clouds cannot be read",
                         cloud_topic_, i, header.stamp, previous, i - 1));
    }
    previous = header.stamp;
    stamped.emplace_back(header.stamp + options.time_offset, message);
  }
  for (const auto& [stamp, message] : stamped) {
    Pose pose;
    if (!poseAt(recorded_, stamp, pose)) {
      dropped.push_back(stamp);
      continue;
    }
    trajectory_.poses.push_back(pose);
    trajectory_.stamps.push_back(stamp);
    clouds_->kept.push_back(message);
  }
  const std::string span =
      fmt::format("{:.3f} to {:.3f} s", trajectory.front().stamp, trajectory.back().stamp);
  if (trajectory_.empty()) {
    failAt(path_, fmt::format("{} covers none of the {} scans of {} (poses {}, scans {})", pose_topic_,
                              clouds.size(), cloud_topic_, span,
                              stamped.empty() ? std::string("none")
                                              : fmt::format("{:.3f} to {:.3f} s", stamped.front().first,
                                                            stamped.back().first)));
  }
  if (!dropped.empty()) {
    warnings_.push_back(fmt::format("{} of {} scans lie outside the trajectory ({}) and are left out",
                                    dropped.size(), clouds.size(), span));
  }
  covered_ = trajectory_;
}

// Keyframes by distance and angle: the other scans are left out.
void Recording::keepKeyframes(const RecordingOptions& options, const std::vector<StampedPose>& trajectory) {
  // An earlier run's keyframe poses given back: its keyframes, not new ones
  // chosen by poses that moved since.
  std::vector<std::size_t> keyframes =
      options.poses ? scansAt(trajectory_.stamps, trajectory) : std::vector<std::size_t>{};
  if (keyframes.size() != trajectory.size()) keyframes = keyframesOf(trajectory_.poses, options);
  const std::size_t covered = trajectory_.size();
  Trajectory kept_trajectory;
  std::vector<StoredMessage> kept_messages;
  for (const std::size_t i : keyframes) {
    kept_trajectory.poses.push_back(trajectory_.poses[i]);
    kept_trajectory.stamps.push_back(trajectory_.stamps[i]);
    kept_messages.push_back(clouds_->kept[i]);
  }
  trajectory_ = std::move(kept_trajectory);
  clouds_->kept = std::move(kept_messages);
  std::string rule;
  if (options.keyframe_distance > 0.0) rule = fmt::format("every {} m", options.keyframe_distance);
  if (options.keyframe_angle > 0.0) {
    rule += fmt::format("{}every {} deg", rule.empty() ? "" : " or ", options.keyframe_angle);
  }
  notes_.push_back(
      fmt::format("{} of {} scans kept as keyframes (a new one {})", keyframes.size(), covered, rule));
}

// Clouds and poses in frames of other names are joined by /tf_static.
void Recording::joinFrames(const MessageStore& bag, const std::string& pose_frame) {
  pose_frame_ = pose_frame;
  if (!pose_frame.empty() && !cloud_frame_.empty() && frameName(pose_frame) != frameName(cloud_frame_)) {
    extrinsic_ = staticTransform(bag, pose_frame, cloud_frame_, static_problem_);
    if (!static_problem_.empty()) {
      static_problem_ = "the clouds are in frame '" + cloud_frame_ + "', the poses place '" + pose_frame +
                        "', and " + static_problem_;
    } else if (extrinsic_) {
      notes_.push_back("the clouds are in frame '" + cloud_frame_ + "', the poses place '" + pose_frame +
                       "': joined by /tf_static");
    } else {
      notes_.push_back("the clouds are in frame '" + cloud_frame_ + "', the poses place '" + pose_frame +
                       "', and /tf_static does not join them: read as the same frame "
                       "(give --extrinsic if they differ)");
    }
  }
}

PointCloud Recording::loadScan(std::size_t i) const {
  const StoredMessage& message = clouds_->kept.at(i);
  const std::string what =
      fmt::format("{}: scan {} ({} at {:.3f} s)", path_.string(), i, cloud_topic_, trajectory_.stamps.at(i));
  const std::vector<std::uint8_t> bytes = clouds_->store->read(message);
  return decodeCloud(cloud_type_, bytes, clouds_->store->serialization(), what);
}

}  // namespace hba::rec
