// The report's read and downsample times come from wrappers around a
// layer's source: reading is the inner source's time, downsampling the rest.
#include <gtest/gtest.h>

#include <chrono>
#include <thread>
#include <vector>

#include "hba/io/scan_source.hpp"
#include "hba/voxel/downsample.hpp"
#include "timed_clouds.hpp"

namespace hba::pyramid {
namespace {

// Takes `delay` per load; scan i is a dense little cube of points.
class SlowSource : public io::ScanSource {
 public:
  explicit SlowSource(std::chrono::milliseconds delay) : delay_(delay) {}
  std::size_t size() const override { return 3; }
  PointCloud load(std::size_t i) const override {
    std::this_thread::sleep_for(delay_);
    PointCloud cloud;
    for (int k = 0; k < 20000; ++k) {
      cloud.add(Vec3f(0.01f * static_cast<float>(k % 100), 0.01f * static_cast<float>(k / 100 % 100),
                      static_cast<float>(i)));
    }
    return cloud;
  }

 private:
  std::chrono::milliseconds delay_;
};

TEST(TimedClouds, ReadingIsTheSourcesTimeAndDownsamplingTheRest) {
  const SlowSource slow(std::chrono::milliseconds(20));
  const TimedClouds clouds(slow, 0.1);
  EXPECT_EQ(clouds.seconds().read, 0.0);
  ASSERT_EQ(clouds.source().size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) {
    const PointCloud loaded = clouds.source().load(i);
    const PointCloud expected = voxel::downsample(slow.load(i), 0.1);
    ASSERT_EQ(loaded.size(), expected.size());
    EXPECT_EQ(loaded.points, expected.points);
  }
  const LoadSeconds seconds = clouds.seconds();
  EXPECT_GE(seconds.read, 3 * 0.020);
  EXPECT_GT(seconds.downsample, 0.0);
  // The sleeps are reading, not downsampling.
  EXPECT_LT(seconds.downsample, seconds.read);
}

TEST(TimedClouds, StoredCloudsAreOnlyRead) {
  const SlowSource slow(std::chrono::milliseconds(5));
  const TimedClouds clouds(slow);
  EXPECT_EQ(clouds.source().load(1).size(), 20000u);
  EXPECT_GE(clouds.seconds().read, 0.005);
  EXPECT_EQ(clouds.seconds().downsample, 0.0);
}

// A layer's wrapped source (timed, downsampled, kept on disk) tells the
// scans' sizes as the source it wraps does: the windows are shared out by them.
TEST(TimedClouds, TellTheScansSizesAsTheirSourceDoes) {
  std::vector<PointCloud> scans(3);
  for (std::size_t i = 0; i < scans.size(); ++i) {
    for (std::size_t k = 0; k < 10 * (i + 1); ++k) scans[i].add(Vec3f(static_cast<float>(k), 0.0f, 0.0f));
  }
  const io::MemoryScanSource source(scans);
  for (const bool keep : {false, true}) {
    const TimedClouds clouds(source, 0.5, keep);
    for (std::size_t i = 0; i < scans.size(); ++i) EXPECT_EQ(clouds.source().sizeHint(i), 10.0 * (i + 1));
  }
}

}  // namespace
}  // namespace hba::pyramid
