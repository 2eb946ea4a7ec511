#include "hba/render/image.hpp"

#include <stb_image_write.h>

#include <algorithm>
#include <string>

#include "hba/core/atomic_file.hpp"
#include "hba/core/error.hpp"

namespace hba::render {

Image::Image(int width, int height, Rgb fill) : width_(width), height_(height) {
  if (width <= 0 || height <= 0 || width > 32768 || height > 32768) {
    throw Error("image size " + std::to_string(width) + "x" + std::to_string(height) +
                " is out of range (1..32768)");
  }
  pixels_.resize(static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 3);
  for (std::size_t i = 0; i < pixels_.size(); i += 3) {
    pixels_[i] = fill.r;
    pixels_[i + 1] = fill.g;
    pixels_[i + 2] = fill.b;
  }
}

Rgb Image::at(int x, int y) const {
  const std::size_t i =
      (static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) + static_cast<std::size_t>(x)) * 3;
  return {pixels_.at(i), pixels_.at(i + 1), pixels_.at(i + 2)};
}

void Image::set(int x, int y, Rgb color) { blend(x, y, color, 1.0); }

void Image::blend(int x, int y, Rgb color, double alpha) {
  if (!contains(x, y) || !(alpha > 0.0)) return;
  alpha = std::min(alpha, 1.0);
  const std::size_t i =
      (static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) + static_cast<std::size_t>(x)) * 3;
  const std::uint8_t channels[3] = {color.r, color.g, color.b};
  for (int c = 0; c < 3; ++c) {
    const double mixed = pixels_[i + c] + (channels[c] - pixels_[i + c]) * alpha;
    pixels_[i + c] = static_cast<std::uint8_t>(std::clamp(mixed + 0.5, 0.0, 255.0));
  }
}

namespace {

void appendBytes(void* context, void* data, int size) {
  auto* out = static_cast<std::string*>(context);
  out->append(static_cast<const char*>(data), static_cast<std::size_t>(size));
}

}  // namespace

void writePng(const std::filesystem::path& path, const Image& image) {
  std::string png;
  if (!stbi_write_png_to_func(appendBytes, &png, image.width(), image.height(), 3, image.pixels().data(),
                              image.width() * 3)) {
    failAt(path, "PNG encoding failed");
  }
  writeFileAtomically(
      path, [&](std::ostream& out) { out.write(png.data(), static_cast<std::streamsize>(png.size())); });
}

}  // namespace hba::render
