#include "refine_settings.hpp"

namespace hba::settings {

refine::RefineSettings refineSettingsOf(const HbaSettings& settings) {
  refine::RefineSettings out;
  out.ba = settings.refinementBa();
  out.refine = settings.refine;
  out.groups = settings.refine_groups;
  out.scan_voxel = settings.refine_scan_voxel;
  out.max_points = settings.refine_max_points;
  out.group_min_frames = settings.group_min_frames;
  out.group_max_count = settings.group_max_count;
  out.group_voxel = settings.group_voxel;
  return out;
}

}  // namespace hba::settings
