// readPly: the vertex element's x y z (and intensity). Elements before the
// vertices are skipped record by record (their lists sized as declared);
// elements after them (faces, PCL's camera) are never touched.
#include <string>

#include "cloud_readers.hpp"
#include "file_bytes.hpp"
#include "hba/core/error.hpp"
#include "hba/io/ply.hpp"
#include "ply_body.hpp"
#include "text_parsing.hpp"

namespace hba::io {
namespace {
namespace fs = std::filesystem;
using detail::PlyElement;

// CloudCompare names its scalar fields "scalar_<name>".
bool isIntensityName(std::string_view name) {
  return detail::equalsIgnoreCase(name, "intensity") || detail::equalsIgnoreCase(name, "scalar_intensity");
}

int slotOf(const std::string& name) {
  if (name == "x") return 0;
  if (name == "y") return 1;
  if (name == "z") return 2;
  return isIntensityName(name) ? 3 : -1;
}

detail::PlyVertexFields findVertexFields(const PlyElement& vertex, const fs::path& path) {
  std::optional<std::size_t> found[4];
  for (std::size_t p = 0; p < vertex.properties.size(); ++p) {
    const std::string& name = vertex.properties[p].name;
    const int slot = slotOf(name);
    if (slot < 0) continue;
    if (found[slot]) failAt(path, "vertex property " + detail::quoteToken(name) + " appears twice");
    if (vertex.properties[p].is_list) {
      failAt(path, "vertex property " + detail::quoteToken(name) + " is a list");
    }
    found[slot] = p;
  }
  if (!found[0] || !found[1] || !found[2]) failAt(path, "the vertices have no x, y and z");
  detail::PlyVertexFields fields;
  fields.count = found[3] ? 4 : 3;
  for (std::size_t k = 0; k < fields.count; ++k) fields.index[k] = *found[k];
  return fields;
}

template <typename Cloud, typename Body>
Cloud readVertexElement(Body body, const detail::PlyHeader& header, const fs::path& path) {
  for (const PlyElement& element : header.elements) {
    if (element.name == "vertex") {
      return body.template readVertices<Cloud>(element, findVertexFields(element, path));
    }
    body.skipElement(element);
  }
  failAt(path, "the PLY file has no vertex element");
}

}  // namespace

namespace detail {

template <typename Cloud>
Cloud readPlyAs(const fs::path& path) {
  const FileBytes bytes = readFileBytes(path);
  const PlyHeader header = parsePlyHeader(bytes.view(), path);
  const std::string_view body = bytes.view().substr(header.data_offset);
  if (header.storage == PlyStorage::Ascii) {
    return readVertexElement<Cloud>(PlyAsciiBody(body, path), header, path);
  }
  const bool big_endian = header.storage == PlyStorage::BinaryBigEndian;
  return readVertexElement<Cloud>(PlyBinaryBody(body, big_endian, path), header, path);
}

template PointCloud readPlyAs(const fs::path&);
template WideCloud readPlyAs(const fs::path&);

}  // namespace detail

PointCloud readPly(const fs::path& path) { return detail::readPlyAs<PointCloud>(path); }

}  // namespace hba::io
