#pragma once
// Checks the writers make before writing a cloud they are given.
#include <filesystem>
#include <string>

#include "hba/core/error.hpp"
#include "hba/core/point_cloud.hpp"

namespace hba::io::detail {

// A cloud whose intensity vector is neither empty nor one per point would be
// written misaligned; refuse it.
inline void requireOneIntensityPerPoint(const PointCloud& cloud, const std::filesystem::path& path) {
  if (cloud.hasIntensity() && cloud.intensity.size() != cloud.size()) {
    failAt(path, "cannot write: the cloud has " + std::to_string(cloud.size()) + " points but " +
                     std::to_string(cloud.intensity.size()) + " intensities");
  }
}

}  // namespace hba::io::detail
