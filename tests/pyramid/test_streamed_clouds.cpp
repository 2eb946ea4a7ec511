// Clouds are loaded once, when a batch first needs them, and dropped after.
#include <gtest/gtest.h>

#include <atomic>
#include <memory>
#include <stdexcept>

#include "streamed_clouds.hpp"

namespace hba::pyramid {
namespace {

// Frame i has i + 1 points; counts how often each frame is loaded.
class CountingSource : public io::ScanSource {
 public:
  explicit CountingSource(std::size_t n) : n_(n), loads_(new std::atomic<int>[n]) {
    for (std::size_t i = 0; i < n; ++i) loads_[i] = 0;
  }
  std::size_t size() const override { return n_; }
  PointCloud load(std::size_t i) const override {
    ++loads_[i];
    PointCloud cloud;
    for (std::size_t k = 0; k <= i; ++k) cloud.add(Vec3f(static_cast<float>(k), 0.0f, 0.0f));
    return cloud;
  }
  int loads(std::size_t i) const { return loads_[i]; }

 private:
  std::size_t n_;
  std::unique_ptr<std::atomic<int>[]> loads_;
};

TEST(StreamedClouds, LoadsEachFrameOnceAndDropsThoseBehind) {
  const CountingSource source(10);
  StreamedClouds clouds(source);
  clouds.keepRange(0, 4);
  EXPECT_EQ(clouds.pointsLoaded(), 1u + 2u + 3u + 4u);
  clouds.keepRange(2, 6);
  for (std::size_t i = 0; i < 6; ++i) EXPECT_EQ(source.loads(i), 1) << "frame " << i;
  EXPECT_EQ(source.loads(6), 0);
  EXPECT_EQ(clouds.pointsLoaded(), 21u);
  EXPECT_THROW(clouds.get(1), std::out_of_range);
  EXPECT_EQ(clouds.get(2)->size(), 3u);
}

TEST(StreamedClouds, CloudsOfAWindowAreItsFramesInOrder) {
  const CountingSource source(10);
  StreamedClouds clouds(source);
  clouds.keepRange(3, 8);
  const auto window = clouds.cloudsOf(Window{4, 3});
  ASSERT_EQ(window.size(), 3u);
  EXPECT_EQ(window[0]->size(), 5u);
  EXPECT_EQ(window[1]->size(), 6u);
  EXPECT_EQ(window[2]->size(), 7u);
  EXPECT_THROW(clouds.cloudsOf(Window{7, 2}), std::out_of_range);
}

}  // namespace
}  // namespace hba::pyramid
