// The recordings: ROS 1 bags, ROS 2 sqlite3 bags (.db3), rosbag2 folders'
// metadata.yaml, and the ROS messages inside them, read as `hba info`,
// `extract` and `optimize` read them.
#include <unistd.h>

#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <memory>
#include <string>
#include <system_error>
#include <vector>

#include "harness.hpp"
#include "harness_checks.hpp"
#include "hba/rec/recording.hpp"
#include "hba/rec/ros_messages.hpp"
#include "rec/message_store.hpp"

namespace hba::fuzz {
namespace fs = std::filesystem;

namespace {

// Each topic's first messages are decoded alone: enough for every path
// through the decoders, and a fuzzed index of thousands of entries does not
// make one input take seconds.
constexpr std::size_t kMessagesPerTopic = 64;

std::vector<std::uint8_t> readBytes(const fs::path& input) {
  std::ifstream in(input, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void checkPoses(const std::vector<rec::StampedPose>& poses) {
  for (const rec::StampedPose& pose : poses) checkRotation(pose.pose.q);
}

// A trajectory message's positions are finite (a NaN is refused when read).
void checkTrajectory(const std::vector<rec::StampedPose>& poses) {
  checkPoses(poses);
  for (const rec::StampedPose& pose : poses) {
    if (!pose.pose.t.allFinite()) std::abort();
  }
}

// One message decoded as its type says, as the recording does.
void decodeMessage(const std::string& type, const std::vector<std::uint8_t>& message,
                   rec::Serialization serialization) {
  const std::string what = "fuzzed " + type;
  if (rec::isCloudType(type)) {
    rejectOnlyWithError([&] { rec::decodeCloudHeader(type, message, serialization, what); });
    rejectOnlyWithError([&] { checkCloud(rec::decodeCloud(type, message, serialization, what)); });
  } else if (rec::isTrajectoryType(type)) {
    rejectOnlyWithError([&] { checkTrajectory(rec::decodePoses(type, message, serialization, what)); });
  } else if (type == rec::kTfMessage) {
    rejectOnlyWithError([&] { checkPoses(rec::decodeTransforms(message, serialization, what)); });
  }
}

void readEveryTopic(const rec::MessageStore& store) {
  for (const rec::StoredChannel& channel : store.channels()) {
    const std::vector<rec::StoredMessage> messages = store.messages(channel.topic);
    for (std::size_t i = 0; i < messages.size() && i < kMessagesPerTopic; ++i) {
      rejectOnlyWithError(
          [&] { decodeMessage(channel.type, store.read(messages[i]), store.serialization()); });
    }
  }
}

void readAsRecording(const fs::path& input, const rec::RecordingOptions& options) {
  const rec::Recording recording = rec::Recording::open(input, options);
  const Trajectory& trajectory = recording.trajectory();
  if (trajectory.size() != trajectory.stamps.size() || recording.size() == 0) std::abort();
  for (const Pose& pose : trajectory.poses) checkRotation(pose.q);
  for (std::size_t i = 0; i < recording.size() && i < kMessagesPerTopic; ++i) {
    rejectOnlyWithError([&] { checkCloud(recording.loadScan(i)); });
  }
}

// The options a user gives where the defaults refuse (several cloud topics,
// a /tf trajectory), with keyframes: the first cloud topic, the first tf
// topic as the trajectory.
rec::RecordingOptions namedTopics(const rec::MessageStore& store) {
  rec::RecordingOptions options;
  for (const rec::StoredChannel& channel : store.channels()) {
    if (options.cloud_topic.empty() && rec::isCloudType(channel.type)) options.cloud_topic = channel.topic;
    if (options.pose_topic.empty() && channel.type == rec::kTfMessage && channel.topic != "/tf_static")
      options.pose_topic = channel.topic;
  }
  options.keyframe_distance = 0.5;
  return options;
}

// A private folder in memory (/dev/shm) holding a rosbag2 recording's
// storage file, where each fuzzed metadata.yaml is put beside it.
class Rosbag2Folder {
 public:
  Rosbag2Folder() {
    std::error_code error;
    const fs::path shm = "/dev/shm";
    const fs::path base = fs::is_directory(shm, error) ? shm : fs::temp_directory_path();
    folder_ = base / ("hba_fuzz_rosbag2_" + std::to_string(::getpid()));
    fs::create_directories(folder_);
    fs::copy_file(HBA_FUZZ_DIR "/fixtures/run_0.db3", folder_ / "run_0.db3",
                  fs::copy_options::overwrite_existing);
  }
  ~Rosbag2Folder() {
    std::error_code error;
    fs::remove_all(folder_, error);
  }
  Rosbag2Folder(const Rosbag2Folder&) = delete;
  Rosbag2Folder& operator=(const Rosbag2Folder&) = delete;

  const fs::path& holding(const std::vector<std::uint8_t>& metadata) {
    std::ofstream out(folder_ / "metadata.yaml", std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(metadata.data()), static_cast<std::streamsize>(metadata.size()));
    if (!out) std::abort();  // the harness itself cannot work: stop loudly
    return folder_;
  }

 private:
  fs::path folder_;
};

}  // namespace

void feedRecordingFile(const fs::path& input) {
  rec::RecordingOptions named;
  rejectOnlyWithError([&] {
    const std::unique_ptr<rec::MessageStore> store = rec::openMessageStore(input);
    readEveryTopic(*store);
    named = namedTopics(*store);
  });
  rejectOnlyWithError([&] { readAsRecording(input, {}); });
  if (!named.cloud_topic.empty()) rejectOnlyWithError([&] { readAsRecording(input, named); });
}

void feedRos1Bag(const fs::path& input) { feedRecordingFile(input); }
void feedDb3(const fs::path& input) { feedRecordingFile(input); }

void feedRosbag2Metadata(const fs::path& input) {
  static Rosbag2Folder folder;
  feedRecordingFile(folder.holding(readBytes(input)));
}

// The types a recording's messages are decoded as, each in either
// serialization: the first byte, modulo 16, is 2 * type + (0 ROS 1, 1 CDR)
// (fuzz/make_recording_seeds.py writes the seeds so).
void feedRosMessage(const fs::path& input) {
  static const char* const kTypes[] = {rec::kPointCloud2,
                                       rec::kLivoxCustom,
                                       "livox_ros_driver2/CustomMsg",
                                       "nav_msgs/Odometry",
                                       "geometry_msgs/PoseStamped",
                                       "geometry_msgs/PoseWithCovarianceStamped",
                                       "nav_msgs/Path",
                                       rec::kTfMessage};
  constexpr std::size_t kKinds = 2 * (sizeof(kTypes) / sizeof(kTypes[0]));
  std::vector<std::uint8_t> bytes = readBytes(input);
  if (bytes.empty()) return;
  const std::size_t kind = bytes.front() % kKinds;
  bytes.erase(bytes.begin());
  decodeMessage(kTypes[kind / 2], bytes, kind % 2 == 0 ? rec::Serialization::Ros1 : rec::Serialization::Cdr);
}
}  // namespace hba::fuzz
