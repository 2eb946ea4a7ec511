#include "hba/core/frame_cluster.hpp"

#include <cmath>

namespace hba {

FrameCluster::FrameCluster(std::uint32_t frame_index, const PointCluster& points)
    : frame(frame_index),
      count_(static_cast<std::uint32_t>(std::llround(points.count))),
      mean_(points.mean),
      scatter_{points.scatter(0, 0), points.scatter(0, 1), points.scatter(0, 2),
               points.scatter(1, 1), points.scatter(1, 2), points.scatter(2, 2)} {}

}  // namespace hba
