#pragma once
// Small antialiased drawing primitives on an Image (private to render).
#include <string>
#include <vector>

#include "hba/core/types.hpp"
#include "hba/render/image.hpp"

namespace hba::render {

using Pixel = Eigen::Vector2d;  // sub-pixel position, x right, y down

// Pixels [x0, x1) x [y0, y1) that a drawing may touch.
struct Clip {
  int x0 = 0, y0 = 0, x1 = 1 << 30, y1 = 1 << 30;
};

void fillRect(Image& image, int x0, int y0, int x1, int y1, Rgb color, double alpha = 1.0);
void strokeRect(Image& image, int x0, int y0, int x1, int y1, Rgb color, double alpha = 1.0);
// A polyline of the given width with a darker halo so it reads on any map colour.
void drawPolyline(Image& image, const std::vector<Pixel>& points, Rgb color, double width,
                  const Clip& clip = {});
void drawDisc(Image& image, const Pixel& centre, double radius, Rgb color, double alpha = 1.0);

// Text with the stb_easy_font bitmap font, each font pixel `scale` pixels wide;
// (x, y) is the top-left corner. textWidth/textHeight measure in pixels.
void drawText(Image& image, int x, int y, const std::string& text, Rgb color, int scale = 2);
int textWidth(const std::string& text, int scale = 2);
int textHeight(int scale = 2);

}  // namespace hba::render
