#pragma once
// The colours every hba picture shares (private to render).
#include "hba/render/image.hpp"

namespace hba::render {

inline constexpr Rgb kBackground{14, 17, 23};
inline constexpr Rgb kPanelBackground{22, 26, 34};
inline constexpr Rgb kText{225, 228, 235};
inline constexpr Rgb kDimText{150, 156, 170};

}  // namespace hba::render
