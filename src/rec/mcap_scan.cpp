// The data section read record by record, as MCAP's streaming readers do: for
// a file without a summary, or one whose summary leaves messages unindexed.
#include <algorithm>
#include <cstring>

#include "crc32.hpp"
#include "hba/core/error.hpp"
#include "mcap_format.hpp"

namespace hba::rec::mcap {

void scanDataSection(Source& source, Contents& contents) {
  const std::filesystem::path& path = source.path();
  const std::vector<std::uint8_t> magic = source.bytes(0, 8);
  // The data section's CRC runs over every byte before the DataEnd record.
  std::uint32_t crc = crc32Update(0, magic.data(), magic.size());
  std::uint64_t pos = 8;
  while (pos < source.size()) {
    const std::vector<std::uint8_t> head = source.bytes(pos, kHeadSize);
    RecordHead record;
    record.op = head[0];
    std::memcpy(&record.length, head.data() + 1, 8);
    if (record.op == kFooter) return;  // no DataEnd record before it: nothing to check
    const std::vector<std::uint8_t> content = source.content(pos);
    if (record.op == kDataEnd) {
      ByteReader reader(content.data(), content.size(),
                        path.string() + ": data end record at byte " + std::to_string(pos));
      const std::uint32_t stored = reader.u32();
      if (stored != 0 && stored != crc)  // 0: the writer gave no CRC
        failCrc(path, "data section (bytes 0 to " + std::to_string(pos) + ")", stored, crc);
      return;
    }
    crc = crc32Update(crc, head.data(), head.size());
    crc = crc32Update(crc, content.data(), content.size());
    const std::string where = path.string() + ": record at byte " + std::to_string(pos);
    ByteReader reader(content.data(), content.size(), where);
    if (record.op == kSchema) {
      contents.takeSchema(reader);
    } else if (record.op == kChannel) {
      contents.takeChannel(reader);
    } else if (record.op == kMessage) {
      const auto channel = reader.read<std::uint16_t>();
      reader.u32();  // sequence
      contents.addMessage(reader, channel, reader.u64(), StoredMessage::kNoChunk, pos);
    } else if (record.op == kChunk) {
      contents.takeChunkRecords(chunkRecords(path, pos, content), pos,
                                path.string() + ": chunk at byte " + std::to_string(pos));
    }
    pos += kHeadSize + content.size();
  }
  // The file ends after a whole record, without DataEnd or footer: a
  // recording that was not finished; the caller warns.
}

}  // namespace hba::rec::mcap
