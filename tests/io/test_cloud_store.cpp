// Upper-layer keyframes live on disk: they round-trip exactly and leave
// nothing behind.
#include <gtest/gtest.h>

#include <filesystem>

#include <tbb/parallel_for.h>

#include "hba/core/error.hpp"
#include "io/cloud_store.hpp"

namespace hba::io {
namespace {
namespace fs = std::filesystem;

TEST(CloudStore, RoundTripsPointsExactly) {
  PointCloud with, without;
  for (int i = 0; i < 100; ++i) {
    const Vec3f p(0.1f * static_cast<float>(i), -3.3f + 1e-7f * static_cast<float>(i), 1e5f);
    with.add(p, static_cast<float>(i));
    without.add(p);
  }
  const CloudStore store(2);
  EXPECT_EQ(store.size(), 2u);
  store.store(0, with);
  store.store(1, without);
  const PointCloud a = store.load(0);
  const PointCloud b = store.load(1);
  ASSERT_EQ(a.size(), with.size());
  ASSERT_EQ(b.size(), without.size());
  ASSERT_TRUE(a.hasIntensity());
  EXPECT_FALSE(b.hasIntensity());
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a.points[i], with.points[i]);
    EXPECT_EQ(a.intensity[i], with.intensity[i]);
    EXPECT_EQ(b.points[i], without.points[i]);
  }
  const PointCloud empty;
  store.store(1, empty);
  EXPECT_TRUE(store.load(1).empty());
  EXPECT_EQ(store.load(0).points, with.points);  // the others stay
  EXPECT_THROW(store.store(2, with), Error);
  EXPECT_THROW(store.load(2), Error);
}

// One file for all clouds (a file each cost more to create than a small
// scan takes to read), written from threads at once without loss.
TEST(CloudStore, KeepsEveryCloudInOneFileFromManyThreads) {
  constexpr std::size_t kClouds = 200;
  const CloudStore store(kClouds);
  const auto cloudOf = [](std::size_t i) {
    PointCloud cloud;
    for (std::size_t k = 0; k < 10 + i; ++k) cloud.add(Vec3f(float(i), float(k), 0.5f), float(i + k));
    return cloud;
  };
  tbb::parallel_for(std::size_t{0}, kClouds, [&](std::size_t i) { store.store(i, cloudOf(i)); });
  std::uintmax_t bytes = 0;
  for (std::size_t i = 0; i < kClouds; ++i) {
    const PointCloud expected = cloudOf(i);
    const PointCloud loaded = store.load(i);
    EXPECT_EQ(loaded.points, expected.points) << i;
    EXPECT_EQ(loaded.intensity, expected.intensity) << i;
    bytes += expected.size() * 16;
  }
  std::size_t files = 0;
  for (const auto& entry : fs::directory_iterator(store.folder())) {
    ++files;
    EXPECT_EQ(fs::file_size(entry.path()), bytes);
  }
  EXPECT_EQ(files, 1u);
}

TEST(CloudStore, RemovesItsFolder) {
  fs::path folder;
  {
    const CloudStore store(1);
    store.store(0, PointCloud());
    folder = store.folder();
    EXPECT_TRUE(fs::is_directory(folder));
    EXPECT_EQ(folder.parent_path(), fs::temp_directory_path());
  }
  EXPECT_FALSE(fs::exists(folder));
}

}  // namespace
}  // namespace hba::io
