#pragma once
// A trajectory's error over time (`hba eval --plot`): ATE translation (m)
// in the upper panel, ATE rotation (degrees) in the lower one, against the
// estimate's time (or pose index), with axes, ticks and the RMSE.
#include <filesystem>
#include <string>
#include <vector>

#include "hba/render/image.hpp"

namespace hba::render {

struct ErrorSeries {
  std::vector<double> x;  // time (s) or index, ascending
  std::vector<double> translation_m;
  std::vector<double> rotation_deg;
  std::string x_label = "time (s)";
  std::string title;  // e.g. the estimate's file name
};

Image renderErrorPlot(const ErrorSeries& series, int width = 1200, int height = 720);
// Writes the PNG atomically. Throws hba::Error (no points, unwritable file).
void writeErrorPlot(const ErrorSeries& series, const std::filesystem::path& png);

}  // namespace hba::render
