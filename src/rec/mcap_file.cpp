// MCAP (ROS 2's default bag format since Iron, also written by Foxglove
// tools): a magic, then records of an opcode, a 64-bit length and content.
// One pass over the data section at open learns the schemas, channels and
// where every message lies (inside chunks: none, lz4 or zstd); the summary
// section after it is not needed for that and is not read.
#include <algorithm>
#include <cstring>
#include <fstream>
#include <map>
#include <mutex>

#include "byte_reader.hpp"
#include "chunk_codec.hpp"
#include "hba/core/error.hpp"
#include "message_store.hpp"

namespace hba::rec {
namespace fs = std::filesystem;

namespace {

constexpr std::uint8_t kMagic[8] = {0x89, 'M', 'C', 'A', 'P', '0', '\r', '\n'};

enum Op : std::uint8_t {
  kFooter = 0x02,
  kSchema = 0x03,
  kChannel = 0x04,
  kMessage = 0x05,
  kChunk = 0x06,
  kDataEnd = 0x0F,
};

std::vector<std::uint8_t> readBytes(std::ifstream& in, std::uint64_t pos, std::uint64_t n,
                                    std::uint64_t file_size, const fs::path& path) {
  if (pos > file_size || n > file_size - pos) {
    failAt(path, "truncated: a record at byte " + std::to_string(pos) + " runs past the end of the file (" +
                     std::to_string(file_size) + " bytes); the recording was cut short");
  }
  std::vector<std::uint8_t> bytes(n);
  in.seekg(static_cast<std::streamoff>(pos));
  in.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(n));
  if (!in) failAt(path, "read error at byte " + std::to_string(pos));
  return bytes;
}

// A record's opcode and content length (its 9-byte head at `pos`).
struct RecordHead {
  std::uint8_t op = 0;
  std::uint64_t length = 0;
};

class McapFile : public MessageStore {
 public:
  explicit McapFile(const fs::path& path) : path_(path) { scan(); }
  const fs::path& path() const override { return path_; }
  std::string format() const override { return "MCAP"; }
  Serialization serialization() const override { return Serialization::Cdr; }
  const std::vector<StoredChannel>& channels() const override { return channels_; }

  std::vector<StoredMessage> messages(const std::string& topic) const override {
    std::vector<StoredMessage> out;
    for (const StoredMessage& m : messages_) {
      if (topic_of_.at(m.channel) == topic) out.push_back(m);
    }
    std::stable_sort(out.begin(), out.end(),
                     [](const StoredMessage& a, const StoredMessage& b) { return a.time < b.time; });
    return out;
  }

  std::vector<std::uint8_t> read(const StoredMessage& message) const override {
    std::ifstream in(path_, std::ios::binary);
    const std::string where = path_.string() + ": message at byte " + std::to_string(message.offset);
    if (message.chunk == StoredMessage::kNoChunk) {
      const std::vector<std::uint8_t> record = contentAt(in, message.offset);
      return messageData(record.data(), record.size(), where);
    }
    std::shared_ptr<const std::vector<std::uint8_t>> records;
    {
      const std::lock_guard<std::mutex> lock(cache_mutex_);
      if (cached_ && cached_chunk_ == message.chunk) records = cached_;
    }
    if (!records) {
      records = std::make_shared<const std::vector<std::uint8_t>>(chunkRecords(in, message.chunk));
      const std::lock_guard<std::mutex> lock(cache_mutex_);
      cached_chunk_ = message.chunk;
      cached_ = records;
    }
    ByteReader reader(records->data() + message.offset, records->size() - message.offset, where);
    reader.u8();
    const std::uint64_t length = reader.u64();
    if (length > reader.remaining()) reader.fail("a message record runs past its chunk");
    return messageData(reader.here(), length, where);
  }

 private:
  static std::vector<std::uint8_t> messageData(const std::uint8_t* record, std::size_t size,
                                               const std::string& where) {
    ByteReader reader(record, size, where);
    reader.read<std::uint16_t>();  // channel
    reader.u32();                  // sequence
    reader.u64();                  // log time
    reader.u64();                  // publish time
    return std::vector<std::uint8_t>(reader.here(), reader.here() + reader.remaining());
  }

  RecordHead headAt(std::ifstream& in, std::uint64_t pos) const {
    const std::vector<std::uint8_t> head = readBytes(in, pos, 9, size_, path_);
    RecordHead record;
    record.op = head[0];
    std::memcpy(&record.length, head.data() + 1, 8);
    return record;
  }

  // The content of the record at file offset `pos`.
  std::vector<std::uint8_t> contentAt(std::ifstream& in, std::uint64_t pos) const {
    return readBytes(in, pos + 9, headAt(in, pos).length, size_, path_);
  }

