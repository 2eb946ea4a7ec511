#pragma once
// MCAP's records and their reading from the file, shared by the open from the
// summary (mcap_summary.cpp), the scan of the data section (mcap_scan.cpp) and
// the store (mcap_file.cpp). A file: a magic, records (an opcode, a 64-bit
// length, the content), the magic again. See mcap.dev/spec.
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "byte_reader.hpp"
#include "message_store.hpp"

namespace hba::rec::mcap {

constexpr std::uint8_t kMagic[8] = {0x89, 'M', 'C', 'A', 'P', '0', '\r', '\n'};
constexpr std::uint64_t kHeadSize = 9;  // a record's opcode and length

enum Op : std::uint8_t {
  kFooter = 0x02,
  kSchema = 0x03,
  kChannel = 0x04,
  kMessage = 0x05,
  kChunk = 0x06,
  kMessageIndex = 0x07,
  kChunkIndex = 0x08,
  kStatistics = 0x0B,
  kDataEnd = 0x0F,
};

struct RecordHead {
  std::uint8_t op = 0;
  std::uint64_t length = 0;
};

// The file opened for reading, each read checked against its size. Not
// thread-safe: one per reading thread.
class Source {
 public:
  explicit Source(const std::filesystem::path& path);
  const std::filesystem::path& path() const { return path_; }
  std::uint64_t size() const { return size_; }
  std::vector<std::uint8_t> bytes(std::uint64_t pos, std::uint64_t n);
  RecordHead head(std::uint64_t pos);
  // The content of the record at `pos` (its head read again).
  std::vector<std::uint8_t> content(std::uint64_t pos);

 private:
  std::filesystem::path path_;
  std::ifstream in_;
  std::uint64_t size_ = 0;
};

// "<file>: <what>: CRC mismatch (the file is damaged) ...": exit 1.
[[noreturn]] void failCrc(const std::filesystem::path& path, const std::string& what, std::uint32_t stored,
                          std::uint32_t computed);

// The records of a chunk (its record's content `content`, the record at file
// offset `pos`), decompressed and, with `check_crc`, checked against the
// chunk's CRC when it gives one.
std::vector<std::uint8_t> chunkRecords(const std::filesystem::path& path, std::uint64_t pos,
                                       const std::vector<std::uint8_t>& content, bool check_crc = true);

// What opening a file learns: its schemas, channels and where each message lies.
class Contents {
 public:
  void takeSchema(ByteReader& reader);
  void takeChannel(ByteReader& reader);
  // A message of `channel` recorded at `log_time` (ns), in the chunk at file
  // offset `chunk` at `offset` of its records (or at file offset `offset`).
  void addMessage(ByteReader& reader, std::uint16_t channel, std::uint64_t log_time, std::uint64_t chunk,
                  std::uint64_t offset);
  bool knowsChannel(std::uint16_t channel) const { return index_of_.count(channel) > 0; }
  // Every record a chunk's records hold (`records`, the chunk at file offset `chunk`).
  void takeChunkRecords(const std::vector<std::uint8_t>& records, std::uint64_t chunk,
                        const std::string& where);

  const std::vector<StoredChannel>& channels() const { return channels_; }
  const std::vector<StoredMessage>& messages() const { return messages_; }
  const std::string& topicOf(std::uint32_t channel) const {
    return channels_.at(index_of_.at(channel)).topic;
  }

 private:
  std::map<std::uint16_t, std::string> schemas_;
  std::map<std::uint32_t, std::size_t> index_of_;  // channel id -> its place in channels_
  std::vector<StoredChannel> channels_;
  std::vector<StoredMessage> messages_;
};

// The file's schemas, channels and messages from its summary and indexes,
// without decompressing a chunk (except one its indexes leave unindexed).
// False when the file has no summary that indexes every message: `why` then
// says what is missing.
bool readFromSummary(Source& source, Contents& contents, std::string& why);

// The same by reading every record of the data section (chunks
// decompressed); a file without its footer (a recording not finished) is
// read up to its end. The data section's CRC is checked where the file
// gives it.
void scanDataSection(Source& source, Contents& contents);

}  // namespace hba::rec::mcap
