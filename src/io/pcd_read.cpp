// readPcd: one read of the whole file, then the decoder its DATA line names.
#include "cloud_readers.hpp"
#include "file_bytes.hpp"
#include "hba/core/error.hpp"
#include "pcd_format.hpp"

namespace hba::io {
namespace detail {

template <typename Cloud>
Cloud readPcdAs(const std::filesystem::path& path) {
  const FileBytes bytes = readFileBytes(path);
  const std::optional<PcdHeader> header = parsePcdHeader(bytes.view(), true, path);
  if (!header) failNoPcdDataLine(path);
  const PcdLayout layout = pcdLayout(*header, path);
  const std::string_view body = bytes.view().substr(header->data_offset);
  switch (header->encoding) {
    case PcdEncoding::Ascii:
      return decodePcdAscii<Cloud>(body, *header, layout, path);
    case PcdEncoding::Binary:
      return decodePcdBinary<Cloud>(body, *header, layout, path);
    case PcdEncoding::BinaryCompressed:
      return decodePcdCompressed<Cloud>(body, *header, layout, path);
  }
  failAt(path, "unknown PCD encoding");
}

template PointCloud readPcdAs(const std::filesystem::path&);
template WideCloud readPcdAs(const std::filesystem::path&);

}  // namespace detail

PointCloud readPcd(const std::filesystem::path& path) { return detail::readPcdAs<PointCloud>(path); }

}  // namespace hba::io
