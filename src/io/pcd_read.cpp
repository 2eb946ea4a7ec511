// readPcd: one read of the whole file, then the decoder its DATA line names.
#include "file_bytes.hpp"
#include "hba/core/error.hpp"
#include "pcd_format.hpp"

namespace hba::io {

PointCloud readPcd(const std::filesystem::path& path) {
  const detail::FileBytes bytes = detail::readFileBytes(path);
  const std::optional<PcdHeader> header = detail::parsePcdHeader(bytes.view(), true, path);
  if (!header) detail::failNoPcdDataLine(path);
  const detail::PcdLayout layout = detail::pcdLayout(*header, path);
  const std::string_view body = bytes.view().substr(header->data_offset);
  switch (header->encoding) {
    case PcdEncoding::Ascii:
      return detail::decodePcdAscii(body, *header, layout, path);
    case PcdEncoding::Binary:
      return detail::decodePcdBinary(body, *header, layout, path);
    case PcdEncoding::BinaryCompressed:
      return detail::decodePcdCompressed(body, *header, layout, path);
  }
  failAt(path, "unknown PCD encoding");
}

}  // namespace hba::io
