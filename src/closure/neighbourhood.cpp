#include "neighbourhood.hpp"

#include <algorithm>

#include <tbb/parallel_for.h>

#include "hba/voxel/downsample.hpp"

namespace hba::closure {

FrameRange neighbourhoodFrames(std::size_t centre, std::size_t half_width, std::size_t count) {
  FrameRange range;
  range.first = centre > half_width ? centre - half_width : 0;
  range.last = std::min(count - 1, centre + half_width);
  return range;
}

PointCloud mergeNeighbourhood(const io::ScanSource& scans, const std::vector<Pose>& poses, std::size_t centre,
                              const FrameRange& frames, double voxel) {
  const std::size_t count = frames.last - frames.first + 1;
  std::vector<PointCloud> moved(count);
  const Pose centre_inverse = poses[centre].inverse();
  tbb::parallel_for(std::size_t{0}, count, [&](std::size_t k) {
    const std::size_t frame = frames.first + k;
    PointCloud cloud = scans.load(frame);
    const Pose to_centre = centre_inverse * poses[frame];
    for (std::size_t i = 0; i < cloud.size(); ++i)
      cloud.points[i] = (to_centre * cloud.world(i)).cast<float>();
    cloud.origin = Vec3::Zero();
    cloud.intensity.clear();
    moved[k] = std::move(cloud);
  });
  PointCloud merged;
  std::size_t total = 0;
  for (const PointCloud& cloud : moved) total += cloud.size();
  merged.reserve(total, false);
  for (const PointCloud& cloud : moved) {
    merged.points.insert(merged.points.end(), cloud.points.begin(), cloud.points.end());
  }
  return voxel::downsample(merged, voxel, 4);  // overlapping scans: several points a cell
}

}  // namespace hba::closure
