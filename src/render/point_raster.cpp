#include "point_raster.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "hba/render/colormap.hpp"

namespace hba::render {

PointRaster::PointRaster(int width, int height)
    : width_(std::max(width, 1)), height_(std::max(height, 1)),
      count_(static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_), 0),
      top_value_(count_.size(), -std::numeric_limits<float>::infinity()) {}

void PointRaster::add(double x, double y, float value) {
  if (!(x >= 0.0 && y >= 0.0 && x < width_ && y < height_)) return;
  const std::size_t i = static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) + static_cast<std::size_t>(x);
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
      const std::size_t i = static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) + static_cast<std::size_t>(x);
      if (count_[i] == 0) continue;
      const double density = std::min(1.0, std::log1p(count_[i]) / full);
      const Rgb color = turbo(0.04 + 0.92 * (top_value_[i] - value_low) / span);
      image.blend(left + x, top + y, color, 0.35 + 0.65 * density);
    }
  }
}

}  // namespace hba::render
