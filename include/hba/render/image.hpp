#pragma once
// An 8-bit RGB raster and its PNG output.
#include <cstdint>
#include <filesystem>
#include <vector>

namespace hba::render {

struct Rgb {
  std::uint8_t r = 0, g = 0, b = 0;
};

class Image {
 public:
  Image(int width, int height, Rgb fill = {});
  int width() const { return width_; }
  int height() const { return height_; }
  bool contains(int x, int y) const { return x >= 0 && y >= 0 && x < width_ && y < height_; }
  Rgb at(int x, int y) const;
  void set(int x, int y, Rgb color);  // ignores pixels outside the image
  // Mixes `color` over the pixel with opacity alpha in [0, 1].
  void blend(int x, int y, Rgb color, double alpha);
  // Copies `source` with its top-left corner at (left, top), clipped.
  void paste(const Image& source, int left, int top);
  const std::vector<std::uint8_t>& pixels() const { return pixels_; }  // row-major RGB

 private:
  std::size_t offsetOf(int x, int y) const;

  int width_, height_;
  std::vector<std::uint8_t> pixels_;
};

// The PNG file of `image` (libpng, 8-bit RGB). Throws hba::Error.
std::vector<std::uint8_t> encodePng(const Image& image);
// One PNG of the images one above the other, the first at the top, read
// in place (no stacked copy). They must be equally wide. Throws hba::Error.
std::vector<std::uint8_t> encodePng(const std::vector<const Image*>& stack);

// A written picture's size in pixels.
struct PictureSize {
  int width = 0, height = 0;
};

// Encodes as PNG and writes atomically; returns the size written (a stack
// is as tall as its images together). Throws hba::Error naming the file.
PictureSize writePng(const std::filesystem::path& path, const Image& image);
PictureSize writePng(const std::filesystem::path& path, const std::vector<const Image*>& stack);

}  // namespace hba::render
