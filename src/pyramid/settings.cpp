#include "hba/pyramid/settings.hpp"

#include <algorithm>
#include <cmath>

#include "hba/core/error.hpp"
#include "hba/pyramid/setting_table.hpp"
#include "hba/pyramid/window_plan.hpp"

namespace hba::pyramid {

namespace {

ba::BaSettings withPointSigma(ba::BaSettings settings, double point_sigma) {
  settings.motion_prior.point_sigma = point_sigma;
  return settings;
}

}  // namespace

HbaSettings::HbaSettings() {
  for (const Setting& setting : settingTable()) {
    if (!setting.shorthand()) setting.set(*this, setting.default_value);
  }
}

ba::BaSettings HbaSettings::localBa() const { return withPointSigma(local, information.point_sigma); }

ba::BaSettings HbaSettings::globalBa() const { return withPointSigma(global, information.point_sigma); }

ba::RefinementSettings HbaSettings::refinementBa() const {
  ba::RefinementSettings out = refinement;
  out.motion_prior.point_sigma = information.point_sigma;
  out.slide_prior = out.motion_prior;
  return out;
}

double keyframeVoxel(const HbaSettings& settings, int layer) {
  return settings.keyframe_voxel * std::pow(settings.keyframe_voxel_growth, std::max(0, layer - 2));
}

int paperLayerCount(std::size_t frames, int window, int stride, int threads) {
  const double n = std::max(threads, 1);
  const double N = static_cast<double>(frames);
  const double s = stride;
  const double w = window;
  const double arg = 3.0 * N * N * (s * s * s - s) * n / (w * w * w);
  int layers = arg > 1.0 ? static_cast<int>(std::floor(0.5 * std::log(arg) / std::log(s))) : 1;
  return std::clamp(layers, 1, maxLayerCount(frames, window, stride));
}

int defaultLayerCount(std::size_t frames, const HbaSettings& settings) {
  constexpr int kPaperThreads = 8;  // Table I of the paper
  return paperLayerCount(frames, settings.window, settings.stride, kPaperThreads);
}

int layerCount(std::size_t frames, const HbaSettings& settings) {
  if (settings.window <= 0 || settings.stride <= 0)
    throw Error("layerCount: the window is automatic; choose it first (window_size.hpp)");
  return settings.layers > 0
             ? std::min(settings.layers, maxLayerCount(frames, settings.window, settings.stride))
             : defaultLayerCount(frames, settings);
}

}  // namespace hba::pyramid