  // The decompressed records of the chunk record at file offset `pos`.
  std::vector<std::uint8_t> chunkRecords(std::ifstream& in, std::uint64_t pos) const {
    const std::vector<std::uint8_t> content = contentAt(in, pos);
    const std::string where = path_.string() + ": chunk at byte " + std::to_string(pos);
    ByteReader reader(content.data(), content.size(), where);
    reader.u64();  // message start time
    reader.u64();  // message end time
    const std::uint64_t uncompressed = reader.u64();
    reader.u32();  // crc
    const std::string compression = reader.string();
    const std::uint64_t compressed = reader.u64();
    if (compressed > reader.remaining()) reader.fail("the chunk's records run past the chunk");
    // MCAP names an uncompressed chunk "".
    return decompressChunk(compression.empty() ? "none" : compression, reader.here(), compressed,
                           uncompressed, where);
  }

  // One record of the data section or of a chunk.
  void takeRecord(std::uint8_t op, const std::uint8_t* content, std::size_t size, std::uint64_t chunk,
                  std::uint64_t offset, const std::string& where) {
    ByteReader reader(content, size, where);
    if (op == kSchema) {
      const auto id = reader.read<std::uint16_t>();
      schemas_[id] = reader.string();
    } else if (op == kChannel) {
      const auto id = reader.read<std::uint16_t>();
      const auto schema = reader.read<std::uint16_t>();
      const std::string topic = reader.string();
      const std::string encoding = reader.string();
      if (topic_of_.count(id)) return;  // repeated (chunks may repeat channels)
      const auto type = schemas_.find(schema);
      if (type == schemas_.end())
        reader.fail("channel " + topic + " names schema " + std::to_string(schema) +
                    ", not defined before it");
      if (encoding != "cdr") {
        channels_.push_back({id, topic, type->second + " (" + encoding + ", not read)", 0});
      } else {
        channels_.push_back({id, topic, rosTypeName(type->second), 0});
      }
      topic_of_[id] = topic;
    } else if (op == kMessage) {
      const auto channel = reader.read<std::uint16_t>();
      reader.u32();
      const std::uint64_t log_time = reader.u64();
      const auto it = std::find_if(channels_.begin(), channels_.end(),
                                   [channel](const StoredChannel& c) { return c.id == channel; });
      if (it == channels_.end())
        reader.fail("a message on channel " + std::to_string(channel) + ", not defined before it");
      ++it->messages;
      messages_.push_back({chunk, offset, channel, static_cast<double>(log_time) * 1e-9});
    }
  }

  void scan() {
    std::ifstream in(path_, std::ios::binary);
    if (!in) failAt(path_, "cannot open for reading");
    in.seekg(0, std::ios::end);
    size_ = static_cast<std::uint64_t>(in.tellg());
    const std::vector<std::uint8_t> magic = readBytes(in, 0, 8, size_, path_);
    if (std::memcmp(magic.data(), kMagic, 8) != 0) failAt(path_, "not an MCAP file");
    std::uint64_t pos = 8;
    while (true) {
      if (pos == size_)
        failAt(path_, "truncated: the file ends at byte " + std::to_string(pos) +
                          " before its footer; the recording was cut short");
      const auto [op, length] = headAt(in, pos);
      if (op == kDataEnd || op == kFooter) break;
      const std::string where = path_.string() + ": record at byte " + std::to_string(pos);
      if (op == kSchema || op == kChannel || op == kMessage) {
        const std::vector<std::uint8_t> content = contentAt(in, pos);
        takeRecord(op, content.data(), content.size(), StoredMessage::kNoChunk, pos, where);
      } else if (op == kChunk) {
        const std::vector<std::uint8_t> records = chunkRecords(in, pos);
        ByteReader reader(records.data(), records.size(),
                          path_.string() + ": chunk at byte " + std::to_string(pos));
        while (reader.remaining() > 0) {
          const std::size_t offset = reader.position();
          const std::uint8_t inner = reader.u8();
          const std::uint64_t inner_length = reader.u64();
          if (inner_length > reader.remaining()) reader.fail("a record runs past its chunk");
          takeRecord(inner, reader.here(), inner_length, pos, offset, where);
          reader.skip(inner_length);
        }
      } else if (length > size_ - pos - 9) {
        failAt(path_,
               "truncated: a record at byte " + std::to_string(pos) + " runs past the end of the file");
      }
      pos += 9 + length;
    }
  }

  fs::path path_;
  std::uint64_t size_ = 0;
  std::map<std::uint16_t, std::string> schemas_;
  std::map<std::uint32_t, std::string> topic_of_;
  std::vector<StoredChannel> channels_;
  std::vector<StoredMessage> messages_;
  mutable std::mutex cache_mutex_;
  mutable std::uint64_t cached_chunk_ = 0;
  mutable std::shared_ptr<const std::vector<std::uint8_t>> cached_;
};

}  // namespace

bool looksLikeMcap(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::uint8_t start[8] = {};
  in.read(reinterpret_cast<char*>(start), 8);
  return in && std::memcmp(start, kMagic, 8) == 0;
}

std::unique_ptr<MessageStore> openMcap(const fs::path& path) { return std::make_unique<McapFile>(path); }

}  // namespace hba::rec
