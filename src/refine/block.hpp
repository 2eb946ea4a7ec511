#pragma once
// One block of the refinement: consecutive frames held at once (the memory
// bound), checked against the input's planes and refined.
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "consistency.hpp"
#include "hba/ba/association.hpp"
#include "hba/core/point_cloud.hpp"
#include "hba/core/pose.hpp"
#include "hba/graph/factors.hpp"
#include "hba/io/scan_source.hpp"
#include "refinement.hpp"

namespace hba::refine {

// The scans of frames [first, end), at the refinement's density.
struct Block {
  std::size_t first = 0;
  std::size_t end = 0;
  std::vector<PointCloud> clouds;
  std::size_t points = 0;
};

// Loads frames from `first` on until `max_points` are held (at least two
// frames, unless the sequence ends), and never beyond `last_end`.
Block loadBlock(const io::ScanSource& scans, std::size_t first, std::size_t max_points, double voxel,
                std::size_t last_end = SIZE_MAX);

// A block's input poses, moved rigidly onto `result` at its first frame.
std::vector<Pose> inputOnto(const std::vector<Pose>& initial, const std::vector<Pose>& result,
                            std::size_t first, std::size_t end);

std::vector<Pose> slice(const std::vector<Pose>& poses, std::size_t first, std::size_t end);

// What one block did; the caller sums the blocks.
struct BlockOutcome {
  explicit BlockOutcome(FixedPlaneMap input_planes) : map(std::move(input_planes)) {}
  FixedPlaneMap map;        // the input's planes, which judge the block
  std::vector<Pose> poses;  // the block's final poses
  double input_rms = 0.0;   // on `map`
  double hierarchy_rms = 0.0;
  double final_rms = 0.0;
  std::vector<double> region_input_rms;
  std::vector<double> region_final_rms;
  bool hierarchy_rejected = false;
  bool hierarchy_insignificant = false;  // not worse, but no gain beyond fitting the noise
  bool final_rejected = false;
  bool refined = false;
  ba::RefinementResult refinement;  // when refined (its poses moved to `poses`)
  std::size_t position_priors = 0;
  StageNotes notes;
};

// A block's input planes found before refineBlock, at `poses`.
struct InputPlanes {
  std::vector<Pose> poses;
  ba::Association association;
};

// The block's self-check, and its refinement when `refines`: from the
// hierarchy's poses (`result`), or from the input's where the hierarchy made
// the map blurrier. `index` counts blocks from 0: later blocks stay held at
// their first frame, which the block before placed.
// `found_before`: the input's planes found already, taken where they are
// at the block's input poses.
BlockOutcome refineBlock(const Block& block, std::size_t index, const std::vector<Pose>& initial,
                         const std::vector<Pose>& result, const std::vector<double>& steps,
                         const std::vector<graph::PositionPriorFactor>& priors,
                         const RefineSettings& settings, bool refines, InputPlanes* found_before = nullptr);

}  // namespace hba::refine
