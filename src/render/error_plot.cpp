#include "hba/render/error_plot.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "draw.hpp"
#include "hba/core/error.hpp"
#include "palette.hpp"

namespace hba::render {
namespace {

constexpr Rgb kGrid{48, 54, 66};
constexpr Rgb kTranslation{90, 200, 250};
constexpr Rgb kRotation{250, 170, 70};

// 1, 2 or 5 times a power of ten: about `count` steps across `span`.
double tickStep(double span, int count) {
  const double raw = span / count;
  const double power = std::pow(10.0, std::floor(std::log10(raw)));
  for (double m : {1.0, 2.0, 5.0, 10.0}) {
    if (m * power >= raw) return m * power;
  }
  return 10.0 * power;
}

std::string tickLabel(double value, double step) {
  const int decimals = step >= 1.0 ? 0 : static_cast<int>(std::ceil(-std::log10(step)));
  return fmt::format("{:.{}f}", value, decimals);
}

struct Area {
  int left, top, width, height;
};

void drawPanel(Image& image, const Area& a, const std::vector<double>& x, const std::vector<double>& y,
               double x_min, double x_max, const std::string& y_label, Rgb color) {
  fillRect(image, a.left, a.top, a.left + a.width, a.top + a.height, kPanelBackground);
  const double y_max = std::max(1e-12, *std::max_element(y.begin(), y.end()) * 1.08);
  const auto toPixel = [&](double px, double py) {
    return Pixel(a.left + (px - x_min) / (x_max - x_min) * a.width, a.top + a.height - py / y_max * a.height);
  };
  const double y_step = tickStep(y_max, 4);
  for (double v = 0.0; v <= y_max; v += y_step) {
    const int row = static_cast<int>(std::round(toPixel(x_min, v).y()));
    fillRect(image, a.left, row, a.left + a.width, row + 1, kGrid);
    const std::string label = tickLabel(v, y_step);
    drawText(image, a.left - textWidth(label) - 8, row - textHeight() / 2, label, kDimText);
  }
  const double x_step = tickStep(x_max - x_min, 8);
  for (double v = std::ceil(x_min / x_step) * x_step; v <= x_max; v += x_step) {
    const int column = static_cast<int>(std::round(toPixel(v, 0.0).x()));
    fillRect(image, column, a.top, column + 1, a.top + a.height, kGrid);
    const std::string label = tickLabel(v, x_step);
    drawText(image, column - textWidth(label) / 2 + 1, a.top + a.height + 6, label + " ", kDimText);
  }
  std::vector<Pixel> line;
  line.reserve(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) line.push_back(toPixel(x[i], y[i]));
  drawPolyline(image, line, color, 1.6, {a.left, a.top, a.left + a.width, a.top + a.height});
  drawText(image, a.left + 10, a.top + 8, y_label, color);
}

double rms(const std::vector<double>& values) {
  double sum = 0.0;
  for (double v : values) sum += v * v;
  return std::sqrt(sum / static_cast<double>(values.size()));
}

}  // namespace

Image renderErrorPlot(const ErrorSeries& s, int width, int height) {
  if (s.x.empty() || s.x.size() != s.translation_m.size() || s.x.size() != s.rotation_deg.size()) {
    throw Error("error plot: no errors to draw");
  }
  Image image(width, height, kBackground);
  const double x_min = s.x.front();
  const double x_max = s.x.size() > 1 && s.x.back() > s.x.front() ? s.x.back() : s.x.front() + 1.0;
  const int left = 110, right = 30, top = 50, gap = 60, bottom = 60;
  const int panel_height = (height - top - gap - bottom) / 2;
  drawText(image, left, 14,
           fmt::format("{}  ATE over {}: rmse {:.4f} m, {:.4f} deg", s.title, s.x_label, rms(s.translation_m),
                       rms(s.rotation_deg)),
           kText);
  drawPanel(image, {left, top, width - left - right, panel_height}, s.x, s.translation_m, x_min, x_max,
            "translation error (m)", kTranslation);
  drawPanel(image, {left, top + panel_height + gap, width - left - right, panel_height}, s.x, s.rotation_deg,
            x_min, x_max, "rotation error (deg)", kRotation);
  drawText(image, left + (width - left - right) / 2 - textWidth(s.x_label) / 2, height - 24, s.x_label,
           kText);
  return image;
}

void writeErrorPlot(const ErrorSeries& series, const std::filesystem::path& png) {
  writePng(png, renderErrorPlot(series));
}

}  // namespace hba::render
