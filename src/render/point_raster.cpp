#include "point_raster.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "hba/render/colormap.hpp"

namespace hba::render {

PointRaster::PointRaster(int width, int height, int footprint_x, int footprint_y)
    : width_(std::max(width, 1)),
      height_(std::max(height, 1)),
      footprint_x_(std::clamp(footprint_x, 1, 64)),
      footprint_y_(std::clamp(footprint_y, 1, 64)),
      count_(static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_), 0),
      top_value_(count_.size(), -std::numeric_limits<float>::infinity()) {}

void PointRaster::add(double x, double y, float value) {
  if (!(std::abs(x) < 1e7 && std::abs(y) < 1e7)) return;  // far away or NaN
  const int x0 = static_cast<int>(std::floor(x - 0.5 * (footprint_x_ - 1)));
  const int y0 = static_cast<int>(std::floor(y - 0.5 * (footprint_y_ - 1)));
  for (int dy = 0; dy < footprint_y_; ++dy) {
    for (int dx = 0; dx < footprint_x_; ++dx) addPixel(x0 + dx, y0 + dy, value);
  }
}

void PointRaster::addPixel(int x, int y, float value) {
  if (x < 0 || y < 0 || x >= width_ || y >= height_) return;
  const std::size_t i =
      static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) + static_cast<std::size_t>(x);
  ++count_[i];
  top_value_[i] = std::max(top_value_[i], value);
}

void PointRaster::paint(Image& image, int left, int top, double value_low, double value_high) const {
  // Density that counts as "full brightness": the 90th percentile of occupied
  // pixels, so a few very dense pixels do not darken everything else.
  std::vector<std::uint32_t> occupied;
  for (std::uint32_t c : count_) {
    if (c > 0) occupied.push_back(c);
  }
  if (occupied.empty()) return;
  const auto rank = static_cast<std::ptrdiff_t>(0.9 * static_cast<double>(occupied.size() - 1));
  std::nth_element(occupied.begin(), occupied.begin() + rank, occupied.end());
  const double full = std::log1p(std::max<double>(occupied[static_cast<std::size_t>(rank)], 2.0));
  const double span = std::max(value_high - value_low, 1e-9);

  for (int y = 0; y < height_; ++y) {
    for (int x = 0; x < width_; ++x) {
      const std::size_t i =
          static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) + static_cast<std::size_t>(x);
      if (count_[i] == 0) continue;
      const double density = std::min(1.0, std::log1p(count_[i]) / full);
      const Rgb color =
          turbo(kColormapLow + (kColormapHigh - kColormapLow) * (top_value_[i] - value_low) / span);
      image.blend(left + x, top + y, color, 0.45 + 0.55 * density);
    }
  }
}

}  // namespace hba::render
