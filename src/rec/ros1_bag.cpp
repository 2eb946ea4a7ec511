// The ROS 1 bag format 2.0: a version line, then records of a header (a
// list of name=value fields, the "op" field saying what the record is) and
// data. The bag header points at the index at the end: every connection,
// then one chunk-info record per chunk; after each chunk come its index
// records (per connection: record time and offset of every message).
#include "hba/rec/ros1_bag.hpp"

#include <algorithm>
#include <cstring>
#include <fstream>
#include <map>
#include <mutex>

#include "byte_reader.hpp"
#include "chunk_codec.hpp"
#include "hba/core/error.hpp"

static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__, "the bag readers assume a little-endian host");

namespace hba::rec {
namespace fs = std::filesystem;

namespace {

constexpr char kMagic[] = "#ROSBAG V2.0\n";
constexpr std::size_t kMagicSize = sizeof(kMagic) - 1;

enum Op : std::uint8_t {
  kMessageData = 0x02,
  kBagHeader = 0x03,
  kIndexData = 0x04,
  kChunk = 0x05,
  kChunkInfo = 0x06,
  kConnection = 0x07,
};

using Fields = std::map<std::string, std::string>;

// A header's name=value fields, each prefixed by its length.
Fields parseFields(const std::uint8_t* data, std::size_t size, const std::string& what) {
  ByteReader reader(data, size, what);
  Fields fields;
  while (reader.remaining() > 0) {
    const std::string field = reader.string();
    const std::size_t equals = field.find('=');
    if (equals == std::string::npos) reader.fail("a header field without '='");
    fields[field.substr(0, equals)] = field.substr(equals + 1);
  }
  return fields;
}

template <typename T>
T fieldAs(const Fields& fields, const std::string& name, const std::string& what) {
  const auto it = fields.find(name);
  if (it == fields.end()) throw Error(what + ": no '" + name + "' field");
  if (it->second.size() != sizeof(T)) throw Error(what + ": field '" + name + "' has the wrong size");
  T value;
  std::memcpy(&value, it->second.data(), sizeof(T));
  return value;
}

std::string textField(const Fields& fields, const std::string& name, const std::string& what) {
  const auto it = fields.find(name);
  if (it == fields.end()) throw Error(what + ": no '" + name + "' field");
  return it->second;
}

// The bag file, read at given positions; a read past its end names the file
// as truncated.
class BagFile {
 public:
  explicit BagFile(const fs::path& path) : path_(path), in_(path, std::ios::binary) {
    if (!in_) failAt(path, "cannot open for reading");
    in_.seekg(0, std::ios::end);
    size_ = static_cast<std::uint64_t>(in_.tellg());
  }
  std::uint64_t size() const { return size_; }
  void readAt(std::uint64_t pos, std::uint8_t* out, std::size_t n, const char* what) {
    if (pos > size_ || n > size_ - pos) {
      failAt(path_, std::string("truncated: ") + what + " at byte " + std::to_string(pos) +
                        " runs past the end of the file (" + std::to_string(size_) + " bytes)");
    }
    in_.seekg(static_cast<std::streamoff>(pos));
    in_.read(reinterpret_cast<char*>(out), static_cast<std::streamsize>(n));
    if (!in_) failAt(path_, std::string("read error in ") + what + " at byte " + std::to_string(pos));
  }
  std::uint32_t u32At(std::uint64_t pos, const char* what) {
    std::uint32_t value = 0;
    readAt(pos, reinterpret_cast<std::uint8_t*>(&value), 4, what);
    return value;
  }

