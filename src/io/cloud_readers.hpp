#pragma once
// Every scan reader for either kind of cloud: PointCloud (hba's, float
// relative to an origin) or WideCloud (double, as stored). Each is defined
// with its format and instantiated there for both.
#include <filesystem>

#include "hba/core/point_cloud.hpp"
#include "hba/io/wide_cloud.hpp"

namespace hba::io::detail {

template <typename Cloud>
Cloud readPcdAs(const std::filesystem::path& path);
template <typename Cloud>
Cloud readPlyAs(const std::filesystem::path& path);
template <typename Cloud>
Cloud readKittiBinAs(const std::filesystem::path& path);
template <typename Cloud>
Cloud readLasAs(const std::filesystem::path& path);

}  // namespace hba::io::detail
