#include "mcap_format.hpp"

#include <cstdio>
#include <cstring>

#include "chunk_codec.hpp"
#include "crc32.hpp"
#include "hba/core/error.hpp"

namespace hba::rec::mcap {
namespace fs = std::filesystem;

Source::Source(const fs::path& path) : path_(path), in_(path, std::ios::binary) {
  if (!in_) failAt(path_, "cannot open for reading");
  in_.seekg(0, std::ios::end);
  size_ = static_cast<std::uint64_t>(in_.tellg());
}

std::vector<std::uint8_t> Source::bytes(std::uint64_t pos, std::uint64_t n) {
  if (pos > size_ || n > size_ - pos) {
    failAt(path_, "truncated: a record at byte " + std::to_string(pos) + " runs past the end of the file (" +
                      std::to_string(size_) + " bytes); the recording was cut short");
  }
  std::vector<std::uint8_t> bytes(n);
  in_.seekg(static_cast<std::streamoff>(pos));
  in_.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(n));
  if (!in_) failAt(path_, "read error at byte " + std::to_string(pos));
  return bytes;
}

RecordHead Source::head(std::uint64_t pos) {
  const std::vector<std::uint8_t> head = bytes(pos, kHeadSize);
  RecordHead record;
  record.op = head[0];
  std::memcpy(&record.length, head.data() + 1, 8);
  return record;
}

std::vector<std::uint8_t> Source::content(std::uint64_t pos) {
  const std::uint64_t length = head(pos).length;
  if (pos > size_ - kHeadSize || length > size_ - pos - kHeadSize) {
    failAt(path_, "truncated: a record at byte " + std::to_string(pos) + " runs past the end of the file (" +
                      std::to_string(size_) + " bytes); the recording was cut short");
  }
  return bytes(pos + kHeadSize, length);
}

void failCrc(const fs::path& path, const std::string& what, std::uint32_t stored, std::uint32_t computed) {
  char numbers[64];
  std::snprintf(numbers, sizeof(numbers), "stored %08x, computed %08x", stored, computed);
  failAt(path, what + ": CRC mismatch (the file is damaged): " + numbers);
}

std::vector<std::uint8_t> chunkRecords(const fs::path& path, std::uint64_t pos,
                                       const std::vector<std::uint8_t>& content, bool check_crc) {
  const std::string where = path.string() + ": chunk at byte " + std::to_string(pos);
  ByteReader reader(content.data(), content.size(), where);
  reader.u64();  // message start time
  reader.u64();  // message end time
  const std::uint64_t uncompressed = reader.u64();
  const std::uint32_t crc = reader.u32();
  const std::string compression = reader.string();
  const std::uint64_t compressed = reader.u64();
  if (compressed > reader.remaining()) reader.fail("the chunk's records run past the chunk");
  // MCAP names an uncompressed chunk "".
  std::vector<std::uint8_t> records = decompressChunk(compression.empty() ? "none" : compression,
                                                      reader.here(), compressed, uncompressed, where);
  if (check_crc && crc != 0) {  // 0: the writer gave no CRC
    const std::uint32_t computed = crc32Update(0, records.data(), records.size());
    if (computed != crc) failCrc(path, "chunk at byte " + std::to_string(pos), crc, computed);
  }
  return records;
}

void Contents::takeSchema(ByteReader& reader) {
  const auto id = reader.read<std::uint16_t>();
  schemas_[id] = reader.string();
}

void Contents::takeChannel(ByteReader& reader) {
  const auto id = reader.read<std::uint16_t>();
  const auto schema = reader.read<std::uint16_t>();
  const std::string topic = reader.string();
  const std::string encoding = reader.string();
  if (index_of_.count(id)) return;  // repeated (chunks and the summary repeat channels)
  const auto type = schemas_.find(schema);
  if (type == schemas_.end())
    reader.fail("channel " + topic + " names schema " + std::to_string(schema) + ", not defined before it");
  index_of_[id] = channels_.size();
  if (encoding != "cdr") {
    channels_.push_back({id, topic, type->second + " (" + encoding + ", not read)", 0});
  } else {
    channels_.push_back({id, topic, rosTypeName(type->second), 0});
  }
}

void Contents::addMessage(ByteReader& reader, std::uint16_t channel, std::uint64_t log_time,
                          std::uint64_t chunk, std::uint64_t offset) {
  const auto it = index_of_.find(channel);
  if (it == index_of_.end())
    reader.fail("a message on channel " + std::to_string(channel) + ", not defined before it");
  ++channels_[it->second].messages;
  messages_.push_back({chunk, offset, channel, static_cast<double>(log_time) * 1e-9});
}

void Contents::takeChunkRecords(const std::vector<std::uint8_t>& records, std::uint64_t chunk,
                                const std::string& where) {
  ByteReader chunk_reader(records.data(), records.size(), where);
  while (chunk_reader.remaining() > 0) {
    const std::size_t offset = chunk_reader.position();
    const std::uint8_t op = chunk_reader.u8();
    const std::uint64_t length = chunk_reader.u64();
    if (length > chunk_reader.remaining()) chunk_reader.fail("a record runs past its chunk");
    ByteReader reader(chunk_reader.here(), length, where);
    if (op == kSchema) {
      takeSchema(reader);
    } else if (op == kChannel) {
      takeChannel(reader);
    } else if (op == kMessage) {
      const auto channel = reader.read<std::uint16_t>();
      reader.u32();  // sequence
      addMessage(reader, channel, reader.u64(), chunk, offset);
    }
    chunk_reader.skip(length);
  }
}

}  // namespace hba::rec::mcap
