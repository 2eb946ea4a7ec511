#pragma once
// The self-check's figures by region, and each block's map kept on disk so
// that the groups' result is measured again without reading every block's
// scans once more.
#include <cstddef>
#include <filesystem>
#include <memory>
#include <vector>

#include "consistency.hpp"
#include "hba/core/pose.hpp"
#include "io/cloud_store.hpp"

namespace hba::refine {

// Frames [first, end) of one block.
struct FrameSpan {
  std::size_t first = 0;
  std::size_t end = 0;
};

// The self-check's figures for one stretch of frames.
struct RegionFigures {
  std::size_t first_frame = 0;
  double input_rms = 0.0;
  double final_rms = 0.0;
};

// Appends the regions of a block that starts at frame `first`.
void addRegions(const FixedPlaneMap& map, const std::vector<double>& region_input,
                const std::vector<double>& region_final, std::size_t first, std::vector<RegionFigures>& out);

// Running sums of squared plane distances and points over blocks.
struct RmsSum {
  double squares = 0.0;
  double points = 0.0;
  void add(double rms, double n);
  double rms() const;
};

// Each block's map on disk (44 bytes a plane cluster, hundreds of MB on long
// sequences): not held in memory while later blocks are refined. The folder
// (a private temporary folder, removed at the end and on Ctrl-C) is made
// with the first map.
class BlockMaps {
 public:
  void keep(const FixedPlaneMap& map);
  FixedPlaneMap load(std::size_t block) const;

 private:
  std::unique_ptr<io::CloudStore> folder_;
  std::vector<std::filesystem::path> files_;  // per block
  std::vector<const dist::Group*> groups_;    // per block: what its map is spread over
};

// The final poses measured again on each block's kept map (the groups
// moved them after the blocks were checked): the overall final RMS, and
// `regions` filled again.
double remeasure(const std::vector<Pose>& initial, const std::vector<Pose>& result,
                 const std::vector<FrameSpan>& spans, const BlockMaps& kept,
                 std::vector<RegionFigures>& regions);

}  // namespace hba::refine
