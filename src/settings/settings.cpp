#include "hba/settings/settings.hpp"

#include <algorithm>
#include <cmath>

#include "hba/core/error.hpp"
#include "hba/settings/setting_table.hpp"

namespace hba {

namespace {

ba::BaSettings withPointSigma(ba::BaSettings settings, double point_sigma) {
  settings.motion_prior.point_sigma = point_sigma;
  return settings;
}

}  // namespace

HbaSettings::HbaSettings() {
  for (const settings::Setting& setting : settings::settingTable()) {
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

}  // namespace hba
