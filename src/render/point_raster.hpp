#pragma once
// Accumulates projected points per pixel (count and highest value), then
// paints them: colour from the value through the colormap, brightness from
// the point density (log scale), so dense structure (walls, poles) stands
// out from sparse ground. Private to render.
#include <cstdint>
#include <vector>

#include "hba/render/image.hpp"

namespace hba::render {

class PointRaster {
 public:
  PointRaster(int width, int height);
  // (x, y) in raster pixels; points outside are ignored.
  void add(double x, double y, float value);
  // Paints non-empty pixels into `image` with the raster's top-left at (left, top).
  void paint(Image& image, int left, int top, double value_low, double value_high) const;

 private:
  int width_, height_;
  std::vector<std::uint32_t> count_;
  std::vector<float> top_value_;
};

}  // namespace hba::render
