#include <cmath>
#include <string>

#include "hba/closure/loop_check.hpp"
#include "hba/core/error.hpp"

namespace hba::closure {
namespace {

void require(bool ok, const char* name, const char* what) {
  if (!ok) throw Error(std::string("loop check setting ") + name + ": must be " + what);
}

bool positive(double v) { return v > 0.0 && std::isfinite(v); }
bool nonNegative(double v) { return v >= 0.0 && std::isfinite(v); }
bool share(double v) { return v >= 0.0 && v <= 1.0; }

}  // namespace

void validate(const LoopCheckSettings& s) {
  require(nonNegative(s.neighbourhood_voxel), "neighbourhood_voxel", "0 (off) or positive");
  require(nonNegative(s.search_radius_m), "search_radius_m", "0 (no search) or positive");
  require(nonNegative(s.search_yaw_deg) && s.search_yaw_deg <= 180.0, "search_yaw_deg", "in [0, 180]");
  require(positive(s.search_cell_m), "search_cell_m", "positive");
  require(positive(s.structure_height_m), "structure_height_m", "positive");
  require(share(s.min_search_score), "min_search_score", "in [0, 1]");
  require(share(s.max_second_peak_ratio), "max_second_peak_ratio", "in [0, 1]");
  require(nonNegative(s.ambiguous_distance_m), "ambiguous_distance_m", "0 or positive");
  require(nonNegative(s.ambiguous_yaw_deg), "ambiguous_yaw_deg", "0 or positive");
  require(positive(s.voxel_size), "voxel_size", "positive");
  require(positive(s.final_voxel_size) && s.final_voxel_size <= s.voxel_size, "final_voxel_size",
          "positive and at most voxel_size");
  require(share(s.min_overlap), "min_overlap", "in [0, 1]");
  require(positive(s.max_rms_m), "max_rms_m", "positive");
  require(s.max_sigma_ratio >= 1.0, "max_sigma_ratio", "at least 1");
  require(positive(s.max_sigma_m), "max_sigma_m", "positive");
  require(positive(s.max_sigma_deg), "max_sigma_deg", "positive");
}

}  // namespace hba::closure
