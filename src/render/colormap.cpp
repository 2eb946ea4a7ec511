#include "hba/render/colormap.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace hba::render {

Rgb mix(Rgb a, Rgb b, double t) {
  auto channel = [t](std::uint8_t x, std::uint8_t y) {
    return static_cast<std::uint8_t>(std::clamp(x + (y - x) * t + 0.5, 0.0, 255.0));
  };
  return {channel(a.r, b.r), channel(a.g, b.g), channel(a.b, b.b)};
}

Rgb turbo(double t) {
  // Anchors sampled by eye along Google's Turbo, evenly spaced in t.
  static const std::array<Rgb, 15> kAnchors{{{48, 18, 59},
                                             {65, 69, 171},
                                             {70, 117, 237},
                                             {57, 162, 252},
                                             {27, 207, 212},
                                             {36, 236, 166},
                                             {97, 252, 108},
                                             {164, 252, 59},
                                             {209, 232, 52},
                                             {243, 198, 58},
                                             {254, 155, 45},
                                             {243, 99, 21},
                                             {217, 56, 6},
                                             {177, 25, 1},
                                             {122, 4, 3}}};
  if (!(t > 0.0)) return kAnchors.front();  // also NaN
  if (t >= 1.0) return kAnchors.back();
  const double position = t * static_cast<double>(kAnchors.size() - 1);
  const auto index = static_cast<std::size_t>(position);
  return mix(kAnchors[index], kAnchors[index + 1], position - std::floor(position));
}

}  // namespace hba::render
