// Scans kept on disk after their first load: later loads give the same
// clouds, bit for bit, without asking the wrapped source again.
#include <gtest/gtest.h>

#include <tbb/parallel_for.h>

#include <atomic>

#include "io/spilled_scan_source.hpp"

namespace hba::io {
namespace {

// Counts its loads; scan i has i + 1 points, with intensity for even i.
class CountingSource : public io::ScanSource {
 public:
  std::size_t size() const override { return 40; }
  PointCloud load(std::size_t i) const override {
    ++loads;
    PointCloud cloud;
    for (std::size_t k = 0; k <= i; ++k) {
      const Vec3f p(0.1f * static_cast<float>(k), -3.3f + 1e-7f * static_cast<float>(i), 1e4f);
      if (i % 2 == 0) {
        cloud.add(p, static_cast<float>(k));
      } else {
        cloud.add(p);
      }
    }
    return cloud;
  }
  mutable std::atomic<int> loads{0};
};

void expectSame(const PointCloud& a, const PointCloud& b) {
  ASSERT_EQ(a.size(), b.size());
  EXPECT_EQ(a.hasIntensity(), b.hasIntensity());
  for (std::size_t k = 0; k < a.size(); ++k) EXPECT_EQ(a.points[k], b.points[k]);
  EXPECT_EQ(a.intensity, b.intensity);
}

TEST(SpilledScanSource, LaterLoadsGiveTheSameCloudsWithoutTheSource) {
  const CountingSource source;
  const SpilledScanSource spilled(source);
  ASSERT_EQ(spilled.size(), source.size());
  // The first pass in parallel, as the pyramid reads; then twice more.
  tbb::parallel_for(std::size_t{0}, spilled.size(),
                    [&](std::size_t i) { expectSame(spilled.load(i), source.load(i)); });
  const int after_first = source.loads.load();
  EXPECT_EQ(after_first, 2 * 40);  // the spilled source's and the comparison's
  for (int pass = 0; pass < 2; ++pass) {
    tbb::parallel_for(std::size_t{0}, spilled.size(), [&](std::size_t i) {
      const PointCloud kept = spilled.load(i);
      expectSame(kept, CountingSource{}.load(i));
    });
  }
  EXPECT_EQ(source.loads.load(), after_first) << "kept scans must not be read again";
}

}  // namespace
}  // namespace hba::io
