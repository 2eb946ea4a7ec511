#pragma once
// A ROS 1 bag (format 2.0) read without ROS: its connections (topic, type,
// message definition) and its index, read at open from the end of the file;
// then any message by its place, one chunk decompressed at a time (none,
// lz4 or bz2). Nothing else of the bag is held in memory.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

namespace hba::rec {

struct Ros1Connection {
  std::uint32_t id = 0;
  std::string topic;
  std::string type;  // "sensor_msgs/PointCloud2"
  std::string md5sum;
  std::string definition;  // the message definition the recorder wrote
};

// Where one message lies: its chunk, its offset in the decompressed chunk,
// and the time it was recorded (s; not the message's own stamp).
struct Ros1MessageRef {
  std::uint64_t chunk_pos = 0;
  std::uint32_t offset = 0;
  std::uint32_t connection = 0;
  double record_time = 0.0;
};

class Ros1Bag {
 public:
  // Reads the bag's header and index. Throws hba::Error naming the file: not
  // a ROS 1 bag, an unindexed or truncated bag (with what to do about it).
  static Ros1Bag open(const std::filesystem::path& path);
  ~Ros1Bag();
  Ros1Bag(Ros1Bag&&) noexcept;
  Ros1Bag& operator=(Ros1Bag&&) noexcept;

  const std::filesystem::path& path() const { return path_; }
  const std::vector<Ros1Connection>& connections() const { return connections_; }
  // The messages of these connections (all when empty), by record time.
  std::vector<Ros1MessageRef> messages(const std::vector<std::uint32_t>& connections = {}) const;
  std::size_t messageCount(std::uint32_t connection) const;
  // The serialized message. Thread-safe; the last chunk read is kept, so
  // reading messages in order decompresses each chunk once.
  std::vector<std::uint8_t> read(const Ros1MessageRef& message) const;

 private:
  Ros1Bag();
  struct ChunkCache;
  std::filesystem::path path_;
  std::vector<Ros1Connection> connections_;
  std::vector<Ros1MessageRef> index_;  // every message, by record time
  std::unique_ptr<ChunkCache> cache_;
};

// True when the file starts as a ROS 1 bag does ("#ROSBAG V2.0").
bool looksLikeRos1Bag(const std::filesystem::path& path);

}  // namespace hba::rec
