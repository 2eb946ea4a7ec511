// A ROS 1 bag as a MessageStore.
#include <algorithm>

#include "hba/core/error.hpp"
#include "hba/rec/ros1_bag.hpp"
#include "message_store.hpp"

namespace hba::rec {
namespace {

class Ros1Store : public MessageStore {
 public:
  explicit Ros1Store(Ros1Bag bag) : bag_(std::move(bag)) {
    for (const Ros1Connection& c : bag_.connections()) {
      channels_.push_back({c.id, c.topic, c.type, bag_.messageCount(c.id)});
    }
  }
  const std::filesystem::path& path() const override { return bag_.path(); }
  std::string format() const override { return "ROS 1 bag"; }
  Serialization serialization() const override { return Serialization::Ros1; }
  const std::vector<StoredChannel>& channels() const override { return channels_; }
  std::vector<StoredMessage> messages(const std::string& topic) const override {
    std::vector<std::uint32_t> ids;
    for (const StoredChannel& c : channels_) {
      if (c.topic == topic) ids.push_back(c.id);
    }
    std::vector<StoredMessage> out;
    for (const Ros1MessageRef& ref : bag_.messages(ids)) {
      out.push_back({ref.chunk_pos, ref.offset, ref.connection, ref.record_time});
    }
    return out;
  }
  std::vector<std::uint8_t> read(const StoredMessage& message) const override {
    Ros1MessageRef ref;
    ref.chunk_pos = message.chunk;
    ref.offset = static_cast<std::uint32_t>(message.offset);
    ref.connection = message.channel;
    ref.record_time = message.time;
    return bag_.read(ref);
  }

 private:
  Ros1Bag bag_;
  std::vector<StoredChannel> channels_;
};

}  // namespace

std::unique_ptr<MessageStore> openRos1Store(const std::filesystem::path& path) {
  return std::make_unique<Ros1Store>(Ros1Bag::open(path));
}

}  // namespace hba::rec
