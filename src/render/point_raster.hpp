#pragma once
// Accumulates projected points per pixel (count and highest value), then
// paints them: colour from the value through the colormap, brightness from
// the point density (log scale), so dense structure (walls, poles) stands
// out from sparse ground. Private to render.
#include <cstdint>
#include <vector>

#include "hba/render/image.hpp"

namespace hba::render {

// The part of the colormap used for heights: its darkest ends would vanish
// on the dark background.
inline constexpr double kColormapLow = 0.08;
inline constexpr double kColormapHigh = 0.9;

class PointRaster {
 public:
  // Each point covers a footprint of footprint_x by footprint_y pixels (the
  // voxel size at the current zoom), so surfaces stay solid when zoomed in.
  PointRaster(int width, int height, int footprint_x = 1, int footprint_y = 1);
  // (x, y) in raster pixels: the footprint's centre; pixels outside are ignored.
  void add(double x, double y, float value);
  // Paints non-empty pixels into `image` with the raster's top-left at (left, top).
  void paint(Image& image, int left, int top, double value_low, double value_high) const;

 private:
  void addPixel(int x, int y, float value);

  int width_, height_, footprint_x_, footprint_y_;
  std::vector<std::uint32_t> count_;
  std::vector<float> top_value_;
};

}  // namespace hba::render
