#pragma once
// What a recording's container gives the recording: its channels (topic and
// type) and its messages' bytes, one at a time. A ROS 1 bag and an MCAP file
// each make one; the recording does not see which.
#include <cstdint>
#include <filesystem>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "hba/rec/ros1_bag.hpp"
#include "hba/rec/ros_messages.hpp"

namespace hba::rec {

struct StoredChannel {
  std::uint32_t id = 0;
  std::string topic;
  std::string type;  // as ROS 1 names it: "sensor_msgs/PointCloud2"
  std::size_t messages = 0;
};

// Where a message lies: in a chunk (its file offset) at an offset of the
// decompressed records, or (chunk == kNoChunk) at a file offset.
struct StoredMessage {
  static constexpr std::uint64_t kNoChunk = std::numeric_limits<std::uint64_t>::max();
  std::uint64_t chunk = kNoChunk;
  std::uint64_t offset = 0;
  std::uint32_t channel = 0;
  double time = 0.0;  // when it was recorded, s
};

class MessageStore {
 public:
  virtual ~MessageStore() = default;
  virtual const std::filesystem::path& path() const = 0;
  virtual std::string format() const = 0;  // "ROS 1 bag", "MCAP"
  virtual Serialization serialization() const = 0;
  virtual const std::vector<StoredChannel>& channels() const = 0;
  // The messages of the channels of `topic`, by record time.
  virtual std::vector<StoredMessage> messages(const std::string& topic) const = 0;
  // A message's serialized bytes. Thread-safe.
  virtual std::vector<std::uint8_t> read(const StoredMessage& message) const = 0;
  // What opening found that the user should know (the recording shows them).
  virtual std::vector<std::string> warnings() const { return {}; }
};

// The container at `path`, a file told by its first bytes or a rosbag2
// folder (metadata.yaml); throws hba::Error for one hba does not read.
std::unique_ptr<MessageStore> openMessageStore(const std::filesystem::path& path);
bool looksLikeRecordingFile(const std::filesystem::path& path);
bool looksLikeRosbag2Folder(const std::filesystem::path& path);

bool looksLikeMcap(const std::filesystem::path& path);
bool looksLikeSqlite(const std::filesystem::path& path);
std::unique_ptr<MessageStore> openMcap(const std::filesystem::path& path);
std::unique_ptr<MessageStore> openSqlite(const std::filesystem::path& path);
std::unique_ptr<MessageStore> openRos1Store(const std::filesystem::path& path);

}  // namespace hba::rec
