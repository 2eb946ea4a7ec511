#pragma once
// Coarse alignment of two local maps in bird's-eye view: a correlative search
// over heading and horizontal shift (z is assumed roughly up), scoring the
// share of the `to` map's structure cells (walls, poles, trunks: cells whose
// points span some height, so the ground everywhere does not count) that
// land on the `from` map's. Coarse level over the whole range on a dilated
// grid, then a fine level around its best.
#include <vector>

#include "hba/core/point_cloud.hpp"
#include "hba/core/pose.hpp"

namespace hba::closure {

struct BirdsEyeSearchSettings {
  double radius_m = 0.0;  // +- horizontal shift around the guess
  double yaw_deg = 0.0;   // +- heading around the guess
  double cell_m = 0.5;    // coarse cell and shift step
  double structure_height_m = 0.5;
  double ambiguous_distance_m = 2.0;
  double ambiguous_yaw_deg = 5.0;
};

struct BirdsEyeMatch {
  Pose relative;                    // the guess corrected by the best offset
  double score = 0.0;               // coarse level: share of structure cells matched at the best offset
  double second_score = 0.0;        // the best offset far (ambiguous_*) from it
  std::size_t structure_cells = 0;  // of the `to` map
};

// `guess` places `to_map` in `from_map`'s frame. Deterministic.
BirdsEyeMatch searchBirdsEye(const PointCloud& from_map, const PointCloud& to_map, const Pose& guess,
                             const BirdsEyeSearchSettings& settings);

}  // namespace hba::closure
