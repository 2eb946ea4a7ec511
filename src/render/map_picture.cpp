// Layout of a picture: per panel a title, a bird's-eye view and a side strip;
// one footer with the legend, the height bar and the scale bar.
#include "hba/render/map_picture.hpp"

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "draw.hpp"
#include "hba/core/error.hpp"
#include "hba/render/colormap.hpp"
#include "palette.hpp"
#include "point_raster.hpp"

namespace hba::render {
namespace {

constexpr int kGap = 10;
constexpr int kTitleBand = 38;
constexpr int kFooter = 46;

// The colours span these quantiles of the heights in view, so that a few
// stray returns do not wash out the rest; the side view's axis spans nearly
// all heights. The captions say which is which.
constexpr double kColourLow = 0.02, kColourHigh = 0.98;
constexpr double kExtentLow = 0.002, kExtentHigh = 0.998;

// q-quantile of values (copied; q in [0, 1]).
double quantile(std::vector<double> values, double q) {
  if (values.empty()) return 0.0;
  const auto rank = static_cast<std::ptrdiff_t>(q * static_cast<double>(values.size() - 1));
  std::nth_element(values.begin(), values.begin() + rank, values.end());
  return values[static_cast<std::size_t>(rank)];
}

// The region to show: the crop, else where most map points and every
// trajectory are (extreme 0.5 % of points ignored: stray returns), plus a margin.
// Every how many points a quantile looks at: at most about 200 000 in all.
// It frames the picture, it is not a measurement: the 0.5 % quantile of
// 200 000 samples is off by about 0.02 % of the points, and sorting a
// million took longer than drawing them.
std::size_t quantileStride(const std::vector<MapPanel>& panels) {
  std::size_t points = 0;
  for (const MapPanel& panel : panels) points += panel.map.size();
  return std::max<std::size_t>(1, points / 200'000);
}

Box2 viewBox(const std::vector<MapPanel>& panels, const RenderSettings& settings) {
  if (settings.crop) return *settings.crop;
  std::vector<double> xs, ys;
  const std::size_t stride = quantileStride(panels);
  for (const MapPanel& panel : panels) {
    for (std::size_t i = 0; i < panel.map.size(); i += stride) {
      const Vec3 p = panel.map.world(i);
      xs.push_back(p.x());
      ys.push_back(p.y());
    }
  }
  Box2 box{quantile(xs, 0.005), quantile(ys, 0.005), quantile(xs, 0.995), quantile(ys, 0.995)};
  bool empty = xs.empty();
  for (const MapPanel& panel : panels) {
    for (const TrajectoryLayer& layer : panel.trajectories) {
      for (const Pose& pose : layer.poses) {
        if (empty) box = {pose.t.x(), pose.t.y(), pose.t.x(), pose.t.y()};
        empty = false;
        box = {std::min(box.xmin, pose.t.x()), std::min(box.ymin, pose.t.y()), std::max(box.xmax, pose.t.x()),
               std::max(box.ymax, pose.t.y())};
      }
    }
  }
  const double margin = 0.04 * std::max({box.xmax - box.xmin, box.ymax - box.ymin, 1.0});
  return {box.xmin - margin, box.ymin - margin, box.xmax + margin, box.ymax + margin};
}

bool inside(const Box2& box, double x, double y) {
  return x >= box.xmin && x <= box.xmax && y >= box.ymin && y <= box.ymax;
}

// Robust height range of the points in view, for the colormap and side view.
std::pair<double, double> heightRange(const std::vector<MapPanel>& panels, const Box2& box, double low_q,
                                      double high_q) {
  std::vector<double> zs;
  const std::size_t stride = quantileStride(panels);
  for (const MapPanel& panel : panels) {
    for (std::size_t i = 0; i < panel.map.size(); i += stride) {
      const Vec3 p = panel.map.world(i);
      if (inside(box, p.x(), p.y())) zs.push_back(p.z());
    }
  }
  double low = quantile(zs, low_q), high = quantile(zs, high_q);
  if (high - low < 0.5) {  // flat or empty: still a sensible range
    const double mid = 0.5 * (low + high);
    low = mid - 0.25;
    high = mid + 0.25;
  }
  return {low, high};
}

// 1, 2 or 5 times a power of ten, close to `target` metres.
double niceLength(double target) {
  const double power = std::pow(10.0, std::floor(std::log10(target)));
  for (double m : {5.0, 2.0, 1.0}) {
    if (m * power <= target) return m * power;
  }
  return power;
}

// One number format for every caption: the side view's and the colour bar's
// numbers read alike.
std::string number(double value) {
  return std::abs(value) >= 10 || value == std::round(value) ? fmt::format("{:.0f}", value)
                                                             : fmt::format("{:.1f}", value);
}

std::string metres(double value) { return number(value) + " m"; }

std::string colourQuantiles() {
  return fmt::format("{:.0f}-{:.0f} %", 100.0 * kColourLow, 100.0 * kColourHigh);
}

struct Rect {
  int left, top, width, height;
  Clip clip() const { return {left, top, left + width, top + height}; }
};

// Pixels covered by one voxel at `pixels_per_meter`, a little more than the
// voxel so that neighbouring (centroid-jittered) points leave no seams.
int footprint(double voxel, double pixels_per_meter) {
  const double pixels = voxel * pixels_per_meter;
  return pixels < 1.5 ? 1 : static_cast<int>(std::ceil(1.2 * pixels));
}

void drawScaleBar(Image& image, const Rect& area, double pixels_per_meter) {
  const double length = niceLength(std::min(140.0, 0.3 * area.width) / pixels_per_meter);
  const int bar = static_cast<int>(std::round(length * pixels_per_meter));
  const std::string label = metres(length);
  const int right = area.left + area.width - 14, y = area.top + area.height - 26;
  fillRect(image, right - bar - textWidth(label, 2) - 20, y - 6, right + 8, y + 20, kPanelBackground, 0.75);
  fillRect(image, right - bar, y + 6, right, y + 9, kText);
  fillRect(image, right - bar, y + 1, right - bar + 2, y + 14, kText);
  fillRect(image, right - 2, y + 1, right, y + 14, kText);
  drawText(image, right - bar - textWidth(label, 2) - 10, y + 1, label, kText, 2);
}

void drawTopView(Image& image, const MapPanel& panel, const Box2& box, const TopViewTransform& view,
                 const Rect& area, std::pair<double, double> heights, double voxel) {
  const int size = footprint(voxel, view.pixels_per_meter);
  PointRaster raster(area.width, area.height, size, size);
  const bool by_value = !panel.values.empty() && panel.values.size() == panel.map.size();
  for (std::size_t i = 0; i < panel.map.size(); ++i) {
    const Vec3 p = panel.map.world(i);
    if (!inside(box, p.x(), p.y()) || (by_value && panel.values[i] < 0.0f)) continue;
    const auto pixel = view.toPixel(p.x(), p.y());
    raster.add(pixel.x() - area.left, pixel.y() - area.top, by_value ? panel.values[i] : p.z());
  }
  raster.paint(image, area.left, area.top, heights.first, heights.second);
  for (const TrajectoryLayer& layer : panel.trajectories) {
    std::vector<Pixel> line;
    for (const Pose& pose : layer.poses) line.push_back(view.toPixel(pose.t.x(), pose.t.y()));
    drawPolyline(image, line, layer.color, 2.2, area.clip());
    const bool start_visible =
        !line.empty() && line.front().x() >= area.left + 5 && line.front().y() >= area.top + 5 &&
        line.front().x() < area.left + area.width - 5 && line.front().y() < area.top + area.height - 5;
    if (start_visible) drawDisc(image, line.front(), 5.0, layer.color);  // the start
  }
}

// x (same columns as the top view) against z, z stretched to fill the strip.
void drawSideView(Image& image, const MapPanel& panel, const Box2& box, const TopViewTransform& view,
                  const Rect& area, std::pair<double, double> heights, std::pair<double, double> z_range,
                  double voxel) {
  const double z_scale = (area.height - 8) / (z_range.second - z_range.first);
  auto toPixel = [&](double x, double z) {
    return Pixel(view.toPixel(x, 0).x(), area.top + 4 + (z_range.second - z) * z_scale);
  };
  PointRaster raster(area.width, area.height, footprint(voxel, view.pixels_per_meter),
                     footprint(voxel, z_scale));
  for (std::size_t i = 0; i < panel.map.size(); ++i) {
    const Vec3 p = panel.map.world(i);
    if (!inside(box, p.x(), p.y())) continue;
    const Pixel pixel = toPixel(p.x(), p.z());
    raster.add(pixel.x() - area.left, pixel.y() - area.top, p.z());
  }
  raster.paint(image, area.left, area.top, heights.first, heights.second);
  for (const TrajectoryLayer& layer : panel.trajectories) {
    std::vector<Pixel> line;
    for (const Pose& pose : layer.poses) {
      if (inside(box, pose.t.x(), pose.t.y())) line.push_back(toPixel(pose.t.x(), pose.t.z()));
    }
    drawPolyline(image, line, layer.color, 1.6, area.clip());
  }
}

// The side view's caption: the heights its axis spans and, when colour is
// by height, the (narrower) range the colours span, as the bar says.
std::string sideCaption(const TopViewTransform& view, const Rect& area, std::pair<double, double> z_range,
                        std::pair<double, double> heights, bool colour_by_height) {
  const double z_scale = (area.height - 8) / (z_range.second - z_range.first);
  const double exaggeration = z_scale / view.pixels_per_meter;
  std::string caption = fmt::format("side view: x vs z (z x{:.1f}), z {}..{} m", exaggeration,
                                    number(z_range.first), number(z_range.second));
  if (colour_by_height) {
    caption += fmt::format("; colour {}..{} m ({})", number(heights.first), number(heights.second),
                           colourQuantiles());
  }
  return caption;
}

void drawFooter(Image& image, const std::vector<MapPanel>& panels, const std::string& low,
                const std::string& high) {
  const int y = image.height() - kFooter + 12;
  int x = kGap + 6;
  std::vector<std::string> seen;
  for (const MapPanel& panel : panels) {
    for (const TrajectoryLayer& layer : panel.trajectories) {
      if (std::find(seen.begin(), seen.end(), layer.label) != seen.end()) continue;
      seen.push_back(layer.label);
      drawPolyline(image, {Pixel(x, y + 8), Pixel(x + 30, y + 8)}, layer.color, 3.0);
      drawText(image, x + 40, y + 2, layer.label, kText, 2);
      x += 40 + textWidth(layer.label, 2) + 34;
    }
  }
  // Colour bar.
  drawText(image, x, y + 2, low, kDimText, 2);
  x += textWidth(low, 2) + 8;
  for (int i = 0; i < 200; ++i)
    fillRect(image, x + i, y + 1, x + i + 1, y + 15,
             turbo(kColormapLow + (kColormapHigh - kColormapLow) * i / 199.0));
  x += 208;
  drawText(image, x, y + 2, high, kDimText, 2);
}

}  // namespace

Box2 parseBox(const std::string& text) {
  std::stringstream in(text);
  double v[4];
  char comma = 0;
  const bool ok = static_cast<bool>(in >> v[0] >> comma) && comma == ',' &&
                  static_cast<bool>(in >> v[1] >> comma) && comma == ',' &&
                  static_cast<bool>(in >> v[2] >> comma) && comma == ',' && static_cast<bool>(in >> v[3]) &&
                  (in >> std::ws).eof();
  if (!ok) throw Error("crop '" + text + "': expected xmin,ymin,xmax,ymax in metres");
  if (!(v[2] > v[0] && v[3] > v[1]))
    throw Error("crop '" + text + "' is empty (need xmin < xmax, ymin < ymax)");
  return {v[0], v[1], v[2], v[3]};
}

Picture renderPanels(const std::vector<MapPanel>& panels, const RenderSettings& settings) {
  if (panels.empty()) throw Error("nothing to render");
  const int n = static_cast<int>(panels.size());
  Picture picture{Image(settings.width, settings.height, kBackground), {}, {}, {}, {}};
  Image& image = picture.image;
  const int panel_width = (settings.width - (n + 1) * kGap) / n;
  const int body = settings.height - kTitleBand - kFooter;
  const int side_height = settings.side_view ? std::max(60, body / 4) : 0;
  const int top_height = body - (settings.side_view ? side_height + kGap : 0);
  if (panel_width < 100 || top_height < 100) throw Error("picture too small for its panels");

  const Box2 box = viewBox(panels, settings);
  const auto heights = settings.value_scale
                           ? std::make_pair(settings.value_scale->low, settings.value_scale->high)
                           : heightRange(panels, box, kColourLow, kColourHigh);
  const auto z_range = heightRange(panels, box, kExtentLow, kExtentHigh);
  const double scale = std::min(panel_width / (box.xmax - box.xmin), top_height / (box.ymax - box.ymin));

  std::vector<Rect> top_areas, side_areas;
  for (int k = 0; k < n; ++k) {
    const int left = kGap + k * (panel_width + kGap);
    top_areas.push_back({left, kTitleBand, panel_width, top_height});
    side_areas.push_back({left, kTitleBand + top_height + kGap, panel_width, side_height});
    fillRect(image, left, kTitleBand, left + panel_width, kTitleBand + top_height, kPanelBackground);
    drawText(image, left + 4, 8, panels[k].title, kText, 3);
    if (settings.side_view) {
      fillRect(image, left, side_areas[k].top, left + panel_width, side_areas[k].top + side_height,
               kPanelBackground);
    }
    TopViewTransform view;
    view.pixels_per_meter = scale;
    view.left = left;
    view.top = kTitleBand;
    // Centre the box in the area.
    view.origin_x = 0.5 * (box.xmin + box.xmax) - 0.5 * panel_width / scale;
    view.origin_y = 0.5 * (box.ymin + box.ymax) + 0.5 * top_height / scale;
    picture.top_views.push_back(view);
  }
  // The panels' views at once: each draws only inside its own areas (its
  // trajectories' start disc a pixel beyond, into the gap). Text is not
  // clipped, so it comes after.
  tbb::parallel_for(0, n, [&](int k) {
    drawTopView(image, panels[k], box, picture.top_views[k], top_areas[k], heights, settings.voxel);
    if (settings.side_view) {
      drawSideView(image, panels[k], box, picture.top_views[k], side_areas[k], heights, z_range,
                   settings.voxel);
    }
  });
  for (int k = 0; k < n; ++k) {
    drawScaleBar(image, top_areas[k], scale);
    if (!settings.side_view) continue;
    // Unclipped text: drawn after the panels' views.
    picture.side_caption =
        sideCaption(picture.top_views[k], side_areas[k], z_range, heights, !settings.value_scale);
    drawText(image, side_areas[k].left + 8, side_areas[k].top + 6, picture.side_caption, kDimText, 2);
  }
  const std::optional<RenderSettings::ValueScale>& values = settings.value_scale;
  picture.bar_low = values ? values->low_label : "z " + metres(heights.first);
  picture.bar_high = values ? values->high_label : metres(heights.second) + " (" + colourQuantiles() + ")";
  drawFooter(image, panels, picture.bar_low, picture.bar_high);
  return picture;
}

}  // namespace hba::render
