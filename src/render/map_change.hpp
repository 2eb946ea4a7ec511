#pragma once
// Where a map changed (private to render): the thickness of its planes and
// the square where optimization made them thinnest, for the zoomed
// before/after row of before_after.png.
#include <optional>
#include <vector>

#include "hba/core/point_cloud.hpp"
#include "hba/render/map_picture.hpp"

namespace hba::render {

// Per point: the thickness (m) of the plane around it, the square root of
// the smallest eigenvalue of the covariance of the map's points in its
// `cell` voxel, where those points form a plane (a wall seen twice, 4 cm
// apart, is about 2 cm thick; a crisp one a few mm); -1 elsewhere (too few
// points, or no plane: foliage, edges).
std::vector<float> planeThickness(const PointCloud& map, double cell);

// The square (side `side`, m) where the planes got thinner the most, summed
// over its voxels; nothing if no square's planes got thinner by 2 mm on
// average (a rigid shift of the whole map changes nothing).
std::optional<Box2> mostThinnedRegion(const PointCloud& before, const std::vector<float>& before_thickness,
                                      const PointCloud& after, const std::vector<float>& after_thickness,
                                      double cell, double side);

}  // namespace hba::render
