#pragma once
// PLY point clouds: ascii and binary_little_endian, vertex x y z with optional
// intensity (other vertex properties and other elements are skipped).
#include <filesystem>

#include "hba/core/point_cloud.hpp"

namespace hba::io {

enum class PlyEncoding { Ascii, BinaryLittleEndian };

PointCloud readPly(const std::filesystem::path& path);
void writePly(const std::filesystem::path& path, const PointCloud& cloud,
              PlyEncoding encoding = PlyEncoding::BinaryLittleEndian);

}  // namespace hba::io
