#pragma once
// Pictures of merged maps: a bird's-eye view coloured by height (density
// shading makes walls and poles stand out from the floor), an optional side
// view below it (horizontal axis vs z, to see vertical drift and doubled
// floors), trajectories drawn on top, a legend, a height bar and a scale bar.
// Several panels sit side by side and share one view, so "before" and
// "after" compare pixel for pixel.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "hba/core/memory_budget.hpp"
#include "hba/core/point_cloud.hpp"
#include "hba/core/pose.hpp"
#include "hba/io/scan_source.hpp"
#include "hba/render/image.hpp"

namespace hba::render {

// An axis-aligned region of the world's x-y plane, in metres.
struct Box2 {
  double xmin = 0, ymin = 0, xmax = 0, ymax = 0;
};
// Parses "xmin,ymin,xmax,ymax"; throws hba::Error if malformed or empty.
Box2 parseBox(const std::string& text);

struct RenderSettings {
  int width = 1800;  // whole picture, pixels
  int height = 1100;
  double voxel = 0.1;  // m, downsampling of each merged map
  // The scans come downsampled at this voxel already (m; 0: as recorded):
  // at `voxel` or coarser, the before/after picture takes them as they are.
  double scans_voxel = 0.0;
  std::optional<Box2> crop;  // show only this region (at full resolution)
  bool side_view = true;     // add the side strip under each bird's-eye view
  // Colour by the panels' `values` on this scale instead of by height.
  struct ValueScale {
    double low = 0.0, high = 1.0;
    std::string low_label, high_label;  // "plane thickness 0 cm", "3 cm"
  };
  std::optional<ValueScale> value_scale;
  // The maps a picture is drawn from stop (MemoryExceeded) once the
  // process outgrows it. No limit by default.
  MemoryBudget budget;
};

// Distinct trajectory colours, chosen to stand out from the height colours.
inline constexpr Rgb kInitialColor{255, 70, 200};      // magenta
inline constexpr Rgb kOptimizedColor{245, 245, 245};   // white
inline constexpr Rgb kGroundTruthColor{40, 255, 140};  // green

struct TrajectoryLayer {
  std::string label;
  std::vector<Pose> poses;
  Rgb color;
};

struct MapPanel {
  std::string title;
  PointCloud map;  // world frame
  // One per map point when the settings have a value_scale (< 0: not drawn).
  std::vector<float> values;
  std::vector<TrajectoryLayer> trajectories;
};

// World x-y to picture pixels for one bird's-eye view (x right, y up).
struct TopViewTransform {
  double origin_x = 0, origin_y = 0;  // world point at the view's top-left corner
  double pixels_per_meter = 1;
  int left = 0, top = 0;  // the view's top-left pixel in the picture
  Eigen::Vector2d toPixel(double x, double y) const {
    return {left + (x - origin_x) * pixels_per_meter, top + (origin_y - y) * pixels_per_meter};
  }
};

struct Picture {
  Image image;
  std::vector<TopViewTransform> top_views;  // one per panel
  // The text drawn: the colour bar's two ends ("z -1.0 m", "27 m (2-98 %)")
  // and the side views' caption (empty without side views).
  std::string bar_low, bar_high, side_caption;
};

// Draws the panels side by side with one shared view. Throws hba::Error.
Picture renderPanels(const std::vector<MapPanel>& panels, const RenderSettings& settings);

// For `hba optimize`: merges the scans once with `before` and once
// with `after` (one pose per scan each), and writes the two maps side by side
// ("initial poses" left, "optimized poses" right) with the trajectories
// drawn on them; `ground_truth` (may be null) is drawn on both after a rigid
// alignment onto `after`, since ground truth may live in another frame.
// Without a crop, a row below zooms on where planes got thinnest (7/10 of
// settings.height tall), when some did. The PNG is written atomically;
// returns its size. Throws hba::Error.
PictureSize writeBeforeAfter(const io::ScanSource& scans, const std::vector<Pose>& before,
                             const std::vector<Pose>& after, const std::vector<Pose>* ground_truth,
                             const std::filesystem::path& out_png, const RenderSettings& settings = {});

// One panel: the map of `poses` with that trajectory (and ground truth).
// Returns the size written.
PictureSize writeMapPicture(const io::ScanSource& scans, const std::vector<Pose>& poses,
                            const std::vector<Pose>* ground_truth, const std::filesystem::path& out_png,
                            const RenderSettings& settings = {});

}  // namespace hba::render
