// The dataset-level entry points: merge the maps, then draw them.
#include "hba/core/error.hpp"
#include "hba/eval/alignment.hpp"
#include "hba/eval/merged_map.hpp"
#include "hba/render/map_picture.hpp"

namespace hba::render {
namespace {

PointCloud mergedMap(const io::Dataset& dataset, const std::vector<Pose>& poses, const RenderSettings& settings) {
  eval::MapSettings map;
  map.voxel = settings.voxel;
  return eval::buildMergedMap(dataset, poses, map);
}

// Ground truth moved onto `reference` when both pair up by index; as given otherwise.
std::vector<Pose> alignedGroundTruth(const std::vector<Pose>& ground_truth, const std::vector<Pose>& reference) {
  if (ground_truth.size() != reference.size() || ground_truth.size() < 3) return ground_truth;
  const eval::Similarity s = eval::alignTrajectory(reference, ground_truth, eval::Alignment::SE3);
  std::vector<Pose> out;
  out.reserve(ground_truth.size());
  for (const Pose& p : ground_truth) out.push_back(s.apply(p));
  return out;
}

}  // namespace

void writeBeforeAfter(const io::Dataset& dataset, const std::vector<Pose>& before,
                      const std::vector<Pose>& after, const std::vector<Pose>* ground_truth,
                      const std::filesystem::path& out_png, const RenderSettings& settings) {
  std::vector<MapPanel> panels(2);
  panels[0].title = "initial poses";
  panels[0].map = mergedMap(dataset, before, settings);
  panels[0].trajectories.push_back({"initial", before, kInitialColor});
  panels[1].title = "optimized poses";
  panels[1].map = mergedMap(dataset, after, settings);
  panels[1].trajectories.push_back({"optimized", after, kOptimizedColor});
  if (ground_truth) {
    const std::vector<Pose> gt = alignedGroundTruth(*ground_truth, after);
    for (MapPanel& panel : panels) panel.trajectories.insert(panel.trajectories.begin(), {"ground truth", gt, kGroundTruthColor});
  }
  writePng(out_png, renderPanels(panels, settings).image);
}

void writeMapPicture(const io::Dataset& dataset, const std::vector<Pose>& poses,
                     const std::vector<Pose>* ground_truth, const std::filesystem::path& out_png,
                     const RenderSettings& settings) {
  std::vector<MapPanel> panels(1);
  panels[0].title = "map";
  panels[0].map = mergedMap(dataset, poses, settings);
  panels[0].trajectories.push_back({"poses", poses, kOptimizedColor});
  if (ground_truth) {
    panels[0].trajectories.insert(panels[0].trajectories.begin(),
                                  {"ground truth", alignedGroundTruth(*ground_truth, poses), kGroundTruthColor});
  }
  writePng(out_png, renderPanels(panels, settings).image);
}

}  // namespace hba::render
