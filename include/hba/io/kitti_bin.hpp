#pragma once
// KITTI velodyne scans: a flat array of float32 (x, y, z, intensity).
#include <cstddef>
#include <cstdint>
#include <filesystem>

#include "hba/core/point_cloud.hpp"

namespace hba::io {

// Bytes of one stored point: four float32.
inline constexpr std::size_t kKittiPointBytes = 4 * sizeof(float);

PointCloud readKittiBin(const std::filesystem::path& path);
// Written atomically (synced, then renamed into place).
void writeKittiBin(const std::filesystem::path& path, const PointCloud& cloud);
// The same bytes written straight to `path`, neither synced nor renamed:
// for scratch files a process reads back itself, where syncing each file
// would cost more than the work that reads it. Throws hba::Error (a full disk).
void writeScratchKittiBin(const std::filesystem::path& path, const PointCloud& cloud);
// Points stored in a .bin file, from its size alone. Throws hba::Error when
// the size is not a whole number of points.
std::uint64_t kittiBinPointCount(const std::filesystem::path& path);

}  // namespace hba::io
