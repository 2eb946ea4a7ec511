// MCAP (ROS 2's default bag format since Iron, also written by Foxglove
// tools) as a message store. Opening reads the summary and the chunks'
// message indexes (mcap_summary.cpp): no chunk is decompressed until a
// message in it is read, once for all the messages read from it in a row. A
// file without a usable summary (a recording not finished, or one written
// without) is scanned instead (mcap_scan.cpp), with a warning. Every CRC the
// file gives is checked on the bytes it covers when they are read.
#include <algorithm>
#include <cstring>
#include <mutex>
#include <set>

#include "hba/core/error.hpp"
#include "mcap_format.hpp"
#include "message_store.hpp"

namespace hba::rec {
namespace fs = std::filesystem;

namespace {

class McapFile : public MessageStore {
 public:
  explicit McapFile(const fs::path& path) : path_(path) {
    mcap::Source source(path);
    const std::vector<std::uint8_t> magic =
        source.size() >= 8 ? source.bytes(0, 8) : std::vector<std::uint8_t>{};
    if (magic.empty() || std::memcmp(magic.data(), mcap::kMagic, 8) != 0) failAt(path_, "not an MCAP file");
    std::string why;
    if (!mcap::readFromSummary(source, contents_, why)) {
      contents_ = mcap::Contents();
      mcap::scanDataSection(source, contents_);
      for (const StoredMessage& m : contents_.messages()) verified_.insert(m.chunk);  // checked by the scan
      warnings_.push_back(path_.string() + ": " + why + "; every chunk was read to find the messages");
    }
  }
  const fs::path& path() const override { return path_; }
  std::string format() const override { return "MCAP"; }
  Serialization serialization() const override { return Serialization::Cdr; }
  const std::vector<StoredChannel>& channels() const override { return contents_.channels(); }
  std::vector<std::string> warnings() const override { return warnings_; }

  std::vector<StoredMessage> messages(const std::string& topic) const override {
    std::vector<StoredMessage> out;
    for (const StoredMessage& m : contents_.messages()) {
      if (contents_.topicOf(m.channel) == topic) out.push_back(m);
    }
    std::stable_sort(out.begin(), out.end(),
                     [](const StoredMessage& a, const StoredMessage& b) { return a.time < b.time; });
    return out;
  }

  std::vector<std::uint8_t> read(const StoredMessage& message) const override {
    mcap::Source source(path_);
    if (message.chunk == StoredMessage::kNoChunk) {
      const std::string where = path_.string() + ": message at byte " + std::to_string(message.offset);
      const std::vector<std::uint8_t> record = source.content(message.offset);
      return messageData(record.data(), record.size(), message.channel, where);
    }
    const std::string where = path_.string() + ": chunk at byte " + std::to_string(message.chunk) +
                              ": message at byte " + std::to_string(message.offset) + " of its records";
    const std::shared_ptr<const std::vector<std::uint8_t>> records = chunk(source, message.chunk);
    if (message.offset > records->size()) throw Error(where + ": past the chunk's end");
    ByteReader reader(records->data() + message.offset, records->size() - message.offset, where);
    if (reader.u8() != mcap::kMessage) reader.fail("no message record there");
    const std::uint64_t length = reader.u64();
    if (length > reader.remaining()) reader.fail("a message record runs past its chunk");
    return messageData(reader.here(), length, message.channel, where);
  }

 private:
  static std::vector<std::uint8_t> messageData(const std::uint8_t* record, std::size_t size,
                                               std::uint32_t channel, const std::string& where) {
    ByteReader reader(record, size, where);
    if (reader.read<std::uint16_t>() != channel)
      reader.fail("a message of another channel than its index says");
    reader.u32();  // sequence
    reader.u64();  // log time
    reader.u64();  // publish time
    return std::vector<std::uint8_t>(reader.here(), reader.here() + reader.remaining());
  }

  // The records of the chunk at file offset `pos`: decompressed (and CRC
  // checked) once for the messages read from it in a row.
  std::shared_ptr<const std::vector<std::uint8_t>> chunk(mcap::Source& source, std::uint64_t pos) const {
    {
      const std::lock_guard<std::mutex> lock(cache_mutex_);
      if (cached_ && cached_chunk_ == pos) return cached_;
    }
    if (source.head(pos).op != mcap::kChunk) {
      failAt(path_, "chunk at byte " + std::to_string(pos) + ": no chunk record there (its index says so)");
    }
    // A chunk's CRC is checked the first time it is decompressed (at open,
    // when the file was scanned): the CRC costs about as much as zstd.
    bool verified = false;
    {
      const std::lock_guard<std::mutex> lock(cache_mutex_);
      verified = verified_.count(pos) > 0;
    }
    auto records = std::make_shared<const std::vector<std::uint8_t>>(
        mcap::chunkRecords(path_, pos, source.content(pos), !verified));
    const std::lock_guard<std::mutex> lock(cache_mutex_);
    verified_.insert(pos);
    cached_chunk_ = pos;
    cached_ = records;
    return records;
  }

  fs::path path_;
  mcap::Contents contents_;
  std::vector<std::string> warnings_;
  mutable std::mutex cache_mutex_;
  mutable std::uint64_t cached_chunk_ = 0;
  mutable std::shared_ptr<const std::vector<std::uint8_t>> cached_;
  mutable std::set<std::uint64_t> verified_;  // chunks whose CRC was checked
};

}  // namespace

bool looksLikeMcap(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::uint8_t start[8] = {};
  in.read(reinterpret_cast<char*>(start), 8);
  return in && std::memcmp(start, mcap::kMagic, 8) == 0;
}

std::unique_ptr<MessageStore> openMcap(const fs::path& path) { return std::make_unique<McapFile>(path); }

}  // namespace hba::rec
