#pragma once
// Readers of a PLY body (the bytes after end_header), one per storage kind.
// Each walks the elements in order: skipElement() for those before the
// vertices, then readVertices().
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string_view>

#include "hba/core/point_cloud.hpp"
#include "hba/io/wide_cloud.hpp"
#include "ply_format.hpp"
#include "point_columns.hpp"

namespace hba::io::detail {

// Property indices of the values hba keeps, in the order x y z intensity.
struct PlyVertexFields {
  std::size_t index[4] = {0, 0, 0, 0};
  std::size_t count = 3;  // 4 with intensity
};

// True if x, y or z is stored as float64 (see addFinitePoint).
bool hasWideCoordinates(const PlyElement& vertex, const PlyVertexFields& fields);

class PlyBinaryBody {
 public:
  PlyBinaryBody(std::string_view bytes, bool big_endian, const std::filesystem::path& path)
      : bytes_(bytes), big_endian_(big_endian), path_(path) {}
  void skipElement(const PlyElement& element);
  template <typename Cloud>  // PointCloud or WideCloud
  Cloud readVertices(const PlyElement& vertex, const PlyVertexFields& fields);

 private:
  std::uint64_t remaining() const { return bytes_.size() - pos_; }
  void require(std::uint64_t n, const PlyElement& element) const;
  void advance(std::uint64_t n, const PlyElement& element);
  std::uint64_t listCount(const PlyProperty& property, const PlyElement& element);
  void walkRecord(const PlyElement& element, std::size_t* starts);

  std::string_view bytes_;
  std::size_t pos_ = 0;
  bool big_endian_;
  const std::filesystem::path& path_;
};

class PlyAsciiBody {
 public:
  PlyAsciiBody(std::string_view text, const std::filesystem::path& path) : rest_(text), path_(path) {}
  void skipElement(const PlyElement& element);
  template <typename Cloud>  // PointCloud or WideCloud
  Cloud readVertices(const PlyElement& vertex, const PlyVertexFields& fields);

 private:
  std::string_view token(const PlyElement& element);
  void skipProperty(const PlyProperty& property, const PlyElement& element);
  double parseValue(std::string_view word, ScalarType type, std::uint64_t vertex) const;

  std::string_view rest_;
  const std::filesystem::path& path_;
};

}  // namespace hba::io::detail
