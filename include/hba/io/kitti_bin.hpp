#pragma once
// KITTI velodyne scans: a flat array of float32 (x, y, z, intensity).
#include <filesystem>

#include "hba/core/point_cloud.hpp"

namespace hba::io {

PointCloud readKittiBin(const std::filesystem::path& path);
void writeKittiBin(const std::filesystem::path& path, const PointCloud& cloud);

}  // namespace hba::io
