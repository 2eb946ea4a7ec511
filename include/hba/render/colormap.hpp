#pragma once
// Perceptual colormap for heights.
#include "hba/render/image.hpp"

namespace hba::render {

// Turbo-like rainbow (dark blue -> cyan -> green -> yellow -> red) for t in
// [0, 1], clamped outside. Smooth and easy to read on a dark background.
Rgb turbo(double t);

// a + (b - a) * t per channel.
Rgb mix(Rgb a, Rgb b, double t);

}  // namespace hba::render