 private:
  fs::path path_;
  std::ifstream in_;
  std::uint64_t size_ = 0;
};

struct Record {
  Fields header;
  std::uint8_t op = 0;
  std::uint64_t data_pos = 0;
  std::uint32_t data_size = 0;
  std::uint64_t end() const { return data_pos + data_size; }
};

Record readRecord(BagFile& file, std::uint64_t pos, const std::string& what) {
  Record record;
  const std::uint32_t header_size = file.u32At(pos, "a record header");
  if (std::uint64_t{header_size} + 8 > file.size() - pos) {
    throw Error(what + ": truncated: a record header of " + std::to_string(header_size) + " bytes at byte " +
                std::to_string(pos) + " runs past the end of the file");
  }
  std::vector<std::uint8_t> header(header_size);
  file.readAt(pos + 4, header.data(), header.size(), "a record header");
  record.header = parseFields(header.data(), header.size(), what);
  record.op = fieldAs<std::uint8_t>(record.header, "op", what);
  record.data_size = file.u32At(pos + 4 + header_size, "a record's data size");
  record.data_pos = pos + 8 + header_size;
  if (record.data_pos + record.data_size > file.size()) {
    throw Error(what + ": truncated: a record's data runs past the end of the file");
  }
  return record;
}

std::vector<std::uint8_t> recordData(BagFile& file, const Record& record) {
  std::vector<std::uint8_t> data(record.data_size);
  file.readAt(record.data_pos, data.data(), data.size(), "a record's data");
  return data;
}

Ros1Connection readConnection(BagFile& file, const Record& record, const std::string& where) {
  Ros1Connection connection;
  connection.id = fieldAs<std::uint32_t>(record.header, "conn", where);
  connection.topic = textField(record.header, "topic", where);
  const std::vector<std::uint8_t> data = recordData(file, record);
  const Fields details = parseFields(data.data(), data.size(), where);
  connection.type = textField(details, "type", where);
  connection.md5sum = textField(details, "md5sum", where);
  const auto definition = details.find("message_definition");
  if (definition != details.end()) connection.definition = definition->second;
  return connection;
}

}  // namespace

struct Ros1Bag::ChunkCache {
  std::mutex mutex;
  std::uint64_t chunk_pos = 0;
  std::shared_ptr<const std::vector<std::uint8_t>> records;
};

Ros1Bag::Ros1Bag() : cache_(std::make_unique<ChunkCache>()) {}
Ros1Bag::~Ros1Bag() = default;
Ros1Bag::Ros1Bag(Ros1Bag&&) noexcept = default;
Ros1Bag& Ros1Bag::operator=(Ros1Bag&&) noexcept = default;

bool looksLikeRos1Bag(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  char start[kMagicSize] = {};
  in.read(start, static_cast<std::streamsize>(kMagicSize));
  return in && std::memcmp(start, kMagic, kMagicSize) == 0;
}

Ros1Bag Ros1Bag::open(const fs::path& path) {
  if (!looksLikeRos1Bag(path)) {
    if (!fs::exists(path)) failAt(path, "no such file");
    failAt(path, "not a ROS 1 bag (it does not start with \"#ROSBAG V2.0\")");
  }
  Ros1Bag bag;
  bag.path_ = path;
  BagFile file(path);
  const std::string where = path.string();

  const Record header = readRecord(file, kMagicSize, where + ": bag header");
  if (header.op != kBagHeader) failAt(path, "the first record is not a bag header");
  const auto index_pos = fieldAs<std::uint64_t>(header.header, "index_pos", where);
  const auto connection_count = fieldAs<std::uint32_t>(header.header, "conn_count", where);
  const auto chunk_count = fieldAs<std::uint32_t>(header.header, "chunk_count", where);
  if (index_pos == 0) {
    failAt(path,
           "the bag has no index: its recording was cut short or is still being written "
           "(`rosbag reindex` repairs it)");
  }
  if (index_pos >= file.size()) {
    failAt(path, "truncated: its index should start at byte " + std::to_string(index_pos) + " of " +
                     std::to_string(file.size()) + " (`rosbag reindex` may repair it)");
  }

  // The index: the connections, then one chunk-info record per chunk.
  std::uint64_t pos = index_pos;
  for (std::uint32_t c = 0; c < connection_count; ++c) {
    const Record record = readRecord(file, pos, where + ": connection record");
    if (record.op != kConnection) failAt(path, "the index holds a record that is not a connection");
    bag.connections_.push_back(readConnection(file, record, where + ": connection record"));
    pos = record.end();
  }
  std::vector<std::uint64_t> chunks;
  for (std::uint32_t c = 0; c < chunk_count; ++c) {
    const Record record = readRecord(file, pos, where + ": chunk info record");
    if (record.op != kChunkInfo) failAt(path, "the index holds a record that is not a chunk info");
    chunks.push_back(fieldAs<std::uint64_t>(record.header, "chunk_pos", where));
    pos = record.end();
  }

  // After each chunk, its index records: where each message lies in it.
  for (const std::uint64_t chunk_pos : chunks) {
    const Record chunk = readRecord(file, chunk_pos, where + ": chunk at byte " + std::to_string(chunk_pos));
    if (chunk.op != kChunk)
      failAt(path, "chunk info points at byte " + std::to_string(chunk_pos) + ", not a chunk");
    const auto chunk_size = fieldAs<std::uint32_t>(chunk.header, "size", where);
    std::uint64_t next = chunk.end();
    while (next < index_pos) {
      const Record record = readRecord(file, next, where + ": index record");
      if (record.op != kIndexData) break;
      const auto version = fieldAs<std::uint32_t>(record.header, "ver", where);
      if (version != 1) failAt(path, "index record version " + std::to_string(version) + " (hba reads 1)");
      const auto connection = fieldAs<std::uint32_t>(record.header, "conn", where);
      const auto count = fieldAs<std::uint32_t>(record.header, "count", where);
      const std::vector<std::uint8_t> data = recordData(file, record);
      ByteReader entries(data.data(), data.size(), where + ": index record");
      for (std::uint32_t k = 0; k < count; ++k) {
        Ros1MessageRef ref;
        ref.record_time = entries.time();
        ref.offset = entries.u32();
        if (ref.offset >= chunk_size) failAt(path, "an index entry points past the end of its chunk");
        ref.chunk_pos = chunk_pos;
        ref.connection = connection;
        bag.index_.push_back(ref);
      }
      next = record.end();
    }
  }
  std::stable_sort(
      bag.index_.begin(), bag.index_.end(),
      [](const Ros1MessageRef& a, const Ros1MessageRef& b) { return a.record_time < b.record_time; });
  return bag;
}

std::vector<Ros1MessageRef> Ros1Bag::messages(const std::vector<std::uint32_t>& connections) const {
  if (connections.empty()) return index_;
  std::vector<Ros1MessageRef> out;
  for (const Ros1MessageRef& ref : index_) {
    if (std::find(connections.begin(), connections.end(), ref.connection) != connections.end())
      out.push_back(ref);
  }
  return out;
}

std::size_t Ros1Bag::messageCount(std::uint32_t connection) const {
  return static_cast<std::size_t>(
      std::count_if(index_.begin(), index_.end(),
                    [connection](const Ros1MessageRef& r) { return r.connection == connection; }));
}

std::vector<std::uint8_t> Ros1Bag::read(const Ros1MessageRef& message) const {
  const std::string where = path_.string() + ": chunk at byte " + std::to_string(message.chunk_pos);
  std::shared_ptr<const std::vector<std::uint8_t>> records;
  {
    const std::lock_guard<std::mutex> lock(cache_->mutex);
    if (cache_->records && cache_->chunk_pos == message.chunk_pos) records = cache_->records;
  }
  if (!records) {
    BagFile file(path_);
    const Record chunk = readRecord(file, message.chunk_pos, where);
    const std::vector<std::uint8_t> data = recordData(file, chunk);
    records = std::make_shared<const std::vector<std::uint8_t>>(
        decompressChunk(textField(chunk.header, "compression", where), data.data(), data.size(),
                        fieldAs<std::uint32_t>(chunk.header, "size", where), where));
    const std::lock_guard<std::mutex> lock(cache_->mutex);
    cache_->chunk_pos = message.chunk_pos;
    cache_->records = records;
  }
  // The message data record at the offset: header (op, conn, time), data.
  ByteReader reader(records->data() + message.offset, records->size() - message.offset,
                    where + ", message at offset " + std::to_string(message.offset));
  const auto header = reader.bytes();
  const Fields fields = parseFields(header.first, header.second, where);
  if (fieldAs<std::uint8_t>(fields, "op", where) != kMessageData) {
    reader.fail("the index points at a record that is not a message");
  }
  const auto body = reader.bytes();
  return std::vector<std::uint8_t>(body.first, body.first + body.second);
}

}  // namespace hba::rec
