#pragma once
// One frame's share of a plane's points: their count, mean and scatter in
// that frame's own (sensor) coordinates, which a pose moves exactly, so that
// a plane's cost never needs its points again (BALM2).
#include <array>
#include <cstdint>

#include "hba/core/point_cluster.hpp"
#include "hba/core/types.hpp"

namespace hba {

// The points of one plane seen by one frame, in that frame's sensor
// coordinates, as the planes keep them: the count as an integer and the
// (symmetric) scatter as its upper triangle, 80 bytes where a PointCluster
// and its frame take 112. A refinement's planes hold millions: this is their
// memory, and what every cost evaluation reads.
struct FrameCluster {
  FrameCluster() = default;
  // `points.count` is a point count (a whole number below 2^32); the scatter
  // is kept as its upper triangle, mirrored on reading.
  FrameCluster(std::uint32_t frame_index, const PointCluster& points);

  double count() const { return static_cast<double>(count_); }
  const Vec3& mean() const { return mean_; }
  Mat3 scatter() const {
    Mat3 s;
    s << scatter_[0], scatter_[1], scatter_[2], scatter_[1], scatter_[3], scatter_[4], scatter_[2],
        scatter_[4], scatter_[5];
    return s;
  }

  std::uint32_t frame = 0;

 private:
  std::uint32_t count_ = 0;
  Vec3 mean_ = Vec3::Zero();
  std::array<double, 6> scatter_{};  // xx xy xz yy yz zz
};

}  // namespace hba
