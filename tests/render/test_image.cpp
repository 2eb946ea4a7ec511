// The raster and its PNG: every pixel must come back from an independent
// decoder (stb_image), and the copies and blends must touch only what they say.
#include <gtest/gtest.h>
#include <stb_image.h>

#include <fstream>
#include <memory>
#include <random>

#include "hba/core/error.hpp"
#include "hba/render/image.hpp"
#include "test_support.hpp"

namespace hba::render {
namespace {

// Noise over smooth gradients: the filters and the compressor both get work.
Image testImage(int width, int height, unsigned seed) {
  Image image(width, height);
  std::mt19937 random(seed);
  std::uniform_int_distribution<int> byte(0, 255);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const bool noisy = (x / 7 + y / 5) % 3 == 0;
      image.set(x, y,
                noisy ? Rgb{static_cast<std::uint8_t>(byte(random)), static_cast<std::uint8_t>(byte(random)),
                            static_cast<std::uint8_t>(byte(random))}
                      : Rgb{static_cast<std::uint8_t>(x % 256), static_cast<std::uint8_t>(y % 256), 90});
    }
  }
  return image;
}

void expectSamePixels(const Image& expected, const unsigned char* decoded) {
  for (int y = 0; y < expected.height(); ++y) {
    for (int x = 0; x < expected.width(); ++x) {
      const std::size_t i = (static_cast<std::size_t>(y) * expected.width() + x) * 3;
      const Rgb e = expected.at(x, y);
      ASSERT_EQ(decoded[i], e.r) << x << "," << y;
      ASSERT_EQ(decoded[i + 1], e.g) << x << "," << y;
      ASSERT_EQ(decoded[i + 2], e.b) << x << "," << y;
    }
  }
}

TEST(Png, EveryPixelComesBackFromAnotherDecoder) {
  test::TempDir tmp;
  for (const auto& [w, h] : {std::pair{1, 1}, std::pair{3, 200}, std::pair{517, 301}}) {
    const Image image = testImage(w, h, static_cast<unsigned>(w * 1000 + h));
    writePng(tmp / "t.png", image);
    int dw = 0, dh = 0, channels = 0;
    std::unique_ptr<unsigned char, void (*)(void*)> pixels(
        stbi_load((tmp / "t.png").c_str(), &dw, &dh, &channels, 3), stbi_image_free);
    ASSERT_TRUE(pixels) << stbi_failure_reason();
    EXPECT_EQ(channels, 3);
    ASSERT_EQ(dw, w);
    ASSERT_EQ(dh, h);
    expectSamePixels(image, pixels.get());
  }
}

// Rows of several images, encoded in place one above the other, decode as
// the stacked picture; images of different widths are refused.
TEST(Png, StackedImagesComeBackAsOnePicture) {
  test::TempDir tmp;
  const Image upper = testImage(131, 40, 3), lower = testImage(131, 17, 4);
  writePng(tmp / "s.png", std::vector<const Image*>{&upper, &lower});
  int dw = 0, dh = 0, channels = 0;
  std::unique_ptr<unsigned char, void (*)(void*)> pixels(
      stbi_load((tmp / "s.png").c_str(), &dw, &dh, &channels, 3), stbi_image_free);
  ASSERT_TRUE(pixels) << stbi_failure_reason();
  ASSERT_EQ(dw, 131);
  ASSERT_EQ(dh, 57);
  expectSamePixels(upper, pixels.get());
  expectSamePixels(lower, pixels.get() + static_cast<std::size_t>(131) * 40 * 3);
  // One image alone is the same file as its stack of one.
  EXPECT_EQ(encodePng(upper), encodePng(std::vector<const Image*>{&upper}));
  const Image narrow = testImage(130, 5, 5);
  EXPECT_THROW(encodePng(std::vector<const Image*>{&upper, &narrow}), Error);
  EXPECT_THROW(encodePng(std::vector<const Image*>{}), Error);
}

TEST(Png, AnUnwritablePathIsNamedAndNothingIsLeft) {
  test::TempDir tmp;
  const auto path = tmp / "missing-folder" / "t.png";
  try {
    writePng(path, testImage(8, 8, 1));
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("missing-folder"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(std::filesystem::exists(path));
}

TEST(Image, PasteCopiesTheSourceClippedToTheImage) {
  const Image source = testImage(20, 10, 7);
  Image target(30, 15, Rgb{1, 2, 3});
  target.paste(source, 25, -4);  // sticks out right and above
  for (int y = 0; y < 15; ++y) {
    for (int x = 0; x < 30; ++x) {
      const bool covered = x >= 25 && y < 6;
      const Rgb want = covered ? source.at(x - 25, y + 4) : Rgb{1, 2, 3};
      const Rgb got = target.at(x, y);
      ASSERT_TRUE(got.r == want.r && got.g == want.g && got.b == want.b) << x << "," << y;
    }
  }
  Image whole(20, 10);
  whole.paste(source, 0, 0);
  EXPECT_EQ(whole.pixels(), source.pixels());
  Image untouched(5, 5, Rgb{9, 9, 9});
  untouched.paste(source, -30, 0);  // entirely outside
  EXPECT_EQ(untouched.pixels(), Image(5, 5, Rgb{9, 9, 9}).pixels());
}

TEST(Image, BlendMixesByOpacityAndOpaqueIsASet) {
  Image image(4, 1, Rgb{100, 0, 200});
  image.blend(0, 0, Rgb{200, 100, 0}, 0.25);
  EXPECT_EQ(image.at(0, 0).r, 125);
  EXPECT_EQ(image.at(0, 0).g, 25);
  EXPECT_EQ(image.at(0, 0).b, 150);
  image.blend(1, 0, Rgb{7, 8, 9}, 1.0);
  image.blend(2, 0, Rgb{7, 8, 9}, 3.0);  // above 1: opaque
  image.blend(3, 0, Rgb{7, 8, 9}, 0.0);  // nothing
  EXPECT_EQ(image.at(1, 0).g, 8);
  EXPECT_EQ(image.at(2, 0).b, 9);
  EXPECT_EQ(image.at(3, 0).r, 100);
  image.blend(-1, 0, Rgb{}, 1.0);  // outside: ignored
  image.set(4, 0, Rgb{});
  EXPECT_EQ(image.at(3, 0).b, 200);
}

}  // namespace
}  // namespace hba::render
