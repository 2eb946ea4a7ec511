#include "draw.hpp"

#include <stb_easy_font.h>

#include <algorithm>
#include <cmath>

namespace hba::render {
namespace {

// Coverage of a pixel centre at distance d from a stroke's axis.
double coverage(double distance, double half_width) {
  return std::clamp(half_width + 0.5 - distance, 0.0, 1.0);
}

double distanceToSegment(const Pixel& p, const Pixel& a, const Pixel& b) {
  const Pixel ab = b - a;
  const double length_sq = ab.squaredNorm();
  const double t = length_sq > 0.0 ? std::clamp((p - a).dot(ab) / length_sq, 0.0, 1.0) : 0.0;
  return (p - (a + t * ab)).norm();
}

void strokePolyline(Image& image, const std::vector<Pixel>& points, Rgb color, double width, double alpha,
                    const Clip& clip) {
  const int clip_x1 = std::min(image.width(), clip.x1), clip_y1 = std::min(image.height(), clip.y1);
  const double half = 0.5 * width;
  // Per pixel, the best coverage over all segments, so joints are not drawn twice.
  for (std::size_t k = 0; k + 1 < points.size(); ++k) {
    const Pixel& a = points[k];
    const Pixel& b = points[k + 1];
    const int x0 = static_cast<int>(std::floor(std::min(a.x(), b.x()) - half - 1));
    const int x1 = static_cast<int>(std::ceil(std::max(a.x(), b.x()) + half + 1));
    const int y0 = static_cast<int>(std::floor(std::min(a.y(), b.y()) - half - 1));
    const int y1 = static_cast<int>(std::ceil(std::max(a.y(), b.y()) + half + 1));
    for (int y = std::max(y0, clip.y0); y <= std::min(y1, clip_y1 - 1); ++y) {
      for (int x = std::max(x0, clip.x0); x <= std::min(x1, clip_x1 - 1); ++x) {
        const Pixel centre(x + 0.5, y + 0.5);
        double c = coverage(distanceToSegment(centre, a, b), half);
        if (c <= 0.0) continue;
        // Skip what the previous segment already covered (avoids dark joints).
        if (k > 0 && coverage(distanceToSegment(centre, points[k - 1], a), half) >= c) continue;
        image.blend(x, y, color, c * alpha);
      }
    }
  }
}

}  // namespace

void fillRect(Image& image, int x0, int y0, int x1, int y1, Rgb color, double alpha) {
  for (int y = std::max(y0, 0); y < std::min(y1, image.height()); ++y) {
    for (int x = std::max(x0, 0); x < std::min(x1, image.width()); ++x) image.blend(x, y, color, alpha);
  }
}

void strokeRect(Image& image, int x0, int y0, int x1, int y1, Rgb color, double alpha) {
  fillRect(image, x0, y0, x1, y0 + 1, color, alpha);
  fillRect(image, x0, y1 - 1, x1, y1, color, alpha);
  fillRect(image, x0, y0 + 1, x0 + 1, y1 - 1, color, alpha);
  fillRect(image, x1 - 1, y0 + 1, x1, y1 - 1, color, alpha);
}

void drawPolyline(Image& image, const std::vector<Pixel>& points, Rgb color, double width, const Clip& clip) {
  strokePolyline(image, points, Rgb{0, 0, 0}, width + 2.5, 0.6, clip);
  strokePolyline(image, points, color, width, 1.0, clip);
}

void drawDisc(Image& image, const Pixel& centre, double radius, Rgb color, double alpha) {
  for (int y = static_cast<int>(centre.y() - radius - 1); y <= centre.y() + radius + 1; ++y) {
    for (int x = static_cast<int>(centre.x() - radius - 1); x <= centre.x() + radius + 1; ++x) {
      const double d = (Pixel(x + 0.5, y + 0.5) - centre).norm();
      image.blend(x, y, color, alpha * coverage(d, radius - 0.5));
    }
  }
}

void drawText(Image& image, int x, int y, const std::string& text, Rgb color, int scale) {
  // stb_easy_font emits axis-aligned quads (4 vertices of 16 bytes) in font pixels.
  std::vector<char> buffer(text.size() * 300 + 64);
  std::string copy = text;
  const int quads =
      stb_easy_font_print(0, 0, copy.data(), nullptr, buffer.data(), static_cast<int>(buffer.size()));
  for (int q = 0; q < quads; ++q) {
    const auto* v = reinterpret_cast<const float*>(buffer.data() + q * 64);
    const float qx0 = v[0], qy0 = v[1];  // first vertex: top-left
    const float qx1 = v[8], qy1 = v[9];  // third vertex: bottom-right
    fillRect(image, x + static_cast<int>(qx0 * scale), y + static_cast<int>(qy0 * scale),
             x + static_cast<int>(qx1 * scale), y + static_cast<int>(qy1 * scale), color);
  }
}

int textWidth(const std::string& text, int scale) {
  std::string copy = text;
  return stb_easy_font_width(copy.data()) * scale;
}

int textHeight(int scale) { return 7 * scale; }

}  // namespace hba::render
