// Upper-layer keyframes live on disk: they round-trip exactly and leave
// nothing behind.
#include <gtest/gtest.h>

#include <filesystem>

#include "hba/io/kitti_bin.hpp"
#include "keyframe_store.hpp"
#include "test_support.hpp"

namespace hba::pyramid {
namespace {
namespace fs = std::filesystem;

TEST(KeyframeStore, RoundTripsPointsExactly) {
  PointCloud with, without;
  for (int i = 0; i < 100; ++i) {
    const Vec3f p(0.1f * static_cast<float>(i), -3.3f + 1e-7f * static_cast<float>(i), 1e5f);
    with.add(p, static_cast<float>(i));
    without.add(p);
  }
  const KeyframeStore store(2);
  EXPECT_EQ(store.size(), 2u);
  store.store(0, with);
  store.store(1, without);
  const PointCloud a = store.load(0);
  const PointCloud b = store.load(1);
  ASSERT_EQ(a.size(), with.size());
  ASSERT_EQ(b.size(), without.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a.points[i], with.points[i]);
    EXPECT_EQ(a.intensity[i], with.intensity[i]);
    EXPECT_EQ(b.points[i], without.points[i]);
  }
  const PointCloud empty;
  store.store(1, empty);
  EXPECT_TRUE(store.load(1).empty());
}

// Keyframe files are io's KITTI scans, byte for byte.
TEST(KeyframeStore, WritesKittiScans) {
  PointCloud cloud;
  for (int i = 0; i < 50; ++i) cloud.add(Vec3f(0.3f * static_cast<float>(i), 1.0f / 3.0f, -2.0f), 0.5f);
  const KeyframeStore store(1);
  store.store(0, cloud);
  hba::test::TempDir dir;
  io::writeKittiBin(dir / "expected.bin", cloud);
  EXPECT_EQ(hba::test::readText(store.folder() / "0.bin"), hba::test::readText(dir / "expected.bin"));
}

TEST(KeyframeStore, RemovesItsFolder) {
  fs::path folder;
  {
    const KeyframeStore store(1);
    store.store(0, PointCloud());
    folder = store.folder();
    EXPECT_TRUE(fs::is_directory(folder));
    EXPECT_EQ(folder.parent_path(), fs::temp_directory_path());
  }
  EXPECT_FALSE(fs::exists(folder));
}

}  // namespace
}  // namespace hba::pyramid
