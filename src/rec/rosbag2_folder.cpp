// A rosbag2 folder: metadata.yaml names the storage files (sqlite3 or MCAP,
// one or several when the recording was split), read as one recording.
#include <yaml-cpp/yaml.h>

#include <algorithm>

#include "core/input_file.hpp"
#include "hba/core/error.hpp"
#include "message_store.hpp"

namespace hba::rec {
namespace fs = std::filesystem;

namespace {

// Several stores one after the other; channel ids carry their store's index.
class SplitStore : public MessageStore {
 public:
  SplitStore(fs::path folder, std::vector<std::unique_ptr<MessageStore>> parts)
      : folder_(std::move(folder)), parts_(std::move(parts)) {
    if (parts_.size() > kMostParts) {
      failAt(folder_, "names " + std::to_string(parts_.size()) + " storage files; hba reads at most " +
                          std::to_string(kMostParts) + " in one folder");
    }
    for (std::size_t k = 0; k < parts_.size(); ++k) {
      for (StoredChannel channel : parts_[k]->channels()) {
        // The id shares 32 bits with the part's index (see idOf).
        if (channel.id >= kPart) {
          failAt(parts_[k]->path(), "topic id " + std::to_string(channel.id) + " is beyond " +
                                        std::to_string(kPart - 1) +
                                        ", the largest hba reads in a split recording");
        }
        channel.id = idOf(k, channel.id);
        channels_.push_back(channel);
      }
    }
  }
  const fs::path& path() const override { return folder_; }
  std::string format() const override { return "rosbag2 folder of " + parts_.front()->format() + "s"; }
  Serialization serialization() const override { return parts_.front()->serialization(); }
  const std::vector<StoredChannel>& channels() const override { return channels_; }
  std::vector<StoredMessage> messages(const std::string& topic) const override {
    std::vector<StoredMessage> out;
    for (std::size_t k = 0; k < parts_.size(); ++k) {
      for (StoredMessage message : parts_[k]->messages(topic)) {
        message.channel = idOf(k, message.channel);
        out.push_back(message);
      }
    }
    std::stable_sort(out.begin(), out.end(),
                     [](const StoredMessage& a, const StoredMessage& b) { return a.time < b.time; });
    return out;
  }
  std::vector<std::uint8_t> read(const StoredMessage& message) const override {
    StoredMessage inner = message;
    inner.channel = message.channel % kPart;
    return parts_.at(message.channel / kPart)->read(inner);
  }

 private:
  static constexpr std::uint32_t kPart = 1u << 20;
  static constexpr std::size_t kMostParts = 4096;  // 4096 x 2^20 ids fill 32 bits
  static std::uint32_t idOf(std::size_t part, std::uint32_t id) {
    return static_cast<std::uint32_t>(part) * kPart + id;
  }
  fs::path folder_;
  std::vector<std::unique_ptr<MessageStore>> parts_;
  std::vector<StoredChannel> channels_;
};

std::unique_ptr<MessageStore> openFile(const fs::path& path) {
  // Before its first bytes are read: a FIFO would block the read forever.
  requireRegularFile(path);
  if (looksLikeRos1Bag(path)) return openRos1Store(path);
  if (looksLikeMcap(path)) return openMcap(path);
  if (looksLikeSqlite(path)) return openSqlite(path);
  failAt(path, "neither a ROS 1 bag, an MCAP file nor a ROS 2 sqlite3 bag (hba reads those recordings)");
}

// A storage file named twice (or under two names) would be read twice: every
// message twice, the scans paired with their own copies.
void requireNamedOnce(const fs::path& metadata, const std::vector<fs::path>& files, std::size_t k) {
  for (std::size_t earlier = 0; earlier < k; ++earlier) {
    std::error_code error;
    const bool same = files[earlier].lexically_normal() == files[k].lexically_normal() ||
                      fs::equivalent(files[earlier], files[k], error);
    if (!same) continue;
    failAt(metadata,
           "names the storage file " + files[k].filename().string() + " twice (relative_file_paths entries " +
               std::to_string(earlier + 1) + " and " + std::to_string(k + 1) +
               (files[earlier] == files[k]
                    ? ""
                    : ": " + files[earlier].string() + " and " + files[k].string() + " are one file") +
               "); each file of a recording is read once");
  }
}

}  // namespace

bool looksLikeRosbag2Folder(const fs::path& path) {
  std::error_code error;
  return fs::is_directory(path, error) && fs::is_regular_file(path / "metadata.yaml", error);
}

bool looksLikeRecordingFile(const fs::path& path) {
  std::error_code error;
  return fs::is_regular_file(path, error) &&
         (looksLikeRos1Bag(path) || looksLikeMcap(path) || looksLikeSqlite(path));
}

std::unique_ptr<MessageStore> openMessageStore(const fs::path& path) {
  if (!looksLikeRosbag2Folder(path)) return openFile(path);
  const fs::path metadata = path / "metadata.yaml";
  std::vector<fs::path> files;
  try {
    const YAML::Node info = YAML::LoadFile(metadata.string())["rosbag2_bagfile_information"];
    if (!info) failAt(metadata, "no rosbag2_bagfile_information: not a rosbag2 folder's metadata");
    for (const YAML::Node& file : info["relative_file_paths"]) files.push_back(path / file.as<std::string>());
  } catch (const YAML::Exception& e) {
    failAt(metadata, std::string("cannot read it as YAML (") + e.what() + ")");
  }
  if (files.empty()) failAt(metadata, "names no storage file (relative_file_paths)");
  std::vector<std::unique_ptr<MessageStore>> parts;
  for (std::size_t k = 0; k < files.size(); ++k) {
    requireNamedOnce(metadata, files, k);
    parts.push_back(openFile(files[k]));
  }
  if (parts.size() == 1) return std::move(parts.front());
  return std::make_unique<SplitStore>(path, std::move(parts));
}

}  // namespace hba::rec
