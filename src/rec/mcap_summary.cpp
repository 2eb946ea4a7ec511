// A file opened as MCAP intends: the footer at its end places the summary
// (schemas, channels, one index per chunk, statistics), and each chunk's
// message indexes, after the chunk, say where its messages lie and when they
// were recorded. No chunk is decompressed until a message is read.
#include <algorithm>
#include <cstring>

#include "crc32.hpp"
#include "hba/core/error.hpp"
#include "mcap_format.hpp"

namespace hba::rec::mcap {
namespace {

constexpr std::uint64_t kFooterSize = kHeadSize + 8 + 8 + 4;

struct ChunkIndex {
  std::uint64_t start = 0;                                 // the chunk record's file offset
  std::uint64_t length = 0;                                // the chunk record's length, head included
  std::map<std::uint16_t, std::uint64_t> message_indexes;  // channel -> its MessageIndex record's file offset
  std::uint64_t message_index_length = 0;                  // the chunk's message index records, after it
  std::uint64_t uncompressed_size = 0;
  std::uint64_t end() const { return start + length + message_index_length; }
};

struct Statistics {
  bool present = false;
  std::uint64_t messages = 0;
  std::uint32_t chunks = 0;
};

ChunkIndex readChunkIndex(ByteReader& reader) {
  ChunkIndex index;
  reader.u64();  // message start time
  reader.u64();  // message end time
  index.start = reader.u64();
  index.length = reader.u64();
  const std::uint32_t map_bytes = reader.u32();
  if (map_bytes % 10 != 0) reader.fail("its message index offsets are not pairs of channel and offset");
  for (std::uint32_t k = 0; k < map_bytes / 10; ++k) {
    const auto channel = reader.read<std::uint16_t>();
    index.message_indexes[channel] = reader.u64();
  }
  index.message_index_length = reader.u64();
  reader.string();  // compression
  reader.u64();     // compressed size
  index.uncompressed_size = reader.u64();
  return index;
}

Statistics readStatistics(ByteReader& reader) {
  Statistics statistics;
  statistics.present = true;
  statistics.messages = reader.u64();
  reader.read<std::uint16_t>();  // schemas
  reader.u32();                  // channels
  reader.u32();                  // attachments
  reader.u32();                  // metadata
  statistics.chunks = reader.u32();
  return statistics;
}

// The messages of one chunk from its message indexes, in the order they lie
// in it (as a scan would find them). False when an index names a channel the
// summary does not define.
bool takeMessageIndexes(Source& source, Contents& contents, const ChunkIndex& chunk) {
  const std::string where = source.path().string() + ": chunk at byte " + std::to_string(chunk.start);
  struct Entry {
    std::uint64_t offset;
    std::uint64_t log_time;
    std::uint16_t channel;
  };
  std::vector<Entry> entries;
  for (const auto& [channel, at] : chunk.message_indexes) {
    if (!contents.knowsChannel(channel)) return false;
    const std::string index_where = where + ": message index at byte " + std::to_string(at);
    // Each chunk's own, so no index is read twice.
    if (at < chunk.start + chunk.length || at >= chunk.end())
      throw Error(index_where + ": outside the chunk's message indexes");
    if (source.head(at).op != kMessageIndex) throw Error(index_where + ": no message index record there");
    const std::vector<std::uint8_t> content = source.content(at);
    ByteReader reader(content.data(), content.size(), index_where);
    if (reader.read<std::uint16_t>() != channel)
      reader.fail("it indexes another channel than its chunk index says");
    const std::uint32_t bytes = reader.u32();
    if (bytes % 16 != 0 || bytes > reader.remaining())
      reader.fail("its " + std::to_string(bytes) + " bytes of entries are not whole entries of the record");
    for (std::uint32_t k = 0; k < bytes / 16; ++k) {
      const std::uint64_t log_time = reader.u64();
      const std::uint64_t offset = reader.u64();
      if (offset >= chunk.uncompressed_size) {
        reader.fail("it places a message at byte " + std::to_string(offset) + " of a chunk of " +
                    std::to_string(chunk.uncompressed_size) + " bytes");
      }
      entries.push_back({offset, log_time, channel});
    }
  }
  std::stable_sort(entries.begin(), entries.end(),
                   [](const Entry& a, const Entry& b) { return a.offset < b.offset; });
  ByteReader reader(nullptr, 0, where);
  for (const Entry& e : entries) contents.addMessage(reader, e.channel, e.log_time, chunk.start, e.offset);
  return true;
}

// A chunk its index gives no message index for: its records, decompressed.
void takeUnindexedChunk(Source& source, Contents& contents, const ChunkIndex& chunk) {
  const std::string where = source.path().string() + ": chunk at byte " + std::to_string(chunk.start);
  if (source.head(chunk.start).op != kChunk)
    throw Error(where + ": no chunk record there (its chunk index says so)");
  contents.takeChunkRecords(chunkRecords(source.path(), chunk.start, source.content(chunk.start)),
                            chunk.start, where);
}

}  // namespace

bool readFromSummary(Source& source, Contents& contents, std::string& why) {
  const std::filesystem::path& path = source.path();
  const std::uint64_t size = source.size();
  const std::uint64_t footer_at = size >= kFooterSize + 8 ? size - kFooterSize - 8 : 0;
  std::vector<std::uint8_t> footer;
  if (footer_at >= 8) footer = source.bytes(footer_at, kFooterSize + 8);
  std::uint64_t footer_length = 0;
  if (!footer.empty()) std::memcpy(&footer_length, footer.data() + 1, 8);
  if (footer.empty() || footer[0] != kFooter || footer_length != kFooterSize - kHeadSize ||
      std::memcmp(footer.data() + kFooterSize, kMagic, 8) != 0) {
    why = "the summary is missing: the file ends at byte " + std::to_string(size) +
          " without its footer (a recording that was not finished, or a copy cut short)";
    return false;
  }
  std::uint64_t summary_start = 0;
  std::uint32_t summary_crc = 0;
  std::memcpy(&summary_start, footer.data() + kHeadSize, 8);
  std::memcpy(&summary_crc, footer.data() + kHeadSize + 16, 4);
  if (summary_start == 0) {
    why = "the summary is missing: the file was written without one";
    return false;
  }
  if (summary_start < 8 || summary_start > footer_at) {
    failAt(path, "the footer places the summary at byte " + std::to_string(summary_start) +
                     ", outside the file's " + std::to_string(size) + " bytes: the file is damaged");
  }
  const std::vector<std::uint8_t> summary = source.bytes(summary_start, footer_at - summary_start);
  if (summary_crc != 0) {  // 0: the writer gave no CRC
    // It runs from the summary to the footer's summary_offset_start.
    const std::uint32_t computed =
        crc32Update(crc32Update(0, summary.data(), summary.size()), footer.data(), kHeadSize + 16);
    if (computed != summary_crc)
      failCrc(path,
              "summary section (bytes " + std::to_string(summary_start) + " to " + std::to_string(footer_at) +
                  ")",
              summary_crc, computed);
  }

  std::vector<ChunkIndex> chunks;
  Statistics statistics;
  ByteReader records(summary.data(), summary.size(),
                     path.string() + ": summary section at byte " + std::to_string(summary_start));
  while (records.remaining() > 0) {
    const std::uint64_t at = summary_start + records.position();
    const std::uint8_t op = records.u8();
    const std::uint64_t length = records.u64();
    if (length > records.remaining())
      records.fail("a record at byte " + std::to_string(at) + " runs past it");
    ByteReader reader(records.here(), length,
                      path.string() + ": summary record at byte " + std::to_string(at));
    if (op == kSchema) {
      contents.takeSchema(reader);
    } else if (op == kChannel) {
      contents.takeChannel(reader);
    } else if (op == kChunkIndex) {
      chunks.push_back(readChunkIndex(reader));
      const ChunkIndex& chunk = chunks.back();
      if (chunk.start < 8 || chunk.start > summary_start || chunk.length > summary_start - chunk.start ||
          chunk.message_index_length > summary_start - chunk.start - chunk.length)
        reader.fail("it places a chunk at byte " + std::to_string(chunk.start) +
                    ", outside the data section");
    } else if (op == kStatistics) {
      statistics = readStatistics(reader);
    }
    records.skip(length);
  }

  if (chunks.empty()) {
    why = "the summary indexes no chunk";
    return false;
  }
  if (statistics.present && statistics.chunks != chunks.size()) {
    why = "the summary indexes " + std::to_string(chunks.size()) + " chunks of " +
          std::to_string(statistics.chunks);
    return false;
  }
  std::sort(chunks.begin(), chunks.end(),
            [](const ChunkIndex& a, const ChunkIndex& b) { return a.start < b.start; });
  for (std::size_t k = 1; k < chunks.size(); ++k) {
    if (chunks[k].start < chunks[k - 1].end()) {
      failAt(path, "the summary's chunk indexes place chunks at bytes " +
                       std::to_string(chunks[k - 1].start) + " and " + std::to_string(chunks[k].start) +
                       " that overlap: the file is damaged");
    }
  }
  for (const ChunkIndex& chunk : chunks) {
    if (chunk.message_indexes.empty()) {
      takeUnindexedChunk(source, contents, chunk);
    } else if (!takeMessageIndexes(source, contents, chunk)) {
      why = "a message index names a channel the summary does not define";
      return false;
    }
  }
  if (statistics.present && statistics.messages != contents.messages().size()) {
    why = "its indexes place " + std::to_string(contents.messages().size()) +
          " messages, its statistics count " + std::to_string(statistics.messages);
    return false;
  }
  return true;
}

}  // namespace hba::rec::mcap
