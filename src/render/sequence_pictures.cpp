// The entry points on a sequence of scans: merge the maps, then draw them.
#include <tbb/parallel_invoke.h>

#include "aligned_ground_truth.hpp"
#include "before_after_maps.hpp"
#include "core/release_memory.hpp"
#include "hba/core/error.hpp"
#include "hba/eval/merged_map.hpp"
#include "hba/render/map_picture.hpp"
#include "map_change.hpp"

#include <algorithm>
#include <array>
#include <limits>
#include <optional>

namespace hba::render {
namespace {

PointCloud mergedMap(const io::ScanSource& scans, const std::vector<Pose>& poses,
                     const RenderSettings& settings) {
  eval::MapSettings map;
  map.voxel = settings.voxel;
  map.budget = settings.budget;
  return eval::buildMergedMap(scans, poses, map);
}

}  // namespace

// Centimetre corrections are invisible at the scale of a whole map: a second
// row zooms on the square where the planes got thinnest, coloured by their
// thickness (a doubled wall is thick, a crisp one thin). Nothing when no
// plane got thinner. Its points come from the scans taken near the square.
std::optional<Image> thicknessZoom(const io::ScanSource& scans,
                                   const std::array<const std::vector<Pose>*, 2>& poses,
                                   const BeforeAfterMaps& maps, const std::vector<MapPanel>& panels,
                                   const RenderSettings& settings) {
  Eigen::AlignedBox3d box;
  for (const Pose& pose : *poses[1]) box.extend(pose.t);
  const double extent = box.isEmpty() ? 0.0 : box.sizes().head<2>().maxCoeff() + 20.0;  // scans reach beyond
  const double side = std::clamp(extent / 6.0, 6.0, 40.0);
  const PlaneThickness before(maps.moments[0]), after(maps.moments[1]);
  const std::optional<Box2> region = mostThinnedRegion(before, after, side);
  if (!region) return std::nullopt;
  // Scans within a few tens of metres give the square its dense points.
  constexpr double kReach = 40.0;
  std::array<PointCloud, 2> fine =
      squareMaps(scans, poses, settings.voxel, *region, kReach, settings.scans_voxel, settings.budget);
  std::vector<MapPanel> zoom(2);
  for (std::size_t k = 0; k < 2; ++k) {
    zoom[k].values = (k == 0 ? before : after).perPoint(fine[k]);
    zoom[k].map = std::move(fine[k]);
    zoom[k].trajectories = panels[k].trajectories;
  }
  zoom[0].title = "initial: plane thickness where it fell most";
  zoom[1].title = "optimized: plane thickness";
  RenderSettings z = settings;
  z.height = settings.height * 7 / 10;
  z.crop = *region;
  z.side_view = false;
  z.value_scale = RenderSettings::ValueScale{0.0, 0.03, "plane thickness 0 cm", "3 cm"};
  return renderPanels(zoom, z).image;
}

namespace {

// The overview row and, when some plane got thinner, the zoom row below it.
// The maps they are drawn from are gone when this returns: the PNG is
// encoded without them.
std::vector<Image> drawBeforeAfter(const io::ScanSource& scans,
                                   const std::array<const std::vector<Pose>*, 2>& poses,
                                   std::vector<MapPanel> panels, const RenderSettings& settings) {
  constexpr double kThicknessCell = 1.0;  // m: a patch of wall
  // Two panels side by side: each about half the picture's width.
  BeforeAfterMaps maps = streamBeforeAfter(scans, poses, settings.voxel, settings.width / 2, kThicknessCell,
                                           settings.scans_voxel, settings.budget);
  for (std::size_t k = 0; k < 2; ++k) panels[k].map = std::move(maps.overview[k]);
  // The scans' chunks were made and freed on several threads, each in its
  // own heap: handed back, so that the drawing's buffers do not stack on them.
  releaseFreedMemory();
  RenderSettings overview = settings;
  overview.voxel = maps.overview_voxel;  // the points' footprint
  // The zoom's scans are read while the overview is drawn (mostly on one core).
  std::optional<Image> whole, zoom;
  tbb::parallel_invoke([&] { whole = renderPanels(panels, overview).image; },
                       [&] { zoom = thicknessZoom(scans, poses, maps, panels, settings); });
  std::vector<Image> rows;
  rows.push_back(std::move(*whole));
  if (zoom) rows.push_back(std::move(*zoom));
  return rows;
}

}  // namespace

PictureSize writeBeforeAfter(const io::ScanSource& scans, const std::vector<Pose>& before,
                             const std::vector<Pose>& after, const std::vector<Pose>* ground_truth,
                             const std::filesystem::path& out_png, const RenderSettings& settings) {
  const std::array<const std::vector<Pose>*, 2> poses{&before, &after};
  std::vector<MapPanel> panels(2);
  panels[0].title = "initial poses";
  panels[0].trajectories.push_back({"initial", before, kInitialColor});
  panels[1].title = "optimized poses";
  panels[1].trajectories.push_back({"optimized", after, kOptimizedColor});
  if (ground_truth) {
    const std::vector<Pose> gt = alignedGroundTruth(*ground_truth, after);
    for (MapPanel& panel : panels)
      panel.trajectories.insert(panel.trajectories.begin(), {"ground truth", gt, kGroundTruthColor});
  }
  if (settings.crop) {  // one region at full resolution, no zoom row
    std::array<PointCloud, 2> fine =
        squareMaps(scans, poses, settings.voxel, *settings.crop, std::numeric_limits<double>::infinity(),
                   settings.scans_voxel, settings.budget);
    for (std::size_t k = 0; k < 2; ++k) panels[k].map = std::move(fine[k]);
    return writePng(out_png, renderPanels(panels, settings).image);
  }
  // What the caller freed (an optimization's heap) stays resident while the
  // picture's buffers come as fresh pages: handed back first, the picture
  // adds nothing to the caller's peak memory.
  releaseFreedMemory();
  const std::vector<Image> rows = drawBeforeAfter(scans, poses, std::move(panels), settings);
  std::vector<const Image*> stack;
  for (const Image& row : rows) stack.push_back(&row);
  return writePng(out_png, stack);
}

PictureSize writeMapPicture(const io::ScanSource& scans, const std::vector<Pose>& poses,
                            const std::vector<Pose>* ground_truth, const std::filesystem::path& out_png,
                            const RenderSettings& settings) {
  std::vector<MapPanel> panels(1);
  panels[0].title = "map";
  panels[0].map = mergedMap(scans, poses, settings);
  panels[0].trajectories.push_back({"poses", poses, kOptimizedColor});
  if (ground_truth) {
    panels[0].trajectories.insert(
        panels[0].trajectories.begin(),
        {"ground truth", alignedGroundTruth(*ground_truth, poses), kGroundTruthColor});
  }
  return writePng(out_png, renderPanels(panels, settings).image);
}

}  // namespace hba::render
