#pragma once
// From voxel plane features to BA plane observations (their per-frame
// clusters), and the outlier filter on plane residuals.
#include <cstddef>
#include <utility>
#include <vector>

#include "hba/ba/plane_cost.hpp"
#include "hba/ba/plane_problem.hpp"
#include "hba/core/point_cloud.hpp"
#include "hba/voxel/plane_map.hpp"

namespace hba::ba {

// Indices (ascending) of the planes kept when the worst `reject_ratio`
// fraction by `residual` is dropped (ties broken by index, so the choice is
// deterministic). reject_ratio <= 0 keeps all.
std::vector<std::size_t> keepBestPlanes(const std::vector<double>& residual, double reject_ratio);

// One association: the plane features of `scans` at `poses` and their
// observations, minus the worst `reject_ratio` of planes by mean squared
// distance (not the sum, so large planes are not dropped for their size).
struct Association {
  voxel::PlaneExtraction extraction;  // the kept planes (their clusters moved to the problem)
  PlaneProblem problem{{}, 0};
  // problem.planeCosts() at the poses it was found at, computed by the
  // outlier filter anyway: a solver starting there needs no evaluation.
  std::vector<double> plane_costs;
  double cost() const;  // their sum, as problem.cost() adds them (same bits)
};

// Clouds of 4 M points or more (refinement blocks) hand the extraction's
// freed memory back to the system before returning (core/release_memory.hpp).
Association associate(const std::vector<const PointCloud*>& scans, const std::vector<Pose>& poses,
                      const voxel::PlaneSettings& planes, double reject_ratio);

// associate() spread over the members of `group` (a collective: every
// member calls it with the same scans and poses): each extracts the planes
// of its share of the root voxels, the outlier filter drops the same planes
// everywhere, and each member ends with whole chunks of the planes
// (problem.spread()). plane_costs are every plane's; the extraction is
// left empty. With one member, associate()'s association.
Association associateSpread(const std::vector<const PointCloud*>& scans, const std::vector<Pose>& poses,
                            const voxel::PlaneSettings& planes, double reject_ratio,
                            const dist::Group& group);

// associate() at root voxel `planes.voxel_size` and at `fine_voxel`, at the
// same poses: the same two associations, from one placing and hashing of the
// points (voxel::extractPlanesAtTwoVoxels).
std::pair<Association, Association> associateAtTwoVoxels(const std::vector<const PointCloud*>& scans,
                                                         const std::vector<Pose>& poses,
                                                         const voxel::PlaneSettings& planes,
                                                         double fine_voxel, double reject_ratio);

}  // namespace hba::ba
